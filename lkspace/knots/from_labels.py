"""Identifying one design from its labels: the PD code assembled without geometry, named by key first.

The default path of :func:`lkspace.knots.recognition.identify` (``method: "combinatorial"``):

1. the design's diagram comes from the scaffold's
   :class:`~lkspace.knots.labels_diagram.DiagramTemplate` (the pieces of its twists
   projected once; :func:`~lkspace.knots.assembly.assemble_one` walks the strands), as
   ``enumerate --identify`` does;
2. its key (:mod:`lkspace.knots.keyed`: components, sorted linking numbers, Jones
   polynomial) is computed in plain Python, the Jones polynomial in compiled code only
   when the diagram is too wide for Python to be quick (:data:`PY_FRONTIER`), and by
   regina on the simplified link when it is too wide for the compiled state sum too;
3. the key is looked up in the names judged by earlier runs
   (:func:`~lkspace.knots.key_names.disk_cache`, reading only that key's lines) under the
   trust rule of :func:`~lkspace.knots.key_names.share_names`.  Only a new or untrusted
   key loads the knot libraries and names the diagram in full
   (:func:`~lkspace.knots.naming.name_in_time`); a trusted new key is kept on disk.

A design named from the cache has the invariants the cache keeps (name, mirror, split
pieces, crossings of the simplified diagram, Jones polynomial, table); one named in full
has every field the geometric path gives but ``min_distance``.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..model.scaffold import Scaffold
from ..runtime.progress import Step
from ..runtime.workers import interruptible
from .assembly import assemble_one, work_array
from .bracket import read_ends, smoothing_order
from .budget import INLINE_CROSSINGS, MAX_CROSSINGS, TimeLimitReached, run_in_time
from .identification import Identification, Json, NameFields, Naming
from .jones import jones_buffer_size, jones_into, jones_kernel
from .key_names import KeyCache, disk_cache, share_names
from .keyed import DesignKeys
from .labels_diagram import template
from .naming import name_in_time, named_as_split, presimplified, status_of
from .tables import check_knot_modules

PY_FRONTIER = 12
"""Widest frontier of the state sum computed in plain Python; wider ones run compiled (numba).

Measured on cube to icosahedron designs (-2..2): plain Python takes at most 0.1 s up to
a width of 12, up to 0.35 s at 14 and seconds at 16 (the compiled limit), while
importing numba and loading the compiled kernel takes about half a second.
"""


@dataclass(frozen=True, eq=False)
class OneDesign(DesignKeys):
    """The :class:`~lkspace.knots.keyed.DesignKeys` of one design, holding its diagram (no second assembly)."""

    pd: np.ndarray
    signs: np.ndarray

    def diagram(self, d: int) -> tuple[list[list[int]], int, np.ndarray]:
        """Return the design's PD code (1-based), components and crossing signs (``d`` is 0)."""
        return self.pd.tolist(), int(self.components[d]), self.signs


def design_keys_of(scaffold: Scaffold, labels: np.ndarray, seed: int = 0, time_limit: float | None = None) -> OneDesign:
    """Return the diagram and key of one design (``labels (n_edges,) int``), computed as :func:`~lkspace.knots.keyed.design_keys` does.

    Raises :class:`~lkspace.errors.DiagramError` when no generic template direction was found.
    A diagram too wide for the state sum is keyed by regina within ``time_limit`` seconds of
    CPU (``None``: no limit), else left without a key.
    """
    tmpl = template(scaffold, labels, seed)
    vidx = tmpl.value_index(labels)
    arrays = tmpl.arrays()
    pd, signs, comps, n_comp, n_free = assemble_one.py_func(arrays, vidx, work_array(tmpl))
    m, n_comp = len(pd), int(n_comp)
    lk = np.zeros((n_comp, n_comp), np.int64)  # as keyed._linking_into: each mixed crossing counts half
    mixed = comps[:, 0] != comps[:, 1]
    np.add.at(lk, (comps[mixed, 0], comps[mixed, 1]), signs[mixed])
    np.add.at(lk, (comps[mixed, 1], comps[mixed, 0]), signs[mixed])
    lk_flat = (lk // 2).reshape(-1)
    keys = np.zeros((1, 2), np.uint64)
    keyed = m <= MAX_CROSSINGS and _jones_key(pd, signs, int(n_free), lk_flat, n_comp, keys)
    if not keyed and 0 < m <= MAX_CROSSINGS:
        keyed = _regina_key(pd, lk_flat, n_comp, keys, time_limit)
    return OneDesign(
        template=tmpl,
        vidx=vidx[None],
        keys=keys,
        crossings=np.array([m], np.int64),
        components=np.array([n_comp], np.int64),
        keyed=np.array([keyed]),
        link_offsets=np.array([0, n_comp * n_comp], np.int64),
        link_values=lk_flat,
        free=np.array([n_free], np.int64),
        jones_at=np.zeros(1, np.int64),
        pd=pd,
        signs=signs,
    )


def _jones_key(pd: np.ndarray, signs: np.ndarray, n_free: int, lk: np.ndarray, n_comp: int, keys: np.ndarray) -> bool:
    """Write the design's two key hashes into ``keys[0]``; ``False`` when the diagram is too wide for the state sum."""
    poly = np.zeros(jones_buffer_size(len(pd), n_free), np.int64)
    wide = False
    if len(pd):
        ends = np.full((2 * len(pd), 2), -1, np.int64)
        wide = read_ends(pd, ends) and smoothing_order(pd, ends, np.zeros(len(pd), np.int64)) > PY_FRONTIER
    lowest, length = (jones_kernel if wide else jones_into)(pd, signs, n_free, poly)
    if length < 0:
        return False
    keys[0] = key_hashes(lk, n_comp, int(lowest), poly[:length].tolist())
    return True


def _regina_key(pd: np.ndarray, lk: np.ndarray, n_comp: int, keys: np.ndarray, time_limit: float | None) -> bool:
    """Write the key of a diagram too wide for the state sum, its Jones polynomial regina's (of the link simplified).

    The key holds invariants only, so any diagram of the link gives it: the one compiled
    code would give if it could (``enumerate`` names such designs one by one instead).
    regina computes it in one C++ call of seconds: within ``time_limit`` seconds of CPU
    (:func:`~lkspace.knots.budget.run_in_time`; past it, no key), and so that Ctrl-C goes
    through at once (:func:`_regina_jones`).
    """
    try:
        jones = run_in_time(lambda _stage: _regina_jones(pd), time_limit)
    except TimeLimitReached:
        return False
    if jones is None:
        return False
    low, coefficients = jones
    keys[0] = key_hashes(lk, n_comp, low, coefficients)
    return True


def _regina_jones(pd: np.ndarray) -> tuple[int, list[int]] | None:
    """Return the lowest exponent and the coefficients of regina's Jones polynomial of ``pd`` (``None``: zero).

    The C++ call releases the GIL: it runs in :func:`~lkspace.runtime.workers.interruptible`'s thread.
    """
    from .tables import regina_module

    link = regina_module().Link.fromPD(pd.tolist())

    def simplified_jones() -> Any:
        link.simplify()
        return link.jones()

    jones = interruptible(simplified_jones)
    if jones.isZero():
        return None
    low, high = int(jones.minExp()), int(jones.maxExp())
    return low, [int(str(jones[e])) for e in range(low, high + 1)]


_MASK = (1 << 64) - 1


def _mix(h: int, v: int) -> int:
    """:func:`lkspace.knots.keyed._mix` on Python ints (``v`` read as two's complement, as compiled)."""
    x = ((h ^ (v & _MASK)) * 0x9E3779B97F4A7C15) & _MASK
    x = ((x ^ (x >> 30)) * 0xBF58476D1CE4E5B9) & _MASK
    x = ((x ^ (x >> 27)) * 0x94D049BB133111EB) & _MASK
    return x ^ (x >> 31)


def key_hashes(lk: np.ndarray, n_comp: int, lowest: int, poly: list[int]) -> tuple[int, int]:
    """Return the two hashes of :func:`lkspace.knots.keyed._hashes`, bit for bit, in plain Python (no numba)."""
    pairs = sorted(int(lk[i * n_comp + j]) for i in range(n_comp) for j in range(i + 1, n_comp))
    h1, h2 = _mix(0x243F6A8885A308D3, n_comp), _mix(0x13198A2E03707344, n_comp + 7)
    for v in pairs:
        h1, h2 = _mix(h1, v), _mix(h2, v * 31 + 5)
    h1, h2 = _mix(h1, lowest), _mix(h2, lowest * 17 + 3)
    for i, c in enumerate(poly):
        h1, h2 = _mix(h1, c), _mix(h2, c * 131 + i)
    return h1, h2


def identify_labels(
    scaffold: Scaffold, labels: np.ndarray, seed: int, time_limit: float | None, step: Step | None
) -> Identification:
    """Identify the design ``labels`` of a finite scaffold without nulls from its labels (module docstring).

    ``time_limit`` bounds the naming in full, when the key is not known yet (``None``: no limit).
    """
    t0 = time.monotonic()
    check_knot_modules()  # the extra is needed whether or not this design's key is known
    found = design_keys_of(scaffold, labels, seed, time_limit)
    keyed = bool(found.keyed[0])
    cache = disk_cache((int(found.keys[0, 0]), int(found.keys[0, 1]))) if keyed else KeyCache()
    full: dict[int, tuple[Naming, str]] = {}

    def name_designs(indices: list[int]) -> list[NameFields]:
        out = []
        for d in indices:
            if d not in full:  # a key judged at both levels is named once
                full[d] = _name_in_full(found, d, time_limit, t0, step)
            named, status = full[d]
            refused = status.startswith(("unknown: time limit", "unknown: diagram too large"))
            out.append(NameFields.refused(status) if refused else NameFields.of(named, status))
        return out

    def shared(stage: Callable[[str], None]) -> tuple[NameFields | None, dict[int, tuple[Naming, str]]]:
        stage("naming by key")
        return share_names(found, cache, name_designs)[0], full

    # sharing a key may simplify the diagram and take its HOMFLY-PT polynomial (regina; minutes past
    # 30 crossings): a wider diagram is named in a child stopped at the time limit, as naming in full is
    left = None if not time_limit else max(time_limit - (time.monotonic() - t0), 1e-3)
    try:
        fields, full = run_in_time(shared, left if len(found.pd) > INLINE_CROSSINGS else None, step)
    except TimeLimitReached as exc:
        fields, full = NameFields.refused(f"unknown: time limit {time_limit:g} s reached (during {exc.stage})"), {}
    assert fields is not None
    named, status = full[0] if 0 in full else (naming_of(fields), fields.status)
    named = named_as_split(named)
    pd = found.pd.tolist()
    extra: dict[str, Json] = {"projected_crossings": len(pd), "method": "combinatorial", "pd_code": pd}
    return Identification.of(named, status, int(found.components[0]), found.linking_matrix(0), extra)


def _name_in_full(
    found: OneDesign, d: int, time_limit: float | None, t0: float, step: Step | None
) -> tuple[Naming, str]:
    """Name design ``d``'s diagram with the knot libraries, within ``time_limit`` seconds from ``t0``: naming, status."""
    pd, n_comp, _ = found.diagram(d)
    if len(pd) > MAX_CROSSINGS:
        return Naming.of(name=None), f"unknown: diagram too large: {len(pd):,} crossings > {MAX_CROSSINGS:,}"
    left = None if not time_limit else max(time_limit - (time.monotonic() - t0), 1e-3)
    try:
        named = name_in_time(presimplified(pd), n_comp, left, step)
    except TimeLimitReached as exc:
        return Naming.of(name=None), f"unknown: time limit {time_limit:g} s reached (during {exc.stage})"
    return named, status_of(named)


def naming_of(fields: NameFields) -> Naming:
    """Return the :class:`Naming` a design takes from a key's shared fields (the fields set, in order)."""
    values = {  # in the order a naming in full finds them (name_pd)
        "name": fields.knot_name,
        "mirror": fields.mirror,
        "candidates": fields.candidates,
        "crossings": fields.crossings,
        "jones": fields.jones,
        "table": fields.table,
        "chiral_name": fields.chiral_name,
        "split": fields.split,
        "pieces": fields.pieces,
    }
    keep = {"name", "mirror", "split", "crossings"}
    return Naming.of(**{k: v for k, v in values.items() if v is not None or k in keep})
