"""Identification keyed by invariants: SnapPy and the tables asked once per distinct key.

Per design, compiled code (:func:`design_keys`) assembles the PD code from the labels
(:mod:`lkspace.knots.labels_diagram`) and computes its **key**: the number of components,
the sorted linking numbers of its pairs of components, and the Jones polynomial
(:mod:`lkspace.knots.jones`, exact, free components included), hashed to 128 bits.  The
first design of each key is named in full (:func:`lkspace.knots.naming.name_pd` on its
own PD code: simplification, table lookup, SnapPy's check of the volume); the others
share its name.

A key is trusted only where it separates what the tables hold.  A design is named on its
own (no sharing) when

* the tables hold more than one type with that Jones polynomial and number of
  components (KnotInfo's 5_1 and 10_132, say: HOMFLY-PT and SnapPy tell them apart, a
  key cannot),
* the Jones polynomial equals its mirror image's but the first design's name was chiral
  (the key cannot tell a knot from its mirror image),
* the design's own diagram, simplified, has fewer crossings than the crossing number of
  the table name it would take (another link with the same key, such as a sum),
* the first design ran out of time, or its diagram was too wide for the compiled Jones
  polynomial (:data:`~lkspace.knots.jones` returns no answer).

Beyond the tables (composite knots, split links, hyperbolic links SnapPy names) two types
with equal keys would share a name; the whole spaces of the tetrahedron (-2..2), cube and
octahedron (-1..1) were compared row by row with the geometric path and agree
(``experiments/compare_keyed.py``).
"""

from __future__ import annotations

import functools
import time
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, NamedTuple

import numpy as np

from ..compiled.kernels import helper, kernel, threaded_kernel
from ..model.scaffold import Scaffold
from .assembly import Scratch, assemble_into, assemble_one, work_array
from .budget import MAX_CROSSINGS
from .jones import jones_buffer_size, jones_into
from .labels_diagram import DiagramTemplate, TemplateArrays, template
from .tables import JONES_POINT

KEY_VERSION = "k3"
"""Version of the key's definition (hashes, invariants, trust rule, fields kept): part of the disk cache's name.

Raise it whenever any of them changes, so that no cache written before is read."""

_M1 = np.uint64(0x9E3779B97F4A7C15)
_M2 = np.uint64(0xBF58476D1CE4E5B9)
_M3 = np.uint64(0x94D049BB133111EB)


@helper
def _mix(h: np.uint64, v: int) -> np.uint64:
    """One splitmix64 round of ``h`` with the value ``v`` (compiled: wrapping 64-bit arithmetic)."""
    x = (h ^ np.uint64(v)) * _M1
    x = (x ^ (x >> np.uint64(30))) * _M2
    x = (x ^ (x >> np.uint64(27))) * _M3
    return x ^ (x >> np.uint64(31))


@helper
def _linking_into(comps: np.ndarray, signs: np.ndarray, m: int, n_comp: int, lk: np.ndarray) -> None:
    """Write the linking matrix of a design's ``m`` crossings into ``lk`` (``(n_comp**2,)``, row by row)."""
    lk[:] = 0
    for c in range(m):
        a = comps[c, 0]
        b = comps[c, 1]
        if a != b:
            lk[a * n_comp + b] += signs[c]
            lk[b * n_comp + a] += signs[c]
    for i in range(n_comp * n_comp):
        lk[i] //= 2


@helper
def _with_room(values: np.ndarray, used: int, need: int) -> np.ndarray:
    """Return ``values``, or a copy twice ``need`` long (its first ``used`` kept) when shorter than ``need``."""
    if need <= len(values):
        return values
    grown = np.zeros(2 * need, np.int64)
    grown[:used] = values[:used]
    return grown


@helper
def _hashes(lk: np.ndarray, n_comp: int, lowest: int, poly: np.ndarray, length: int) -> tuple[np.uint64, np.uint64]:
    """Return the two 64-bit hashes of (components, sorted linking numbers of the pairs, Jones polynomial)."""
    pairs = np.zeros(max(n_comp * (n_comp - 1) // 2, 1), np.int64)
    k = 0
    for i in range(n_comp):
        for j in range(i + 1, n_comp):
            pairs[k] = lk[i * n_comp + j]
            k += 1
    pairs = np.sort(pairs[:k])
    h1 = np.uint64(0x243F6A8885A308D3)
    h2 = np.uint64(0x13198A2E03707344)
    h1 = _mix(h1, n_comp)
    h2 = _mix(h2, n_comp + 7)
    for i in range(k):
        h1 = _mix(h1, pairs[i])
        h2 = _mix(h2, pairs[i] * 31 + 5)
    h1 = _mix(h1, lowest)
    h2 = _mix(h2, lowest * 17 + 3)
    for i in range(length):
        h1 = _mix(h1, poly[i])
        h2 = _mix(h2, poly[i] * 131 + i)
    return h1, h2


@kernel
def key_hashes(lk: np.ndarray, n_comp: int, lowest: int, poly: np.ndarray) -> tuple[np.uint64, np.uint64]:
    """Return the key of one link (:func:`design_keys`'s): ``lk (n_comp**2,) int64`` its linking matrix, ``poly`` its Jones coefficients from ``x^lowest``."""
    return _hashes(lk, n_comp, lowest, poly, len(poly))


@helper
def _residue_at(poly: np.ndarray, lowest: int, length: int, point: int, inverse: int) -> int:
    """Return the Laurent polynomial ``poly[:length]`` (from ``x^lowest``) at ``x = point`` modulo :data:`PRIME`."""
    value = 0
    step = power_mod(point if lowest >= 0 else inverse, abs(lowest))
    for i in range(length):
        value = (value + (poly[i] % PRIME) * step) % PRIME
        step = step * point % PRIME
    return value


class KeyArrays(NamedTuple):
    """What :func:`design_keys` returns for ``n_designs`` designs (numba builds and returns it by name).

    ``keys (n_designs, 2) uint64``: two independent 64-bit hashes of (components, sorted
    linking numbers, Jones polynomial).  ``crossings``, ``components (n_designs,) int64``:
    crossings of the assembled diagram, its components.  ``keyed (n_designs,) bool``: the
    Jones polynomial was computed (else the key is not set: too many crossings, or a
    diagram too wide for the compiled state sum).  ``link_offsets (n_designs + 1,) int64``,
    ``link_values (sum of components**2,) int64``: each design's linking matrix, row by row
    (the trace's component order).  ``free (n_designs,) int64``: components without any
    crossing in the diagram.  ``jones_at (n_designs,) int64``: the Jones polynomial at the
    kernel's ``point``, modulo :data:`PRIME` (where ``keyed``).
    """

    keys: np.ndarray
    crossings: np.ndarray
    components: np.ndarray
    keyed: np.ndarray
    link_offsets: np.ndarray
    link_values: np.ndarray
    free: np.ndarray
    jones_at: np.ndarray


@threaded_kernel
def design_keys(
    tmpl: TemplateArrays,
    vidx_2d: np.ndarray,
    work: Scratch,
    max_crossings: int,
    point: int,
) -> tuple[np.ndarray, ...]:
    """Keys of many designs of a template (``tmpl``: :meth:`DiagramTemplate.arrays`).

    ``vidx_2d`` ``(n_designs, n_edges)``: indices into the template's ``label_values``.

    ``point`` is ``x = sqrt(t)`` modulo :data:`PRIME` at which the Jones polynomial is
    also evaluated (for filters comparing it with a target's, :func:`jones_residue`).

    Returns the fields of the designs' :class:`KeyArrays`, in its order, as a plain tuple:
    numba boxing a NamedTuple looks its class up in Python, and a signal raised there made
    it call NULL (a segmentation fault on Ctrl-C); :func:`keys_of` makes the record.
    """
    n_designs = vidx_2d.shape[0]
    size = len(tmpl.crossing_sign)
    pd = np.zeros((size, 4), np.int64)
    signs = np.zeros(size, np.int64)
    comps = np.zeros((size, 2), np.int64)
    poly = np.zeros(jones_buffer_size(size, len(tmpl.port_a)), np.int64)
    keys = np.zeros((n_designs, 2), np.uint64)
    crossings = np.zeros(n_designs, np.int64)
    components = np.zeros(n_designs, np.int64)
    keyed = np.zeros(n_designs, np.bool_)
    link_offsets = np.zeros(n_designs + 1, np.int64)
    link_values = np.zeros(16 * n_designs, np.int64)
    free = np.zeros(n_designs, np.int64)
    jones_at = np.zeros(n_designs, np.int64)
    inverse = power_mod(point, PRIME - 2)
    for d in range(n_designs):
        m, n_comp, n_free = assemble_into(tmpl, vidx_2d[d], pd, signs, comps, work)
        crossings[d] = m
        components[d] = n_comp
        free[d] = n_free
        base = link_offsets[d]
        need = base + n_comp * n_comp
        link_values = _with_room(link_values, base, need)
        lk = link_values[base:need]
        _linking_into(comps, signs, m, n_comp, lk)
        link_offsets[d + 1] = need
        if m > max_crossings:
            continue
        lowest, length = jones_into(pd[:m], signs[:m], n_free, poly)
        if length < 0:
            continue
        h1, h2 = _hashes(lk, n_comp, lowest, poly, length)
        keys[d, 0] = h1
        keys[d, 1] = h2
        keyed[d] = True
        jones_at[d] = _residue_at(poly, lowest, length, point, inverse)
    return (keys, crossings, components, keyed, link_offsets, link_values[: link_offsets[n_designs]], free, jones_at)


PRIME = 2_147_483_647
"""The prime (2**31 - 1) modulo which the Jones polynomial is evaluated: products fit in int64."""


@helper
def power_mod(base: int, exponent: int) -> int:
    """Return ``base ** exponent`` modulo :data:`PRIME` (``exponent >= 0``)."""
    out = 1
    b = base % PRIME
    e = exponent
    while e > 0:
        if e & 1:
            out = out * b % PRIME
        b = b * b % PRIME
        e >>= 1
    return out


def jones_residue(value: Fraction) -> int:
    """Return a rational Jones value (at ``sqrt t = 2/3``, :data:`~lkspace.knots.tables.JONES_POINT`) modulo :data:`PRIME`."""
    return value.numerator % PRIME * pow(value.denominator % PRIME, PRIME - 2, PRIME) % PRIME


def jones_point() -> int:
    """Return :data:`~lkspace.knots.tables.JONES_POINT` modulo :data:`PRIME`."""
    return jones_residue(Fraction(JONES_POINT))


@dataclass(frozen=True, eq=False)
class DesignKeys:
    """What :func:`keys_of` computed for a batch of designs (see :func:`design_keys`)."""

    template: DiagramTemplate
    vidx: np.ndarray
    keys: np.ndarray
    crossings: np.ndarray
    components: np.ndarray
    keyed: np.ndarray
    link_offsets: np.ndarray
    link_values: np.ndarray
    free: np.ndarray
    jones_at: np.ndarray

    def linking_matrix(self, d: int) -> list[list[int]]:
        """Design ``d``'s linking matrix."""
        c = int(self.components[d])
        return self.link_values[self.link_offsets[d] : self.link_offsets[d + 1]].reshape(c, c).tolist()

    @functools.cached_property
    def _assembly(self) -> tuple[TemplateArrays, Scratch]:
        """The template's arrays and one scratch space, made once for every :meth:`diagram` (40% of its time)."""
        return self.template.arrays(), work_array(self.template)

    def diagram(self, d: int) -> tuple[list[list[int]], int, np.ndarray]:
        """Design ``d``'s PD code (1-based), components and crossing signs, assembled again."""
        arrays, work = self._assembly
        pd, signs, _, n_comp, _ = assemble_one(arrays, self.vidx[d], work)
        return pd.tolist(), int(n_comp), signs


def keys_of(
    scaffold: Scaffold, labels_2d: np.ndarray, seed: int = 0, label_values: Any = None, stop: Any = None
) -> DesignKeys:
    """Keys of ``labels_2d`` (``(n_designs, n_edges)``, twists within ``label_values``, default their own).

    ``stop``: a :class:`threading.Event` that, once set, ends the keying between two
    calls of the kernel with :class:`KeyingStopped` (for keying in another thread, which
    Ctrl-C and time limits do not reach).
    """
    tmpl, vidx = keying_input(scaffold, labels_2d, seed, label_values)
    return keys_record(tmpl, vidx, _keys_in_threads(tmpl, vidx, stop))


def keying_input(
    scaffold: Scaffold, labels_2d: np.ndarray, seed: int = 0, label_values: Any = None
) -> tuple[DiagramTemplate, np.ndarray]:
    """Return the template that keys ``labels_2d`` and their indices into its values, ``(n_designs, n_edges)``."""
    values = np.unique(labels_2d) if label_values is None else np.union1d(label_values, np.unique(labels_2d))
    tmpl = template(scaffold, values, seed)
    return tmpl, np.ascontiguousarray(tmpl.value_index(labels_2d))


def key_part(tmpl: DiagramTemplate, vidx: np.ndarray) -> tuple[np.ndarray, ...]:
    """Return :func:`design_keys`'s fields for ``vidx`` (value indices of some designs), in one call on this thread."""
    return tuple(design_keys(tmpl.arrays(), vidx, work_array(tmpl), MAX_CROSSINGS, jones_point()))


def joined(parts: list[tuple[np.ndarray, ...]]) -> tuple[np.ndarray, ...]:
    """Return the fields of consecutive parts' :func:`key_part` as those of all their designs at once."""
    offsets = [parts[0][4]]
    for part in parts[1:]:
        offsets.append(part[4][1:] + offsets[-1][-1])
    fields = [np.concatenate([part[f] for part in parts]) for f in range(len(parts[0]))]
    fields[4] = np.concatenate(offsets)
    return tuple(fields)


def keys_record(tmpl: DiagramTemplate, vidx: np.ndarray, fields: tuple[np.ndarray, ...]) -> DesignKeys:
    """Return the :class:`DesignKeys` of designs ``vidx`` from their :func:`design_keys` ``fields``."""
    out = KeyArrays(*fields)
    return DesignKeys(
        template=tmpl,
        vidx=vidx,
        keys=out.keys,
        crossings=out.crossings,
        components=out.components,
        keyed=out.keyed,
        link_offsets=out.link_offsets,
        link_values=out.link_values,
        free=out.free,
        jones_at=out.jones_at,
    )


STEP_SECONDS = 0.1
"""Seconds of one :func:`design_keys` call in :func:`keys_of`: between calls, Ctrl-C and time limits are seen."""

FIRST_STEP = 256
"""Designs per thread in the first call of :func:`keys_of` (the next calls are sized by its rate)."""


def key_threads() -> int:
    """Threads :func:`keys_of` keys with: the cores this process may use, one in a worker process (its siblings share them)."""
    import multiprocessing
    import os

    if multiprocessing.parent_process() is not None:
        return 1
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1


class KeyingStopped(Exception):
    """Keying ended by its ``stop`` event (:func:`keys_of`)."""


def _keys_in_threads(tmpl: DiagramTemplate, vidx: np.ndarray, stop: Any = None) -> tuple[np.ndarray, ...]:
    """:func:`design_keys` of ``vidx``: calls of about :data:`STEP_SECONDS`, each split over :func:`key_threads` threads.

    The kernel releases Python's lock, so the threads run at once; the designs go in
    consecutive parts, so the result does not depend on how they were split.
    """
    from concurrent.futures import ThreadPoolExecutor

    threads = max(1, key_threads())
    _ = design_keys.compiled  # compiled (or loaded) once, here, not by racing threads
    if not len(vidx):
        return key_part(tmpl, vidx)
    found: list[tuple[np.ndarray, ...]] = []
    with ThreadPoolExecutor(threads) as pool:
        start, step = 0, FIRST_STEP
        while start < len(vidx):
            if stop is not None and stop.is_set():
                raise KeyingStopped
            end = min(len(vidx), start + step * threads)
            bounds = np.linspace(start, end, threads + 1).astype(np.int64)
            parts = [vidx[a:b] for a, b in zip(bounds[:-1], bounds[1:], strict=True) if b > a]
            began = time.perf_counter()
            found.extend(
                pool.map(functools.partial(key_part, tmpl), parts) if len(parts) > 1 else [key_part(tmpl, parts[0])]
            )
            rate = (end - start) / len(parts) / max(time.perf_counter() - began, 1e-4)
            start, step = end, int(min(max(rate * STEP_SECONDS, 16), 1 << 16))
    return joined(found)
