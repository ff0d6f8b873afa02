"""Knot and link identification of a labelled scaffold (extra ``[knots]``).

Two paths give the diagram that is named.  By default (``method: "combinatorial"``) the
design's PD code is assembled from its labels and named by its invariant key first
(:mod:`lkspace.knots.from_labels`): milliseconds when the key was judged before.  The
geometric path (``geometric=True``, and wherever the first does not apply: null
edge-sides, geometry parameters given, no generic template direction) realizes the
strands (:func:`lkspace.geometry.realization.realize`), projects them
(:func:`lkspace.knots.diagram.project`) and names the projection.  Either way a diagram
is named by :func:`lkspace.knots.naming.name_pd` (spherogram ``simplify('global')``, then
the tables of :mod:`lkspace.knots.tables`).

Naming.  The Jones polynomial (regina, no Sage) of the simplified diagram, evaluated
exactly at ``sqrt(t) = 2/3`` and ``3/2`` (its mirror), is looked up in the KnotInfo
(knots up to 13 crossings) and LinkInfo (links up to 11 crossings, every orientation)
tables of ``database_knotinfo``.  Candidates are narrowed by the HOMFLY-PT polynomial
(regina, computed on our diagram and on the table's own PD code, so conventions agree)
and by SnapPy's ``identify()`` of the exterior.  A single remaining table entry is
accepted only if the hyperbolic volume agrees (zero for torus and satellite knots and
links, which ``identify()`` cannot name); otherwise ``name`` is ``None`` and the
invariants are returned.  Names: ``"0_1"``, Rolfsen ``"3_1"``..., Thistlethwaite
``"L2a1"``..., a split link ``"split: 0_1 + 3_1"``; ``mirror`` says whether the structure
is the table diagram's mirror image (``None`` when the knot or link equals its mirror as
far as HOMFLY-PT tells).  KnotInfo's ``3_1`` is the right-handed (positive) trefoil.
"""

from __future__ import annotations

import time
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike

from ..errors import DiagramError, LkspaceError, TooLargeError, UsageError
from ..geometry.params import GeometryParams
from ..model.scaffold import Scaffold
from ..runtime.progress import Step, task
from ..strands.tracing import Trace, trace
from .budget import MAX_CROSSINGS, TIME_LIMIT, TimeLimitReached, twist_crossings
from .diagram import project, project_generic
from .identification import Identification, Json, Naming
from .naming import name_in_time, name_pd, named_as_split, status_of


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
    geometric: bool = False,
) -> Identification:
    """Knot or link type of a scaffold labelled by twist ``labels`` (extra ``[knots]``).

    Parameters
    ----------
    scaffold : Scaffold
        A finite scaffold (periodic ones are refused, :func:`check_identifiable`);
        ``lkspace.identify`` also takes a path or a built-in name (:func:`lkspace.load`).
    labels, nulls : as for :func:`lkspace.trace`
    params : GeometryParams, optional
        Realization parameters (they imply the geometric path).
    seed : int
        Seed of the generic projection.
    time_limit : float or None
        Seconds for the whole identification (default
        :data:`~lkspace.knots.budget.TIME_LIMIT`); past it the status is ``unknown: time
        limit ... reached`` with the invariants known so far.  ``None`` or 0: no limit.
    geometric : bool
        Realize the strands and project them (seconds) instead of assembling the diagram
        from the labels (milliseconds once its key is known); the module docstring says
        where the combinatorial path does not apply.  ``details["method"]`` says which
        path ran, ``details["pd_code"]`` holds the PD code it named.

    Raises
    ------
    TooLargeError
        When the twists alone would make more than
        :data:`~lkspace.knots.budget.MAX_CROSSINGS` crossings (checked before any diagram).

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
        if not (geometric or params is not None or tr.nulls.any()):
            from .from_labels import identify_labels

            step.note("diagram from the labels")
            try:
                return identify_labels(scaffold, tr.labels, seed, time_limit, step)
            except DiagramError:
                pass  # no generic direction for the template: the realized strands have one
        return _identify_geometric(scaffold, tr, nulls, params, seed, time_limit, t0, step)


def _identify_geometric(
    scaffold: Scaffold,
    tr: Trace,
    nulls: ArrayLike | None,
    params: GeometryParams | None,
    seed: int,
    time_limit: float | None,
    t0: float,
    step: Step,
) -> Identification:
    """Identify on the geometric path (:func:`identify`): realize the traced strands, project them, name the projection."""
    from ..geometry.params import RealizeOptions
    from ..geometry.realization import realize

    step.note("realizing")
    # the construction polylines (smoothing off unless asked): isotopic to the smoothed strands, cheaper
    real = realize(scaffold, tr.labels, nulls, params or GeometryParams(smooth=False), options=RealizeOptions(trace=tr))
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
            named = named_as_split(named)
        except TimeLimitReached as exc:
            status = f"unknown: time limit {time_limit:g} s reached (during {exc.stage})"
    extra: dict[str, Json] = {
        "projected_crossings": diagram.n_crossings,
        "min_distance": real.min_distance,
        "method": "geometric",
        "pd_code": [list(map(int, x)) for x in diagram.pd],
    }
    return Identification.of(named, status, len(real.curves), diagram.linking_matrix().tolist(), extra)
