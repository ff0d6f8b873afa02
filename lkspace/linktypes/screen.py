"""One design against a goal: cheap filters first, full identification only for survivors.

The filters, each a proof that the design is *not* the target:

1. **linking numbers** of the realized curves (exact, from the projection's crossing
   signs), compared up to renumbering (:func:`lkspace.linktypes.linking.matches`);
2. **split**: a component that crosses nothing in the projection makes a link split;
3. **crossings**: a projection with fewer crossings than the target's crossing number;
4. **Jones polynomial** of the simplified diagram at ``sqrt t = 2/3``, which must equal
   the target's (or its mirror's, or another orientation's).

A design passing all four is identified (:func:`lkspace.knots.recognition.identify`, with
its time limit) and compared by name and chirality (:func:`lkspace.linktypes.names.judge`).
A linking-matrix goal needs only the first filter: its verdict is exact.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import LkspaceError
from ..geometry.realization import realize
from ..knots.diagram import Diagram, project_generic
from ..knots.naming import one_based
from ..knots.recognition import identify
from ..knots.tables import JONES_POINT, knot_modules, laurent_value
from ..model.scaffold import Scaffold
from .linking import matches
from .names import LinkType, Verdict, judge

if TYPE_CHECKING:
    from ..knots.batch import Namer
    from ..knots.key_names import KeyCache

SIMPLIFY_MAX_CROSSINGS = 400
"""Projections with more crossings skip the simplify-and-Jones filter (identification has time budgets)."""

JONES_MAX_CROSSINGS = 40
"""Simplified diagrams with more crossings skip the Jones filter."""


def type_labels(scaffold: Scaffold, labels: np.ndarray) -> np.ndarray:
    """Return ``labels`` with the edges of degree 1 set to 0: a design of the same knot or link type.

    On an edge of degree 1 a lone strand turns ``t`` times about the edge's axis, inside
    a thin cylinder around the edge that no other strand enters: a one-strand braid,
    isotopic (ends fixed, inside the cylinder) to the untwisted arc.  So the type depends
    on the labels of the edges of degree >= 2 only.

    Examples
    --------
    >>> from lkspace import load
    >>> type_labels(load("book:2"), np.array([[2, 1, -1, 0, 1, 1, 2]])).tolist()
    [[2, 0, 0, 0, 0, 0, 0]]
    """
    out = np.array(labels, np.int64, copy=True)
    out[..., np.asarray(scaffold.edge_degrees) == 1] = 0
    return out


@dataclass(frozen=True, eq=False)
class Goal:
    """What the search wants: a type (``target``), a linking matrix (``linking``), or both."""

    components: int
    target: LinkType | None = None
    linking: np.ndarray | None = None
    signed: bool = False

    @property
    def label(self) -> str:
        """Short text for progress lines and messages."""
        if self.target is not None:
            return self.target.label
        return f"linking matrix {np.asarray(self.linking).tolist()}"


@dataclass(frozen=True)
class Screening:
    """One design judged against a goal.

    ``verdict``: ``"match"``, ``"other"`` or ``"undetermined"``; ``reason``: the filter
    that decided, or ``"identified"``; ``linking_matrix``: of the projection (``None``:
    not realized).  When identified (``identified``), what identify said: ``name``,
    ``chiral_name``, ``mirror``, ``table``, ``status``, ``crossings``.
    """

    verdict: Verdict
    reason: str
    linking_matrix: list[list[int]] | None = None
    identified: bool = False
    name: str | None = None
    chiral_name: str | None = None
    mirror: bool | None = None
    table: str | None = None
    status: str | None = None
    crossings: int | None = None

    def judged(self, target: LinkType, ident: dict[str, Any]) -> Screening:
        """Return this screening completed by an identification (``Identification.to_dict()`` or a batch row)."""
        return replace(
            self,
            verdict=judge(target, ident),
            reason="identified",
            identified=True,
            name=ident.get("name"),
            chiral_name=ident.get("chiral_name"),
            mirror=ident.get("mirror"),
            table=ident.get("table"),
            status=ident.get("status"),
            crossings=ident.get("crossings"),
        )


def _jones_value(diagram: Diagram) -> tuple[int, Any] | None:
    """``(simplified crossings, Jones at 2/3)``, or ``None`` when the diagram is too big for the filter."""
    if diagram.n_crossings > SIMPLIFY_MAX_CROSSINGS:
        return None
    if not diagram.pd:
        return 0, 1
    spherogram, regina, _ = knot_modules()
    link = spherogram.Link(diagram.pd)
    link.simplify("global")
    pd = one_based(link.PD_code())
    if len(pd) > JONES_MAX_CROSSINGS:
        return None
    if not pd:
        return 0, 1
    return len(pd), laurent_value(regina.Link.fromPD(pd).jones(), JONES_POINT)


def screen(
    scaffold: Scaffold, labels: np.ndarray, goal: Goal, seed: int = 0, time_limit: float | None = 60.0
) -> Screening:
    """Judge one design (closed strands, ``goal.components`` of them) against ``goal``."""
    try:
        real = realize(scaffold, labels)
        diagram = project_generic(real.curves, seed)
    except LkspaceError as exc:
        return Screening("undetermined", f"not realized: {exc}")
    lm = diagram.linking_matrix()
    matrix = lm.tolist()
    if goal.linking is not None and not matches(lm, goal.linking, goal.signed):
        return Screening("other", "linking matrix", matrix)
    target = goal.target
    if target is None:
        return Screening("match", "linking matrix", matrix)
    if target.linking is not None and not matches(lm, target.linking):
        return Screening("other", "linking numbers", matrix)
    if diagram.free_components and goal.components > 1:
        return Screening("other", "split", matrix)
    if diagram.n_crossings < target.crossings:
        return Screening("other", "crossings", matrix)
    jones = _jones_value(diagram)
    if jones is not None and jones[1] not in target.fingerprints:
        return Screening("other", "Jones polynomial", matrix)
    try:
        ident = identify(scaffold, labels, seed=seed, time_limit=time_limit).to_dict()
    except LkspaceError as exc:
        return Screening("undetermined", f"not identified: {exc}", matrix)
    return Screening("undetermined", "", matrix).judged(target, ident)


def screen_batch(
    scaffold: Scaffold,
    labels: np.ndarray,
    goal: Goal,
    seed: int,
    cache: KeyCache,
    namer: Namer,
    label_set: np.ndarray,
) -> list[Screening]:
    """Judge a batch of designs (``(n, n_edges)``, closed strands) against ``goal`` from their labels alone.

    First the determinant (:mod:`lkspace.knots.determinant`, modulo a prime: a
    difference is a proof, at a tenth of the Jones polynomial's cost), then the filters
    of :func:`screen` on each design's diagram from labels (:mod:`lkspace.knots.keyed`;
    the Jones polynomial compared modulo a prime, so a difference is a proof), then the survivors identified by key
    (:func:`lkspace.knots.batch.identify_chunk`) and judged.  Returns one verdict per row,
    as :func:`screen`.
    """
    from ..knots.batch import identify_chunk
    from ..knots.keyed import jones_residue, keys_of

    target = goal.target
    verdicts = [Screening("other", "determinant") for _ in range(len(labels))]
    kept = np.arange(len(labels))
    if target is not None and target.determinant is not None:
        from ..knots.determinant import determinants_of, same_determinant

        kept = np.flatnonzero(same_determinant(determinants_of(scaffold, labels, seed, label_set), target.determinant))
    found = keys_of(scaffold, labels[kept], seed, label_set)
    residues = {jones_residue(v) for v in target.fingerprints} if target is not None else set()
    survivors: list[int] = []
    for k, d in enumerate(kept.tolist()):
        lm = np.asarray(found.linking_matrix(k), np.int64)
        matrix = lm.tolist()
        if goal.linking is not None and not matches(lm, goal.linking, goal.signed):
            verdicts[d] = Screening("other", "linking matrix", matrix)
        elif target is None:
            verdicts[d] = Screening("match", "linking matrix", matrix)
        elif target.linking is not None and not matches(lm, target.linking):
            verdicts[d] = Screening("other", "linking numbers", matrix)
        elif found.free[k] and goal.components > 1:
            verdicts[d] = Screening("other", "split", matrix)
        elif found.crossings[k] < target.crossings:
            verdicts[d] = Screening("other", "crossings", matrix)
        elif found.keyed[k] and int(found.jones_at[k]) not in residues:
            verdicts[d] = Screening("other", "Jones polynomial", matrix)
        else:
            survivors.append(d)
            verdicts[d] = Screening("undetermined", "", matrix)
    if survivors and target is not None:
        rows = identify_chunk(scaffold, labels[survivors], seed, cache, namer, label_set).rows()
        for d, row in zip(survivors, rows, strict=True):
            verdicts[d] = verdicts[d].judged(target, {**row, "name": row.get("knot_name")})
    return verdicts
