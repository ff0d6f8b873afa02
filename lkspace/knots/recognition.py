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

import numpy as np
from numpy.typing import ArrayLike

from ..errors import LkspaceError, TooLargeError, UsageError
from ..geometry.params import GeometryParams, RealizeOptions
from ..geometry.realization import realize
from ..model.scaffold import Scaffold
from ..runtime.progress import Step, task
from ..strands.tracing import trace
from .budget import INLINE_CROSSINGS, MAX_CROSSINGS, TIME_LIMIT, TimeLimitReached, run_in_time, twist_crossings
from .diagram import project, project_generic
from .identification import Identification, Naming
from .naming import name_pd
from .tables import knot_modules, tables


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


def identify_curves(curves: Sequence[np.ndarray], seed: int = 0) -> Identification:
    """Identify the link formed by closed polylines ``curves`` (list of ``(n_k, 3)``), without a time limit.

    Returns
    -------
    Identification
        Its details hold ``projected_crossings`` and the invariants of :func:`name_pd`
        (see the module docstring).
    """
    diagram = project(curves, seed=seed)
    named = name_pd(diagram.pd, len(curves))
    lm = diagram.linking_matrix().tolist()
    return Identification.of(named, status_of(named), len(curves), lm, {"projected_crossings": diagram.n_crossings})


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
        named = Naming.of(name=None)
        if diagram.n_crossings > MAX_CROSSINGS:
            status = f"unknown: diagram too large: {diagram.n_crossings:,} crossings > {MAX_CROSSINGS:,}"
        else:
            left = None if not time_limit else max(time_limit - (time.monotonic() - t0), 1e-3)
            try:
                named = name_in_time(diagram.pd, diagram.n_components, left, step)
                status = status_of(named)
            except TimeLimitReached as exc:
                status = f"unknown: time limit {time_limit:g} s reached (during {exc.stage})"
    extra = {"projected_crossings": diagram.n_crossings, "min_distance": real.min_distance}
    return Identification.of(named, status, len(real.curves), diagram.linking_matrix().tolist(), extra)


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
