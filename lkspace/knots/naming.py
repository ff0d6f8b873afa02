"""Naming a PD code: simplify (spherogram), then look up Jones, HOMFLY-PT and volume in the tables.

See :mod:`lkspace.knots.recognition` for the whole pipeline and what a name promises.
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable, Iterable
from types import ModuleType
from typing import Any

from ..runtime.progress import Step
from .budget import INLINE_CROSSINGS, run_in_time
from .hoste import TABLE, ht_name
from .identification import Naming
from .tables import HOMFLY_MAX_CROSSINGS, JONES_POINT, knot_modules, laurent_value, tables

KNOT_FLOER_MAX_CROSSINGS = 40
"""Most crossings of a simplified knot diagram whose knot Floer homology is computed.

Its cost grows steeply with the crossings (minutes past about 60); it is an extra
invariant for knots beyond the tables, so bigger diagrams go without it.
"""


def _homfly(regina: ModuleType, pd: list[list[int]], mirror: bool = False) -> str:
    link = regina.Link.fromPD(pd)
    if mirror:
        link.changeAll()
    return str(link.homfly())


def _identify_names(link: Any) -> tuple[list[str], float | None, Any]:
    """SnapPy's names of the exterior (``[]`` if not hyperbolic), its volume and the exterior if hyperbolic."""
    try:
        exterior = link.exterior()
        hyperbolic = exterior.solution_type() == "all tetrahedra positively oriented"
        volume = float(exterior.volume()) if hyperbolic else 0.0
        names = [str(m).split("(")[0] for m in exterior.identify()] if hyperbolic else []
        return names, volume, exterior if hyperbolic else None
    except Exception:  # noqa: BLE001 - SnapPy may fail on a degenerate exterior
        return [], None, None


def name_diagram(pd: list[list[int]], n_components: int) -> Naming:
    """Name one non-split link diagram given by its PD code.

    Returns
    -------
    Naming
        ``name`` (or ``None``), ``table_name``, ``mirror``, ``candidates`` and invariants
        ``crossings`` (simplified diagram), ``jones``, ``homfly``, ``volume``.
    """
    spherogram, regina, _ = knot_modules()
    out = Naming.of(name=None, table_name=None, mirror=None, candidates=())
    if not pd:
        out = out.updated(crossings=0, jones="1", homfly=None, volume=0.0)
        if n_components == 1:
            out = out.updated(name="0_1", table_name="0_1", table="knotinfo")
        return out
    rl = regina.Link.fromPD(pd)
    jones = rl.jones()
    out = out.updated(crossings=len(pd), jones=str(jones))
    fp, fp_mirror = laurent_value(jones, JONES_POINT), laurent_value(jones, 1 / JONES_POINT)
    index = tables()
    cands = [(e, False) for e in index.get(fp, [])] + [(e, True) for e in index.get(fp_mirror, [])]
    cands = [(e, m) for e, m in cands if e.components == n_components and e.crossings <= len(pd)]
    homfly = str(rl.homfly()) if len(pd) <= HOMFLY_MAX_CROSSINGS else None
    if homfly is not None and cands:
        cands = [(e, m) for e, m in cands if e.pd and _homfly(regina, json.loads(e.pd), m) == homfly]
    link = spherogram.Link(pd)
    names, volume, exterior = _identify_names(link)
    out = out.updated(volume=volume)
    if len({e.name for e, _ in cands}) > 1 and names:
        cands = [(e, m) for e, m in cands if e.name in names or _knot_alias(e.name) in names]
    out = out.updated(
        homfly=homfly, candidates=tuple(sorted({e.table_name + (" (mirror)" if m else "") for e, m in cands}))
    )
    if not cands and exterior is not None:
        return _name_from_ht(out, exterior, n_components)
    if len({e.name for e, _ in cands}) != 1:
        return out
    entry = cands[0][0]
    table_volume = entry.volume or 0.0
    if volume is None or abs(table_volume - volume) > 1e-4 * max(1.0, table_volume):
        return out.updated(note=f"volume {volume} differs from {entry.table_name}'s {table_volume}")
    mirrors = {m for _, m in cands}
    out = out.updated(
        name=entry.name, table_name=entry.table_name, table="knotinfo" if n_components == 1 else "linkinfo"
    )
    out = out.updated(mirror=mirrors.pop() if len(mirrors) == 1 else None)
    if out.mirror is not None and n_components == 1:
        out = out.updated(chiral_name=("m" if out.mirror else "") + entry.name)
    return out


def _name_from_ht(out: Naming, exterior: Any, n_components: int) -> Naming:
    """Name a hyperbolic link in no KnotInfo/LinkInfo entry from ``HTLinkExteriors`` (:mod:`lkspace.knots.hoste`)."""
    found = ht_name(exterior, n_components)
    if found is None:
        return out
    out = out.updated(name=found.name, table_name=found.name, table=TABLE, mirror=found.mirror)
    if found.mirror is not None and n_components == 1:
        out = out.updated(chiral_name=("m" if found.mirror else "") + found.name)
    return out


def _knot_alias(name: str) -> str:
    """KnotInfo ``11a_1`` is SnapPy's ``K11a1``; Rolfsen names are shared."""
    m = re.fullmatch(r"(\d+)([an])_(\d+)", name)
    return f"K{m[1]}{m[2]}{m[3]}" if m else name


def one_based(pd: Iterable[Iterable[int]]) -> list[list[int]]:
    """Renumber PD edges from 1, as KnotTheory and regina do (spherogram numbers them from 0)."""
    return [[int(v) + 1 for v in x] for x in pd]


def _quiet(text: str) -> None:
    """Ignore a stage name (no progress wanted)."""


def name_pd(
    pd: list[list[int]], n_components: int, stage: Callable[[str], None] = _quiet, *, floer: bool = True
) -> Naming:
    """Simplify and name the link of a PD code (1-based, KnotTheory convention).

    Split links are named piece by piece (``name`` stays ``None``, ``pieces`` lists
    them); a composite whose prime factors are all in the tables gets the name
    ``"3_1#4_1"`` (``prime: False``, ``factors``).  ``stage`` is told each stage as it
    starts (``"simplification"``, ``"table lookup"``, ``"knot Floer homology"``).
    ``floer=False`` leaves out knot Floer homology (an extra invariant, seconds on big
    knots, that catalogs do not keep).
    """
    spherogram, _, _ = knot_modules()
    if pd:
        stage(f"simplification ({len(pd)} crossings)")
        pd = presimplified(pd)
    if not pd:
        knot = n_components == 1
        out = Naming.of(name="0_1" if knot else None, table="knotinfo" if knot else None, crossings=0)
        out = out.updated(split=n_components > 1, mirror=None, jones="1")
        if n_components > 1:
            out = out.updated(pieces=("0_1",) * n_components, note=f"unlink of {n_components} components")
        return out
    stage(f"simplification ({len(pd)} crossings)")
    link = spherogram.Link(pd)
    n_free = n_components - len(link.link_components)
    link.simplify("global")
    stage(f"table lookup ({len(link.crossings)} crossings)")
    pieces = link.split_link_diagram()
    n_free += link.unlinked_unknot_components
    if len(pieces) + n_free > 1:
        named = [name_pd(one_based(p.PD_code()), len(p.link_components), stage, floer=floer) for p in pieces]
        names = (*(p.name for p in named), *(["0_1"] * n_free))
        out = Naming.of(name=None, split=True, crossings=sum(p.crossings or 0 for p in named), pieces=names)
        return out.updated(mirror=None, note="split link: " + " + ".join(str(p) for p in names))
    simple = one_based(link.PD_code())
    out = name_diagram(simple, n_components).updated(split=False)
    if out.name is None and simple:
        out = _name_sum(out, link, n_components)
    if floer and n_components == 1 and simple and len(simple) <= KNOT_FLOER_MAX_CROSSINGS:
        stage("knot Floer homology")
        try:
            hfk = link.knot_floer_homology()
            keys = ("seifert_genus", "fibered", "tau", "total_rank", "L_space_knot")
            out = out.updated(knot_floer={k: hfk[k] for k in keys})
        except Exception:  # noqa: BLE001 - optional invariant
            pass
    return out


def _name_sum(out: Naming, link: Any, n_components: int) -> Naming:
    """Name a composite by its prime factors (``factors``; the name ``"3_1#4_1"`` when every factor is named)."""
    factors = link.copy().deconnect_sum()
    if len(factors) <= 1:
        return out
    named = [name_diagram(one_based(f.PD_code()), len(f.link_components)) for f in factors]
    out = out.updated(factors=tuple(f.chiral_name or f.name for f in named))
    if not all(f.name for f in named):
        return out
    out = out.updated(name="#".join(sorted((str(f.name) for f in named), key=name_key)), prime=False, mirror=None)
    out = out.updated(table="+".join(sorted({str(f.table) for f in named})))
    if all(f.chiral_name or f.mirror is None for f in named) and n_components == 1:
        out = out.updated(chiral_name="#".join(sorted((str(f) for f in out.factors or ()), key=name_key)))
    return out


def presimplified(pd: list[list[int]]) -> list[list[int]]:
    """Return ``pd`` after regina's greedy simplification: milliseconds, and it leaves spherogram little to do.

    Components left without crossings drop out of the code (the caller keeps the count).
    Regina's random moves start from its default seed: the same code every run.
    """
    if not pd:
        return pd
    regina = knot_modules()[1]
    regina.RandomEngine.reseedWithDefault()
    link = regina.Link.fromPD(pd)
    link.simplify()
    return [list(x) for x in link.pdData()]


def name_key(name: str) -> tuple[int, str]:
    """Sort key of a name: crossing number first (``"m3_1"``, ``"L6a4"``, ``"K14n10910"`` alike), then the text."""
    m = re.match(r"m?[KL]?(\d+)", name)
    return (int(m[1]) if m else 0, name)


def status_of(named: Naming) -> str:
    """Return the status of a :func:`~lkspace.knots.naming.name_pd` result: identified or why not."""
    if named.name is not None:
        return "identified"
    pieces = named.pieces
    if named.split and pieces and all(p is not None for p in pieces):
        return "identified"
    if named.split:
        return "unknown: a piece of the split link is not in the tables"
    candidates = named.candidates or ()
    if len(candidates) > 1:
        return f"unknown: {len(candidates)} table entries match ({', '.join(str(c) for c in candidates[:4])})"
    if named.note:
        return f"unknown: {named.note}"
    return "unknown: not in the tables (KnotInfo/LinkInfo: knots up to 13 crossings, links up to 11; HTLinkExteriors: hyperbolic knots up to 15, links up to 14)"


def name_in_time(
    pd: list[list[int]], n_components: int, time_limit: float | None, step: Step | None, *, floer: bool = True
) -> Naming:
    """Name the PD code ``pd`` within ``time_limit`` seconds (:func:`~lkspace.knots.budget.run_in_time`).

    Diagrams of at most :data:`~lkspace.knots.budget.INLINE_CROSSINGS` crossings are
    named in this process: they take milliseconds.
    """
    knot_modules()
    tables()  # loaded here, shared with the forked child

    def work(stage: Callable[[str], None]) -> Naming:
        return name_pd(pd, n_components, stage, floer=floer)

    return run_in_time(work, None if len(pd) <= INLINE_CROSSINGS else time_limit, step)


def split_name(pieces: tuple[str | None, ...] | None) -> str | None:
    """Return the name of a split link from its pieces' names, sorted (``None`` when a piece is unnamed).

    The spelling of :func:`lkspace.linktypes.atlas.type_key`, which ``lookup`` reads:
    ``split: 0_1 + 3_1``; an unlink is ``split: 0_1 + 0_1`` (common name ``unlink of 2 components``).
    """
    if not pieces or not all(pieces):
        return None
    return "split: " + " + ".join(sorted(str(p) for p in pieces))


def named_as_split(named: Naming) -> Naming:
    """Return ``named`` with a split link's :func:`split_name` as its name (identify's ``name``; catalogs keep ``None``)."""
    name = split_name(named.pieces) if named.split and named.name is None else None
    return named if name is None else named.updated(name=name)
