"""Knot and link identification of realized strands (extra ``[knots]``).

Pipeline: :func:`lkspace.geometry.realization.realize` -> :func:`lkspace.knots.diagram.project`
(generic projection, PD code) -> :func:`lkspace.knots.naming.name_pd` (spherogram
``simplify('global')``, then the tables of :mod:`lkspace.knots.tables`) -> names.

Naming.  The Jones polynomial (regina, no Sage) of the simplified diagram, evaluated
exactly at ``sqrt(t) = 2/3`` and ``3/2`` (its mirror), is looked up in the KnotInfo
(knots up to 13 crossings) and LinkInfo (links up to 11 crossings, every orientation)
tables of ``database_knotinfo``.  Candidates are narrowed by the HOMFLY-PT polynomial
(regina, computed on our diagram and on the table's own PD code, so conventions agree)
and by SnapPy's ``identify()`` of the exterior.  A single remaining table entry is
accepted only if the hyperbolic volume agrees (zero for torus and satellite knots and
links, which ``identify()`` cannot name); otherwise ``name`` is ``None`` and the
invariants are returned.  Names: ``"0_1"``, Rolfsen ``"3_1"``..., Thistlethwaite
``"L2a1"``...; ``mirror`` says whether the structure is the table diagram's mirror image
(``None`` when the knot or link equals its mirror as far as HOMFLY-PT tells).
KnotInfo's ``3_1`` is the right-handed (positive) trefoil.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..errors import LkspaceError, TooLargeError, UsageError
from ..geometry.params import GeometryParams, RealizeOptions
from ..geometry.realization import realize
from ..model.scaffold import Scaffold
from ..progress import Step, task
from ..strands.tracing import trace
from ..words import plural
from .budget import INLINE_CROSSINGS, MAX_CROSSINGS, TIME_LIMIT, TimeLimitReached, run_in_time, twist_crossings
from .diagram import project, project_generic
from .naming import name_pd
from .tables import knot_modules, tables


@dataclass(frozen=True, repr=False)
class Identification:
    """The knot or link type of a closed structure.

    Attributes
    ----------
    components : int
    name : str or None
        ``"0_1"``, Rolfsen (``"3_1"``) or Thistlethwaite (``"L6a4"``) name; ``None`` if unknown.
    linking_matrix : list of list of int
    mirror : bool or None
        The structure is the table diagram's mirror image (``None``: the tables cannot tell).
    split : bool or None
    crossings : int or None
        Crossings of the simplified diagram.
    details : dict
        Everything else: ``jones``, ``homfly``, ``volume``, ``candidates``, ``pieces``, ...
    status : str
        ``"identified"`` (named, or a split link with every piece named) or
        ``"unknown: <why>"``: not in the tables, several entries match, ``diagram too
        large: N crossings > 2000`` or ``time limit 60 s reached (during ...)``.
    """

    components: int
    name: str | None
    linking_matrix: list[list[int]]
    mirror: bool | None = None
    split: bool | None = None
    crossings: int | None = None
    details: dict[str, Any] = field(default_factory=dict)
    status: str = "identified"

    def __repr__(self) -> str:
        chirality = {True: ", mirror", False: "", None: ""}[self.mirror]
        crossings = "crossings unknown" if self.crossings is None else plural(self.crossings, "crossing")
        counts = f"{plural(self.components, 'component')}, {crossings}"
        return f"Identification({self.name or 'unknown'}{chirality}: {counts})"

    def to_dict(self) -> dict[str, Any]:
        """Return the JSON form (``status``, ``components``, ``name``, ``linking_matrix``, and every invariant)."""
        return {
            "status": self.status,
            "components": self.components,
            "name": self.name,
            "linking_matrix": self.linking_matrix,
            "mirror": self.mirror,
            "split": self.split,
            "crossings": self.crossings,
            **self.details,
        }


def status_of(named: dict[str, Any]) -> str:
    """Return the status of a :func:`~lkspace.knots.naming.name_pd` result: identified or why not."""
    if named.get("name") is not None:
        return "identified"
    pieces = named.get("pieces")
    if named.get("split") and pieces and all(p is not None for p in pieces):
        return "identified"
    if named.get("split"):
        return "unknown: a piece of the split link is not in the tables"
    candidates = named.get("candidates") or []
    if len(candidates) > 1:
        return f"unknown: {len(candidates)} table entries match ({', '.join(candidates[:4])})"
    if named.get("note"):
        return f"unknown: {named['note']}"
    return "unknown: not in the tables (KnotInfo/LinkInfo: knots up to 13 crossings, links up to 11; HTLinkExteriors: hyperbolic knots up to 15, links up to 14)"


def identify_curves(curves: Sequence[np.ndarray], seed: int = 0) -> dict[str, Any]:
    """Identify the link formed by closed polylines ``curves`` (list of ``(n_k, 3)``), without a time limit.

    Returns
    -------
    dict
        ``components``, ``name``, ``linking_matrix``, ``projected_crossings`` and the
        results of :func:`name_pd` (invariants, see the module docstring).
    """
    diagram = project(curves, seed=seed)
    out = {
        "components": len(curves),
        "linking_matrix": diagram.linking_matrix().tolist(),
        "projected_crossings": diagram.n_crossings,
    }
    out.update(name_pd(diagram.pd, len(curves)))
    return out


def check_identifiable(scaffold: Scaffold) -> None:
    """Refuse a periodic scaffold: its strands are infinite structures, not knots or links.

    The loops of one module are not the structure (they link their neighbours), so naming
    them would mislead; ``export --block`` shows a block of the structure instead.
    """
    if scaffold.periodic:
        raise UsageError(
            f"{scaffold.name}: a periodic scaffold; identify names knots and links of finite "
            "scaffolds only (its loops link their lattice translates); to look at a block of the structure, export one with `block`"
        )


def identify(
    scaffold: Scaffold,
    labels: ArrayLike | None = None,
    nulls: ArrayLike | None = None,
    params: GeometryParams | None = None,
    seed: int = 0,
    *,
    time_limit: float | None = TIME_LIMIT,
) -> Identification:
    """Knot or link type of a scaffold labelled by twist ``labels`` (extra ``[knots]``).

    Parameters
    ----------
    scaffold : Scaffold
        A finite scaffold (periodic ones are refused, :func:`check_identifiable`);
        ``lkspace.identify`` also takes a path or a built-in name (:func:`lkspace.load`).
    labels, nulls : as for :func:`lkspace.trace`
    params : GeometryParams, optional
        Realization parameters.
    seed : int
        Seed of the generic projection.
    time_limit : float or None
        Seconds for the whole identification (default
        :data:`~lkspace.knots.budget.TIME_LIMIT`); past it the status is ``unknown: time
        limit ... reached`` with the invariants known so far.  ``None`` or 0: no limit.

    Raises
    ------
    TooLargeError
        When the twists alone would make more than
        :data:`~lkspace.knots.budget.MAX_CROSSINGS` crossings (checked before realizing).

    Examples
    --------
    >>> import lkspace
    >>> lkspace.identify("dihedron:3", 1)
    Identification(3_1: 1 component, 3 crossings)
    """
    t0 = time.monotonic()
    check_identifiable(scaffold)
    with task(f"identifying {scaffold.name}") as step:
        step.note("tracing")
        tr = trace(scaffold, labels, nulls)
        if not tr.closed.all():
            raise LkspaceError(f"{scaffold.name}: cannot identify a structure with open strands (null edge-sides)")
        estimate = twist_crossings(scaffold.edge_degrees, tr.labels)
        if estimate > MAX_CROSSINGS:
            raise TooLargeError(
                f"{scaffold.name}: the twists make about {estimate:,} crossings (sum of |t|(K-1) over the edges) "
                f"> {MAX_CROSSINGS:,} (MAX_CROSSINGS): too large to identify; use smaller twists"
            )
        step.note("realizing")
        # the construction polylines (smoothing off unless asked): isotopic to the smoothed strands, cheaper
        real = realize(
            scaffold, tr.labels, nulls, params or GeometryParams(smooth=False), options=RealizeOptions(trace=tr)
        )
        step.note("diagram")
        diagram = project_generic(real.curves, seed)
        head = {
            "components": len(real.curves),
            "linking_matrix": diagram.linking_matrix().tolist(),
            "projected_crossings": diagram.n_crossings,
        }
        out: dict[str, Any]
        if diagram.n_crossings > MAX_CROSSINGS:
            status = f"unknown: diagram too large: {diagram.n_crossings:,} crossings > {MAX_CROSSINGS:,}"
            out = {**head, "name": None}
        else:
            left = None if not time_limit else max(time_limit - (time.monotonic() - t0), 1e-3)
            try:
                out = {**head, **name_in_time(diagram.pd, diagram.n_components, left, step)}
                status = status_of(out)
            except TimeLimitReached as exc:
                status = f"unknown: time limit {time_limit:g} s reached (during {exc.stage})"
                out = {**head, "name": None}
    out["min_distance"] = real.min_distance
    main = {k: out.pop(k, None) for k in ("components", "name", "linking_matrix", "mirror", "split", "crossings")}
    return Identification(**main, details=out, status=status)


def name_in_time(
    pd: list[list[int]], n_components: int, time_limit: float | None, step: Step | None, *, floer: bool = True
) -> dict[str, Any]:
    """Name the PD code ``pd`` within ``time_limit`` seconds (:func:`~lkspace.knots.budget.run_in_time`).

    Diagrams of at most :data:`~lkspace.knots.budget.INLINE_CROSSINGS` crossings are
    named in this process: they take milliseconds.
    """
    knot_modules()
    tables()  # loaded here, shared with the forked child

    def work(stage: Callable[[str], None]) -> dict[str, Any]:
        return name_pd(pd, n_components, stage, floer=floer)

    return run_in_time(work, None if len(pd) <= INLINE_CROSSINGS else time_limit, step)
