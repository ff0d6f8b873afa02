"""Inverse design: twist labels with exactly N strand components (CP-SAT).

The question: given a scaffold, a set of allowed labels per edge and a target N, find
labels ``t`` whose traced structure has exactly N components (``lkspace solve``), or
prove that none exists.  :func:`build_model` builds the CP-SAT model here;
:func:`~lkspace.inverse.pipeline.solve` runs it, after the linear-time constructions of
:mod:`lkspace.inverse.constructive` when they can answer, and re-traces every solution.

Formulation
-----------
**Nodes.**  The strand model of :mod:`lkspace.strands.ports` is a 2-regular graph on ports:
corner links (fixed) alternate with edge links (set by the labels).  Contract every corner
link: node ``c`` is face corner ``c`` (its ports ``2c`` and ``2 prev(c) + 1``).  Every node
has two ports and every port exactly one edge link, so the edge links form a 2-regular
multigraph on the corners whose cycles are the components.

**Residues.**  Only ``t mod K`` matters on an edge of degree K.  Edge ``e`` gets one boolean
``x[e, r]`` per residue ``r`` reachable by its allowed labels, exactly one true.  Residue
``r`` creates the K links "slot i at end a -- slot (i + r) mod K at end b": the literal of
each such link *is* ``x[e, r]``.  The label reported for ``r`` is the cheapest allowed
label in that class (see ``objective``).

**Contraction.**  An edge with a single reachable residue (boundary edges, ``K = 1``;
``--fix``; label sets that pin the class) contributes fixed links.  The fixed links cut the
corners into paths and closed cycles; a closed cycle is a component in every design
(counted as the constant ``n_fixed_cycles``), and a path becomes one **super-node** with its
two free end ports.  The model lives on the M super-nodes, so boundaries and fixed edges
cost nothing.  We need exactly ``N' = N - n_fixed_cycles`` cycles among them.

**Upper bound (routes).**  ``AddMultipleCircuit`` on the super-nodes plus a depot 0: arcs
``u -> v`` and ``v -> u`` for every pair joined by some candidate link, each arc implying
that one of those links is active; depot arcs ``0 -> u`` ("a route starts at u") and
``u -> 0`` are free.  Every super-node lies on exactly one route and consecutive nodes of a
route are joined by an active link, so each route lies inside one component and each
component holds at least one route: #components <= #routes.  We require exactly N' routes.

**Lower bound (labelling).**  An integer ``L[u] in 0..u`` per super-node, equal on the two
ends of every active link (``x => L[u] == L[v]``), and ``root[u] <=> L[u] == u``.  On a
component C all labels are one value ``l <= min(C)``, and a node u of C can be a root only
if ``u = l``, i.e. ``u = min(C)``: at most one root per component, so #components >=
#roots.  We require exactly N' roots and tie them to the routes, ``start[u] == root[u]``
(skipped when N' = 1, where #components >= 1 holds anyway; the single route then starts at
node 0).

**Exactness.**  Together: N' <= #components <= N'.  Conversely every design with exactly
N' components satisfies the model: label each component by its minimum node, make that
node the root, and run each component once around as a route starting at its root (a
component of one super-node whose two ends are linked to each other is the route
``0 -> u -> 0``).  So the model is feasible exactly when a design exists, and a time-out
says ``unknown``, never ``infeasible``.  Every solution is re-traced by
:func:`lkspace.trace` anyway; a mismatch raises :class:`SolveVerificationError`.

**Redundant cut.**  Residue r on an edge of degree K differs from residue 0 by
K - gcd(K, r) swaps of two edge links (2-opt moves); each changes the number of components
by at most one, and all-zero labels leave one component per face.  So
``sum_e (K_e - gcd(K_e, r_e)) >= |F - N|``: implied by the model, added for the LP bound.

**Objective.**  ``min-abs`` minimizes the total ``|t|``, ``min-nonzero`` the number of
non-zero labels; each is linear in the residue booleans because the cheapest label of
each residue class is fixed in advance.  Distinct solutions (``count``) differ in residues,
that is, in how the strands connect; excluding one (and its images under a symmetry
group) is a clause over the residue booleans (solve-and-exclude, never a census).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, TypeAlias

import numpy as np
import scipy.sparse
import scipy.sparse.csgraph

from ..errors import LabelError
from ..model.scaffold import Scaffold
from ..strands.ports import port_model
from ..words import plural
from .query import Query, SolveStatus, allowed_labels, label_cost, representatives

if TYPE_CHECKING:
    from ortools.sat.python import cp_model

    RouteVars: TypeAlias = tuple[
        list[cp_model.IntVar], list[cp_model.IntVar], dict[tuple[int, int], cp_model.IntVar], list[cp_model.IntVar]
    ]
    """``(starts, ends, arcs, labels)``: the route and labelling variables of :func:`build_model`."""
    PairLits: TypeAlias = dict[tuple[int, int], list[cp_model.BoolVarT]]
    """Per pair of free paths ``(a, b)``, ``a < b``, the residue literals linking them."""


@dataclass(eq=False)
class DesignModel:
    """A CP-SAT model of one query, built apart from solving it (:func:`build_model`).

    Attributes
    ----------
    model : ortools.sat.python.cp_model.CpModel or None
        ``None`` when the query is decided without search (see ``decided``).
    decided : str or None
        ``"infeasible"`` with ``reason`` when the query has no design before search.
    residue_literals : dict of int -> list of (residue, literal)
        Free edges only.
    choices : list of dict of int -> int
        Per edge, residue -> reported label.
    fixed_residues : (n_edges,) int64
        Residue of every edge with one choice, -1 for free edges.
    n_fixed_cycles : int
        Components made of fixed links only.
    n_nodes : int
        Super-nodes M of the model.
    """

    scaffold: Scaffold
    query: Query
    model: cp_model.CpModel | None
    residue_literals: dict[int, list[tuple[int, cp_model.BoolVarT]]]
    choices: list[dict[int, int]]
    fixed_residues: np.ndarray
    n_fixed_cycles: int
    n_nodes: int
    decided: SolveStatus | None = None
    reason: str = ""
    links: list[tuple[int, int, int, int]] = field(default_factory=list)
    route_vars: RouteVars = field(default_factory=lambda: ([], [], {}, []))

    def labels_of(self, residues: np.ndarray) -> np.ndarray:
        """Return the reported labels ``(n_edges,) int64`` of a residue vector.

        Under ``query.invariant_orbits`` each edge copies its orbit's first edge (times
        ``rel``), so the labels are fixed by the subgroup, not just their residues.
        """
        labels = np.array([self.choices[e][int(r)] for e, r in enumerate(residues)], np.int64)
        if self.query.invariant_orbits is not None:
            orbit, rel = self.query.invariant_orbits.orbit, self.query.invariant_orbits.rel
            first = np.unique(orbit, return_index=True)[1]
            labels = rel * labels[first[orbit]]
        return labels

    def residues_from(self, value: Callable[[cp_model.BoolVarT], bool]) -> np.ndarray:
        """Return the residue vector ``(n_edges,) int64`` of a solved model (``value(literal) -> bool``)."""
        res = self.fixed_residues.copy()
        for e, lits in self.residue_literals.items():
            res[e] = next(r for r, lit in lits if value(lit))
        return res

    def exclude(self, residues: np.ndarray) -> None:
        """Forbid the residue vector ``residues`` (a no-good clause over the free edges)."""
        fixed = self.fixed_residues >= 0
        if np.any(residues[fixed] != self.fixed_residues[fixed]):
            return  # not a design of this query: nothing to exclude
        clause = []
        for e, lits in self.residue_literals.items():
            match = [lit.Not() for r, lit in lits if r == residues[e]]
            if not match:
                return
            clause += match
        assert self.model is not None, "exclude: the query was decided without a model"
        self.model.add_bool_or(clause)  # empty when nothing is free: the model becomes infeasible

    def hint(self, residues: np.ndarray) -> None:
        """Give CP-SAT a complete starting point: a design and its routes and labels.

        Each component of the design is walked once from its smallest super-node (its root
        and label) along the active links, which is exactly the assignment of the proof in
        the module docstring.
        """
        model = self.model
        assert model is not None, "hint: the query was decided without a model"
        model.clear_hints()
        for e, lits in self.residue_literals.items():
            for r, lit in lits:
                if lit.Index() >= 0:  # the second of two choices is the negation of the first
                    model.add_hint(lit, bool(r == residues[e]))
        starts, ends, arcs, labels = self.route_vars
        adjacency: list[list[tuple[int, int]]] = [[] for _ in range(self.n_nodes)]
        active = [(a, b) for a, b, e, r in self.links if residues[e] == r]
        for lid, (a, b) in enumerate(active):
            adjacency[a].append((lid, b))
            adjacency[b].append((lid, a))
        root_of = np.full(self.n_nodes, -1, np.int64)
        lasts: set[int] = set()
        used: set[tuple[int, int]] = set()
        for root in range(self.n_nodes):
            if root_of[root] >= 0:
                continue
            cur, came_by = root, -1
            root_of[root] = root
            while True:
                lid, nxt = next((x for x in adjacency[cur] if x[0] != came_by), (-1, root))
                if nxt == root or root_of[nxt] >= 0:
                    break
                used.add((cur, nxt))
                root_of[nxt] = root
                cur, came_by = nxt, lid
            lasts.add(cur)
        for u in range(self.n_nodes):
            model.add_hint(starts[u], bool(root_of[u] == u))
            model.add_hint(ends[u], u in lasts)
        for (tail, head), var in arcs.items():
            model.add_hint(var, (tail, head) in used)
        for u, var in enumerate(labels):
            model.add_hint(var, int(root_of[u]))


def _fixed_structure(scaffold: Scaffold, fixed_residues: np.ndarray) -> tuple[np.ndarray, np.ndarray, int, int]:
    """Contract fixed links: super-node of every corner and the number of closed fixed cycles."""
    pm = port_model(scaffold)
    n = scaffold.n_corners
    node_of_port = np.empty(2 * n, np.int64)
    node_of_port[0::2] = np.arange(n)
    node_of_port[1::2] = scaffold.corner_next
    degrees = scaffold.edge_degrees
    slot_fixed = fixed_residues[pm.slot_edge] >= 0
    k = degrees[pm.slot_edge]
    target = pm.edge_starts[pm.slot_edge] + (pm.slot_index + np.maximum(fixed_residues[pm.slot_edge], 0)) % k
    u = node_of_port[pm.port_a[slot_fixed]]
    v = node_of_port[pm.port_b[target[slot_fixed]]]
    graph = scipy.sparse.coo_matrix((np.ones(len(u)), (u, v)), shape=(n, n))
    n_comp, comp = scipy.sparse.csgraph.connected_components(graph, directed=False)
    size = np.bincount(comp, minlength=n_comp)
    links = np.bincount(comp[u], minlength=n_comp)
    closed = links == size
    super_id = np.cumsum(~closed) - 1
    return node_of_port, super_id[comp], int(closed.sum()), int((~closed).sum())


def build_model(scaffold: Scaffold, query: Query, deadline: float | None = None) -> DesignModel:
    """Build the CP-SAT model of ``query`` on ``scaffold`` (see the module docstring).

    Past ``deadline`` (a ``time.perf_counter()`` value) building stops: ``decided`` is
    then ``"unknown"`` and ``model`` is ``None``.

    Examples
    --------
    >>> from lkspace import load
    >>> m = build_model(load("cube"), Query(1, label_set=np.array([-1, 1])))  # odd everywhere
    >>> m.n_nodes, m.n_fixed_cycles, m.decided
    (0, 4, 'infeasible')
    >>> m = build_model(load("cube"), Query(2, label_set=np.array([0, 1])))
    >>> m.n_nodes, m.n_fixed_cycles, m.decided
    (24, 0, None)
    """
    from ortools.sat.python import cp_model

    dm, structure = _presolve(scaffold, query)
    if structure is None:
        return dm
    node_of_port, super_of, m, need = structure
    dm.model = cp_model.CpModel()
    found = _edge_literals(dm, node_of_port, super_of, deadline)
    if found is None:
        return dm
    pair_lits, objective = found
    if query.invariant_orbits is not None:
        _tie_orbits(dm, query.invariant_orbits.orbit, query.invariant_orbits.rel)
    if not _add_routes(dm, pair_lits, m, need, deadline):
        return dm
    _add_swap_cut(dm)
    if objective:
        dm.model.minimize(sum(objective))
    return dm


def _presolve(scaffold: Scaffold, query: Query) -> tuple[DesignModel, tuple[np.ndarray, np.ndarray, int, int] | None]:
    """Return the model's residue choices and fixed structure (``node_of_port``, ``super_of``, the ``m`` free paths, the ``need`` ed components; ``None``: decided already)."""
    if scaffold.nulls is not None and np.any(scaffold.nulls):
        raise LabelError(f"{scaffold.name}: solve does not handle null edge-sides; remove them from the scaffold")
    allowed = allowed_labels(scaffold, query)
    degrees = scaffold.edge_degrees
    choices = [representatives(a, int(k), query.objective) for a, k in zip(allowed, degrees, strict=True)]
    fixed = np.array([next(iter(c)) if len(c) == 1 else -1 for c in choices], np.int64)
    empty = [e for e, c in enumerate(choices) if not c]
    dm = DesignModel(scaffold, query, None, {}, choices, fixed, 0, 0)
    if empty:
        dm.decided = "infeasible"
        dm.reason = f"edge {scaffold.edge_name(empty[0])} has no allowed label"
        return dm, None
    node_of_port, super_of, n_fixed_cycles, m = _fixed_structure(scaffold, fixed)
    dm.n_fixed_cycles, dm.n_nodes = n_fixed_cycles, m
    need = int(query.components) - n_fixed_cycles
    if m == 0 and need != 0 or m > 0 and not 1 <= need <= m:
        dm.decided = "infeasible"
        dm.reason = (
            f"the allowed labels fix every edge mod K: always {plural(n_fixed_cycles, 'component')}"
            if m == 0
            else f"{plural(n_fixed_cycles, 'component is', 'components are')} fixed and "
            f"{plural(m, 'free path remains', 'free paths remain')}: "
            f"only {n_fixed_cycles + 1}..{n_fixed_cycles + m} components are possible"
        )
        return dm, None
    return dm, (node_of_port, super_of, m, need)


def _edge_literals(
    dm: DesignModel, node_of_port: np.ndarray, super_of: np.ndarray, deadline: float | None
) -> tuple[PairLits, list[cp_model.LinearExprT]] | None:
    """Add a literal per residue choice of each free edge; return those joining each pair of free paths and the objective's terms (``None``: past ``deadline``)."""
    model, scaffold, query = dm.model, dm.scaffold, dm.query
    assert model is not None
    degrees = scaffold.edge_degrees
    pm = port_model(scaffold)
    pair_lits: PairLits = {}
    objective: list[cp_model.LinearExprT] = []
    for done, e in enumerate(np.flatnonzero(dm.fixed_residues < 0).tolist()):
        if done % 256 == 0 and _late(dm, deadline):
            return None
        opts = dm.choices[e]
        k = int(degrees[e])
        start = int(pm.edge_starts[e])
        lits: list[tuple[int, cp_model.BoolVarT]] = []
        for j, r in enumerate(opts):
            if j == 1 and len(opts) == 2:
                lit = lits[0][1].Not()
            else:
                lit = model.new_bool_var(f"x{e}_{r}")
            lits.append((r, lit))
            cost = int(label_cost(np.array([opts[r]]), query.objective)[0])
            if cost:
                objective.append(cost * lit)
            for i in range(k):
                a = super_of[node_of_port[pm.port_a[start + i]]]
                b = super_of[node_of_port[pm.port_b[start + (i + r) % k]]]
                dm.links.append((int(a), int(b), e, r))
                if a != b:
                    pair_lits.setdefault((min(a, b), max(a, b)), []).append(lit)
        if len(opts) > 2:
            model.add_exactly_one([lit for _, lit in lits])
        dm.residue_literals[e] = lits
    return pair_lits, objective


def _add_routes(dm: DesignModel, pair_lits: PairLits, m: int, need: int, deadline: float | None) -> bool:
    """Add the circuit over the ``m`` free paths and the labels counting ``need`` components (False: past ``deadline``)."""
    model = dm.model
    assert model is not None
    arcs = []
    starts = [model.new_bool_var(f"start{u}") for u in range(m)]
    ends = [model.new_bool_var(f"end{u}") for u in range(m)]
    arc_vars: dict[tuple[int, int], cp_model.IntVar] = {}
    label_vars: list[cp_model.IntVar] = []
    dm.route_vars = (starts, ends, arc_vars, label_vars)
    for u in range(m):
        arcs += [(0, u + 1, starts[u]), (u + 1, 0, ends[u])]
    for (a, b), joining in pair_lits.items():
        for tail, head in ((a, b), (b, a)):
            arc = arc_vars[(tail, head)] = model.new_bool_var(f"arc{tail}_{head}")
            if len(joining) == 1:
                model.add_implication(arc, joining[0])
            else:
                model.add_bool_or(joining).only_enforce_if(arc)
            arcs.append((tail + 1, head + 1, arc))
    if _late(dm, deadline):
        return False
    if m:
        model.add_multiple_circuit(arcs)
        model.add(sum(starts) == need)
    if need == 1 and m:
        model.add(starts[0] == 1)
    elif need > 1:
        label = [model.new_int_var(0, u, f"L{u}") for u in range(m)]
        label_vars.extend(label)
        for (a, b), joining in pair_lits.items():
            for lit in {x.Index(): x for x in joining}.values():
                model.add(label[a] == label[b]).only_enforce_if(lit)
        for u in range(m):
            model.add(label[u] == u).only_enforce_if(starts[u])
            if u:
                model.add(label[u] <= u - 1).only_enforce_if(starts[u].Not())
            else:
                model.add(starts[0] == 1)
    return True


def _add_swap_cut(dm: DesignModel) -> None:
    """Add the redundant cut: residue r on an edge of degree K is K - gcd(K, r) swaps (2-opt moves)
    from residue 0, each changing the component count by at most one, and all-zero labels
    give one component per face; so the total swap distance is at least |F - N|.
    """  # noqa: D205
    assert dm.model is not None
    degrees = dm.scaffold.edge_degrees
    base = sum(int(k) - math.gcd(int(k), int(r)) for k, r in zip(degrees, dm.fixed_residues, strict=True) if r > 0)
    distance = [
        (int(degrees[e]) - math.gcd(int(degrees[e]), r)) * lit
        for e, lits in dm.residue_literals.items()
        for r, lit in lits
        if r
    ]
    gap = abs(dm.scaffold.n_faces - int(dm.query.components)) - base
    if distance and gap > 0:
        dm.model.add(sum(distance) >= gap)


def _tie_orbits(dm: DesignModel, orbit: np.ndarray, rel: np.ndarray) -> None:
    """Residue of edge ``e`` = ``rel[e]`` x residue of its orbit's first edge (``solve --invariant``)."""
    assert dm.model is not None
    first = np.unique(orbit, return_index=True)[1]
    degrees = dm.scaffold.edge_degrees
    for e, lits in dm.residue_literals.items():
        e0 = int(first[orbit[e]])
        if e0 == e or e0 not in dm.residue_literals:
            continue  # a fixed first edge has one residue: so has e (their allowed labels match)
        mine = dict(lits)
        for r, lit in dm.residue_literals[e0]:
            other = mine[int(rel[e] * r) % int(degrees[e])]
            dm.model.add_implication(lit, other)
            dm.model.add_implication(other, lit)


def _late(dm: DesignModel, deadline: float | None) -> bool:
    """Mark ``dm`` undecided for lack of time (``decided = "unknown"``) once ``deadline`` has passed."""
    if deadline is None or time.perf_counter() <= deadline:
        return False
    dm.model, dm.decided, dm.reason = None, "unknown", "the time limit ran out while the CP-SAT model was built"
    return True
