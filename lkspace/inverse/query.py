"""What a design must satisfy: :class:`Query`, and the labels each edge may then carry."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Literal, TypeAlias, get_args

import numpy as np

from ..errors import LabelError
from ..model.scaffold import Scaffold

if TYPE_CHECKING:
    from ..symmetry.edge_orbits import SignedOrbits

Objective: TypeAlias = Literal["min-abs", "min-nonzero"]
"""What a solve minimizes: the sum of ``|t|``, or the number of non-zero labels."""
OBJECTIVES: tuple[Objective | None, ...] = (None, *get_args(Objective))
SolveStatus: TypeAlias = Literal["optimal", "feasible", "infeasible", "unknown"]
"""A solve's answer: optimal or feasible designs, none (proved), or time ran out before either."""


@dataclass(frozen=True)
class Query:
    """What a design must satisfy.

    Parameters
    ----------
    components : int
        Exact number of strand components N.
    label_set : (n_labels,) int64
        Labels the design may use (default ``-2..2``).
    no_zero : bool
        Forbid ``t = 0``.
    fixes : dict of int -> int
        Edge -> label it must carry (may lie outside ``labels``).
    parities : dict of int -> int
        Edge -> required parity of its label (0 even, 1 odd).
    objective : None, ``"min-abs"`` or ``"min-nonzero"``
    invariant_orbits : SignedOrbits, optional
        Only designs fixed by a subgroup (``solve(invariant=...)``): the subgroup's signed edge
        orbits (:func:`~lkspace.symmetry.edge_orbits.signed_components`); every edge ``e``
        carries ``rel[e]`` times the label of its orbit's first edge.
    """

    components: int
    label_set: np.ndarray = field(default_factory=lambda: np.arange(-2, 3))
    no_zero: bool = False
    fixes: dict[int, int] = field(default_factory=dict)
    parities: dict[int, int] = field(default_factory=dict)
    objective: Objective | None = None
    invariant_orbits: SignedOrbits | None = None

    def __post_init__(self) -> None:
        check_objective(self.objective)
        if int(self.components) < 1:
            raise LabelError(f"components {self.components}: need at least 1", parameter="components")


def check_objective(objective: str | None) -> Objective | None:
    """Return ``objective`` if it is one of :data:`OBJECTIVES`; raise :class:`~lkspace.errors.LabelError` otherwise."""
    if objective not in OBJECTIVES:
        raise LabelError(
            f"objective {objective!r}: expected one of min-abs, min-nonzero or none", parameter="objective"
        )
    return objective


def label_cost(labels: np.ndarray, objective: Objective | None) -> np.ndarray:
    """Objective cost of each label ``(n,) int64`` (all 0 without objective)."""
    labels = np.asarray(labels, np.int64)
    if objective == "min-abs":
        return np.abs(labels)
    if objective == "min-nonzero":
        return (labels != 0).astype(np.int64)
    return np.zeros(len(labels), np.int64)


def allowed_labels(scaffold: Scaffold, query: Query) -> list[np.ndarray]:
    """Labels each edge may carry after ``label_set``, ``no_zero``, ``fixes`` and ``parities``.

    Returns a list of ``n_edges`` sorted ``(k,) int64`` arrays; an empty one means no
    design exists.  A fix that contradicts ``no_zero`` or a parity raises
    :class:`~lkspace.errors.LabelError` (the query contradicts itself).
    """
    base = np.unique(np.asarray(query.label_set, np.int64))
    if query.no_zero:
        base = base[base != 0]
    out = [base] * scaffold.n_edges
    for option, edges in (("fix", query.fixes), ("parity", query.parities)):
        bad = [e for e in edges if not 0 <= e < scaffold.n_edges]
        if bad:
            raise LabelError(f"{option} on edge {bad[0]}: out of range 0..{scaffold.n_edges - 1}")
    if any(p not in (0, 1) for p in query.parities.values()):
        raise LabelError("parities must be 0 (even) or 1 (odd)")
    for e, t in query.fixes.items():
        name = scaffold.edge_name(e)
        if query.no_zero and t == 0:
            raise LabelError(f"fixes {name}=0 contradicts `no_zero`", parameter="fixes")
        if e in query.parities and t % 2 != query.parities[e]:
            parity = "odd" if query.parities[e] else "even"
            raise LabelError(f"fixes {name}={t} contradicts `parities` {name}={parity}", parameter="fixes")
        out[e] = np.array([t], np.int64)
    for e, p in query.parities.items():
        out[e] = out[e][out[e] % 2 == p]
    return out if query.invariant_orbits is None else symmetric_allowed(out, query.invariant_orbits)


def symmetric_allowed(allowed: list[np.ndarray], orbits: SignedOrbits) -> list[np.ndarray]:
    """Restrict per-edge ``allowed`` labels to fixed assignments: ``rel[e] * u`` with one ``u`` per orbit.

    ``u`` must give an allowed label on every edge of its orbit (and be 0 on a forced-zero orbit).
    """
    orbit, rel, forced_zero = orbits.orbit, orbits.rel, orbits.forced_zero
    out = list(allowed)
    for o in range(len(forced_zero)):
        edges = np.flatnonzero(orbit == o)
        options = allowed[edges[0]]
        for e in edges[1:].tolist():
            options = np.intersect1d(options, rel[e] * allowed[e])
        if forced_zero[o]:
            options = options[options == 0]
        for e in edges.tolist():
            out[e] = np.sort(rel[e] * options)
    return out


def representatives(labels: np.ndarray, k: int, objective: Objective | None) -> dict[int, int]:
    """Residue ``r`` -> the label reported for it: cheapest, then smallest ``|t|``, then positive."""
    best: dict[int, tuple[tuple[int, int, bool], int]] = {}
    costs = label_cost(labels, objective)
    for t, c in zip(labels.tolist(), costs.tolist(), strict=True):
        key = (c, abs(t), t < 0)
        r = t % k
        if r not in best or key < best[r][0]:
            best[r] = (key, t)
    return {r: v[1] for r, v in sorted(best.items())}


def cheapest_label(labels: np.ndarray, objective: Objective | None) -> tuple[int, int] | None:
    """Return ``(cost, label)`` of the cheapest label, ties to small ``|t|`` then positive; ``None`` if empty."""
    if len(labels) == 0:
        return None
    cost = label_cost(labels, objective)
    key = np.lexsort((labels < 0, np.abs(labels), cost))[0]
    return int(cost[key]), int(labels[key])
