"""The keys of the table types, and the names their designs take, computed from the tables' PD codes.

A key (:mod:`lkspace.knots.keyed`) depends on the oriented link only: its components,
the sorted linking numbers of its pairs and its Jones polynomial.  So it can be computed
from a table entry's PD code as from a design's diagram, and a mirror image's key from
the entry's (Jones polynomial at ``1/x``, linking numbers negated).  LinkInfo lists a
link once per orientation class, so the entries and their mirrors reach every key a
design of a table type can have.

:func:`table_fields` gives what :func:`~lkspace.knots.naming.name_pd` gives a design of
that key (the table branch of :func:`~lkspace.knots.naming.name_diagram`, without
SnapPy: the entry's own diagram is minimal and its volume is the table's); the key is
kept with these fields when :func:`~lkspace.knots.key_names.trusted` trusts it, else as
a key whose designs are named on their own.  ``experiments/build_key_names.py`` writes
them to ``lkspace/data/`` (:mod:`lkspace.knots.shipped_keys` reads them).
"""

from __future__ import annotations

import json
from typing import Any

import numpy as np

from .identification import NameFields
from .keyed import key_hashes
from .tables import JONES_POINT, TableEntry, knot_modules, laurent_value, tables

UNKNOT_KEY_FIELDS = NameFields(knot_name="0_1", split=False, crossings=0, jones="1", table="knotinfo")
"""The fields :func:`~lkspace.knots.naming.name_pd` gives an unknot (its diagram simplifies to none)."""


def pd_key(pd: list[list[int]], mirror: bool = False) -> tuple[int, int]:
    """Return the key ``(hash, hash)`` of a PD code (1-based, every component drawn), or of its mirror image.

    The same as :func:`~lkspace.knots.keyed.design_keys` gives a design whose diagram is ``pd``.
    """
    from .jones import jones

    code = np.asarray(pd, np.int64).reshape(-1, 4)
    lowest, coeffs = jones(code)
    lk, n_comp = linking_matrix(code)
    if mirror:
        lowest, coeffs = -(lowest + len(coeffs) - 1), coeffs[::-1]
        lk = -lk
    h1, h2 = key_hashes(np.ascontiguousarray(lk.ravel()), n_comp, lowest, np.asarray(coeffs, np.int64))
    return int(h1), int(h2)


def unknot_key() -> tuple[int, int]:
    """Return the unknot's key (one component, Jones polynomial 1)."""
    h1, h2 = key_hashes(np.zeros(1, np.int64), 1, 0, np.ones(1, np.int64))
    return int(h1), int(h2)


def linking_matrix(code: np.ndarray) -> tuple[np.ndarray, int]:
    """Return the linking matrix ``(c, c) int64`` of a PD code ``(n, 4)`` and its ``c`` components."""
    from .pd_code import pd_signs

    labels = sorted(set(code.ravel().tolist()))
    where = {v: i for i, v in enumerate(labels)}
    parent = list(range(len(labels)))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for a, b, c, d in code.tolist():
        parent[root(where[a])] = root(where[c])
        parent[root(where[b])] = root(where[d])
    roots = sorted({root(i) for i in range(len(labels))})
    comp = {r: k for k, r in enumerate(roots)}
    lk = np.zeros((len(roots), len(roots)), np.int64)
    for (a, b, _, _), sign in zip(code.tolist(), pd_signs(code).tolist(), strict=True):
        i, j = comp[root(where[a])], comp[root(where[b])]
        if i != j:
            lk[i, j] += sign
            lk[j, i] += sign
    return lk // 2, len(roots)


def table_fields(entry: TableEntry, mirror: bool) -> NameFields | None:
    """Return the row fields of a design of ``entry``'s type (its mirror image with ``mirror``).

    ``None`` when the Jones and HOMFLY-PT polynomials leave more than one table name
    (:func:`~lkspace.knots.naming.name_diagram` would ask SnapPy).
    """
    from .key_names import table_homfly

    _, regina, _ = knot_modules()
    pd = entry.pd_code()
    link = regina.Link.fromPD(pd)
    if mirror:
        link.changeAll()
    jones = link.jones()
    fp, fp_mirror = laurent_value(jones, JONES_POINT), laurent_value(jones, 1 / JONES_POINT)
    index = tables()
    cands = [(e, False) for e in index.get(fp, [])] + [(e, True) for e in index.get(fp_mirror, [])]
    cands = [(e, m) for e, m in cands if e.components == entry.components and e.crossings <= len(pd)]
    homfly = str(link.homfly())
    cands = [(e, m) for e, m in cands if table_homfly(e.pd, m) == homfly]
    if {e.name for e, _ in cands} != {entry.name}:
        return None
    mirrors = {m for _, m in cands}
    side = mirrors.pop() if len(mirrors) == 1 else None
    knot = entry.components == 1
    return NameFields(
        knot_name=entry.name,
        split=False,
        mirror=side,
        crossings=len(pd),
        jones=str(jones),
        table="knotinfo" if knot else "linkinfo",
        chiral_name=("m" if side else "") + entry.name if knot and side is not None else None,
        candidates=tuple(sorted({e.table_name + (" (mirror)" if m else "") for e, m in cands})),
    )


def table_keys(max_knot: int, max_link: int) -> dict[tuple[int, int], NameFields | None]:
    """Return every key of the table knots up to ``max_knot`` crossings and links up to ``max_link``, mirrors too.

    A key maps to the fields its designs share, or to ``None`` where they are named on
    their own (the tables hold several types with its Jones polynomial, or both mirror
    images of a chiral type); a key two entries give different fields maps to ``None``.
    """
    from .jones import jones
    from .key_names import candidates, trusted

    out: dict[tuple[int, int], NameFields | None] = {}
    entries = sorted(
        {e.table_name: e for es in tables().values() for e in es}.values(), key=lambda e: (e.crossings, e.table_name)
    )
    out[unknot_key()] = UNKNOT_KEY_FIELDS
    for entry in entries:
        if not entry.pd or entry.crossings > (max_knot if entry.components == 1 else max_link):
            continue
        code = entry.pd_code()
        lowest, coeffs = jones(code)
        for mirror in (False, True):
            key = pd_key(code, mirror)
            poly = (-(lowest + len(coeffs) - 1), list(coeffs[::-1])) if mirror else (lowest, list(coeffs))
            fields = table_fields(entry, mirror)
            if fields is not None and not trusted(fields, candidates(poly, entry.components)):
                fields = None
            if key in out and out[key] != fields:
                fields = None
            out[key] = fields
    return out


def line(key: tuple[int | str, ...], fields: NameFields | None) -> str:
    """Return the cache line of a key (:class:`~lkspace.knots.key_names.KeyCache`'s JSON)."""
    data: dict[str, Any] = {"key": list(key), "fields": None if fields is None else fields.to_json()}
    return json.dumps(data, separators=(",", ":"))
