"""The fast path of :func:`~lkspace.inverse.pipeline.solve`: designs from spanning trees, no search.

On a scaffold whose edges all have degree K <= 2 (manifold or not orientable, with or
without boundary), label every edge even and each face is its own strand.  Making a
degree-2 edge odd swaps its two edge links (a 2-opt move): if the two faces' strands are
different components the move merges them into one.  So odd labels on the edges of a
spanning tree of the dual graph (faces joined by degree-2 edges) and even labels
elsewhere merge the F face strands into one, one tree edge at a time: a single component,
in time linear in the mesh.  (The same argument shows every single-component design needs
at least F - 1 odd edges, which bounds the objectives from below.)  Boundary edges
(K = 1) have one residue: any allowed label does.

Edges of degree K >= 3 and targets N > 1 generalize this (:func:`_greedy_designs`): a
residue coprime to K on an edge whose K faces lie on K different strands chains them into
one, and merging stops when N strands are left (a spanning forest).

Where the greedy order gets stuck (often on non-manifold scaffolds such as honeycomb
supercells), :mod:`lkspace.inverse.local_search` continues from its closest attempt.

Allowed labels may pin some edges odd (they must lie in the tree) or even (outside it);
Kruskal's algorithm with the pinned-odd edges first either finds such a tree or gives up,
and the caller falls back to CP-SAT.  Every design is re-traced by the caller.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse
import scipy.sparse.csgraph

from ..compiled.loops import UnionFind
from ..model.scaffold import Scaffold
from ..runtime.progress import Step
from ..words import plural
from .local_search import local_search
from .query import Query, allowed_labels, cheapest_label, label_cost


def spanning_designs(
    scaffold: Scaffold,
    query: Query,
    count: int = 1,
    seed: int = 0,
    time_budget: float = 5.0,
    deadline: float | None = None,
    step: Step | None = None,
) -> tuple[list[np.ndarray], bool]:
    """Construct up to ``count`` distinct designs with ``query.components`` strands, without search.

    One component on a K <= 2 scaffold: random dual spanning trees; otherwise (any K,
    N <= F components) greedy merging, :func:`_greedy_designs`, and where that gets stuck
    a local search from its closest attempt (:mod:`lkspace.inverse.local_search`, at most
    ``time_budget`` seconds).  Nothing runs past ``deadline`` (a ``time.perf_counter()``
    value); ``step`` (a :func:`lkspace.runtime.progress.task` step) gets the closest count so far.
    A mesh without two-face edges (one face, unwelded faces) has one strand per face
    whatever the labels: the answer is any allowed labelling when N = F, none otherwise.

    Returns
    -------
    designs : list of (n_edges,) int64
        Possibly fewer than ``count`` (none when the construction does not apply).
    optimal : bool
        Whether the first design meets the lower bound of ``query.objective``.
    """
    degrees = scaffold.edge_degrees
    if not 1 <= query.components <= scaffold.n_faces or scaffold.n_edges == 0:
        return [], False
    if scaffold.nulls is not None and np.any(scaffold.nulls):
        return [], False
    if degrees.max() > 2 or query.components > 1:
        partial: list[tuple[int, np.ndarray]] = []
        designs = _greedy_designs(scaffold, query, count, seed, partial, deadline, step)
        if deadline is not None:
            time_budget = min(time_budget, deadline - time.perf_counter())
        if len(designs) < count and partial and time_budget > 0:
            designs += local_search(scaffold, query, partial[0][1], count - len(designs), seed, time_budget, step)
        return designs, False
    choices = _parity_choices(scaffold, query)
    dual = None if choices is None else _dual_edges(scaffold, choices)
    if choices is None or dual is None:
        return [], False
    designs = _tree_designs(scaffold, choices, dual, count, seed, deadline)
    if not designs:
        return [], False
    return designs, _meets_lower_bound(designs[0], choices, dual, scaffold, query)


@dataclass(frozen=True, eq=False)
class ParityChoices:
    """The cheapest allowed label of each edge per parity (a K <= 2 scaffold).

    ``base (n_edges,)``: the even pick (on an edge of degree 1 any label), ``odd
    (n_edges,)``: the odd pick, ``costs (n_edges, 2)`` their costs and ``can (n_edges, 2)
    bool`` whether each exists, ``[even, odd]``.
    """

    base: np.ndarray
    odd: np.ndarray
    costs: np.ndarray
    can: np.ndarray


@dataclass(frozen=True, eq=False)
class DualEdges:
    """The edges of degree 2 (``two``), between faces ``f0`` and ``f1``.

    ``candidate``: may take an odd label (allowed, and not a loop); ``forced``: must (no
    even label); ``delta``: the cost of odd minus that of even.
    """

    two: np.ndarray
    f0: np.ndarray
    f1: np.ndarray
    candidate: np.ndarray
    forced: np.ndarray
    delta: np.ndarray


def _parity_choices(scaffold: Scaffold, query: Query) -> ParityChoices | None:
    """Return the cheapest label of each parity per edge, ``None`` if some edge has none."""
    degrees = scaffold.edge_degrees
    n_edges = scaffold.n_edges
    base = np.zeros(n_edges, np.int64)
    odd = np.zeros(n_edges, np.int64)
    costs = np.zeros((n_edges, 2), np.int64)
    can = np.zeros((n_edges, 2), bool)  # [even, odd]
    for e, labels in enumerate(allowed_labels(scaffold, query)):
        if degrees[e] == 1:
            pick = cheapest_label(labels, query.objective)
            if pick is None:
                return None
            costs[e, 0], base[e] = pick
            can[e, 0] = True
            continue
        for parity in (0, 1):
            pick = cheapest_label(labels[labels % 2 == parity], query.objective)
            if pick is not None:
                can[e, parity] = True
                costs[e, parity], chosen = pick
                (base if parity == 0 else odd)[e] = chosen
    if not can.any(axis=1).all():
        return None
    return ParityChoices(base, odd, costs, can)


def _dual_edges(scaffold: Scaffold, choices: ParityChoices) -> DualEdges | None:
    """Return the edges of degree 2 as the dual graph's edges, ``None`` if a loop must be odd."""
    two = np.flatnonzero(scaffold.edge_degrees == 2)
    sides = scaffold.radial.edge_sides
    starts = scaffold.radial.edge_starts
    f0 = scaffold.corner_face[sides[starts[two]]]
    f1 = scaffold.corner_face[sides[starts[two] + 1]]
    loop = f0 == f1
    can = choices.can
    if np.any(loop & ~can[two, 0]):
        return None
    candidate = can[two, 1] & ~loop
    delta = choices.costs[two, 1] - choices.costs[two, 0]
    return DualEdges(two, f0, f1, candidate, candidate & ~can[two, 0], delta)


def _tree_designs(
    scaffold: Scaffold, choices: ParityChoices, dual: DualEdges, count: int, seed: int, deadline: float | None
) -> list[np.ndarray]:
    """Up to ``count`` one-component designs: odd labels on random dual spanning trees, even elsewhere."""
    two, forced, candidate, delta = dual.two, dual.forced, dual.candidate, dual.delta
    rng = np.random.default_rng(seed)
    designs: list[np.ndarray] = []
    seen: set[bytes] = set()
    lightest = delta.min(initial=0)  # no two-face edge at all: one strand per face, any labels
    for _ in range(4 * count):
        if deadline is not None and designs and time.perf_counter() > deadline:
            break
        weights = np.where(
            forced, 1e-3 * (1 + rng.random(len(two))), 1 + (delta - lightest) + 0.5 * rng.random(len(two))
        )
        tree = _spanning_tree(scaffold.n_faces, dual.f0[candidate], dual.f1[candidate], weights[candidate])
        if tree is None:
            break
        in_tree = np.zeros(len(two), bool)
        in_tree[np.flatnonzero(candidate)[tree]] = True
        if np.any(forced & ~in_tree):
            break
        labels = choices.base.copy()
        labels[two[in_tree]] = choices.odd[two[in_tree]]
        key = in_tree.tobytes()
        if key not in seen:
            seen.add(key)
            designs.append(labels)
        if len(designs) == count:
            break
    return designs


def _spanning_tree(n_faces: int, u: np.ndarray, v: np.ndarray, weights: np.ndarray) -> np.ndarray | None:
    """Return the indices into ``u, v`` of a minimum spanning tree of the dual graph, or None if disconnected."""
    if n_faces == 1:
        return np.zeros(0, np.int64)
    a, b = np.minimum(u, v), np.maximum(u, v)
    order = np.argsort(weights, kind="stable")
    _, first = np.unique(a[order] * n_faces + b[order], return_index=True)
    keep = order[first]  # the lightest edge between each pair of faces
    graph = scipy.sparse.coo_matrix((weights[keep], (a[keep], b[keep])), shape=(n_faces, n_faces)).tocsr()
    mst = scipy.sparse.csgraph.minimum_spanning_tree(graph).tocoo()
    if mst.nnz != n_faces - 1:
        return None
    lookup = {(int(x), int(y)): int(i) for x, y, i in zip(a[keep], b[keep], keep, strict=True)}
    return np.array(
        [lookup[(min(x, y), max(x, y))] for x, y in zip(mst.row.tolist(), mst.col.tolist(), strict=True)], np.int64
    )


def _meets_lower_bound(
    labels: np.ndarray, choices: ParityChoices, dual: DualEdges, scaffold: Scaffold, query: Query
) -> bool:
    """Whether ``labels`` reaches the bound: >= F - 1 odd degree-2 edges, each edge at its cheapest."""
    if query.objective is None:
        return True
    costs, can, degrees, n_faces = choices.costs, choices.can, scaffold.edge_degrees, scaffold.n_faces
    two, forced, delta = dual.two, dual.forced, dual.delta
    cost = int(label_cost(labels, query.objective).sum())
    bound = int(costs[degrees == 1, 0].sum())
    both = can[two, 0] & can[two, 1]
    bound += int(costs[two, 1][forced].sum()) + int(costs[two, 0][~forced].sum())
    gains = np.sort(delta[both])
    n_odd = int(forced.sum())
    take = max(int(np.sum(gains < 0)), n_faces - 1 - n_odd)
    if take > len(gains):
        return False
    bound += int(gains[:take].sum())
    return cost == bound


GREEDY_ATTEMPTS = 16


def _greedy_designs(
    scaffold: Scaffold,
    query: Query,
    count: int,
    seed: int,
    partial: list[tuple[int, np.ndarray]] | None = None,
    deadline: float | None = None,
    step: Step | None = None,
) -> list[np.ndarray]:
    """Designs with N <= F components (any K) by greedy merging.

    Start from residue 0 everywhere (one strand per face) and visit the edges (those that
    cannot take residue 0 first, then by decreasing K, ties at random).  When the K faces of
    an edge lie on K different strands so far, a residue coprime to K joins them into one
    (the K cut strands are chained by the shift ``i -> i + r``), as long as at least N
    strands remain; otherwise the edge keeps residue 0, which changes nothing.  The strand
    count is thus known exactly at every step.  Returns no design if some edge cannot follow
    the rule or the count does not end at N; then ``partial`` (a list, if given) receives
    the attempt that came closest, as a start for :mod:`lkspace.inverse.local_search`.
    Attempts stop at ``deadline`` (``time.perf_counter()``); ``step`` gets the closest count.
    """
    degrees = scaffold.edge_degrees
    allowed = allowed_labels(scaffold, query)
    sides, starts = scaffold.radial.edge_sides, scaffold.radial.edge_starts
    faces_of = [scaffold.corner_face[sides[starts[e] : starts[e + 1]]] for e in range(scaffold.n_edges)]
    stay, merge = [], []
    for e, labels in enumerate(allowed):
        k = int(degrees[e])
        residues = labels % k
        coprime = np.array([np.gcd(k, int(r)) == 1 for r in residues], bool) if k > 1 else np.zeros(len(labels), bool)
        stay.append(cheapest_label(labels[residues == 0], query.objective))
        merge.append(cheapest_label(labels[coprime], query.objective))
    if any(a is None and b is None for a, b in zip(stay, merge, strict=True)):
        return []
    rng = np.random.default_rng(seed)
    designs: list[np.ndarray] = []
    seen: set[bytes] = set()
    closest = scaffold.n_faces + 1
    for attempt in range(GREEDY_ATTEMPTS * count):  # a greedy order can get stuck: try others
        if deadline is not None and time.perf_counter() > deadline:
            break
        if step is not None and attempt % 64 == 0 and attempt:  # shown every few seconds on a long run
            step.note(f"greedy merging: {attempt:,} orders tried, {len(designs):,} designs, closest {closest}")
        must_merge = np.array([a is None for a in stay])
        order = np.lexsort((rng.random(scaffold.n_edges), -degrees, ~must_merge))
        pieces = UnionFind(scaffold.n_faces)
        labels = np.zeros(scaffold.n_edges, np.int64)
        n_strands = scaffold.n_faces
        stuck = False
        for e in order.tolist():
            k = int(degrees[e])
            roots = {pieces.find(int(f)) for f in faces_of[e]}
            distinct = k > 1 and len(roots) == k and merge[e] is not None
            if distinct and (n_strands - (k - 1) >= query.components or stay[e] is None):
                labels[e] = merge[e][1]
                first, *rest = roots
                for r in rest:
                    pieces.join(first, r)
                n_strands -= k - 1
            elif stay[e] is not None:
                labels[e] = stay[e][1]
            else:
                stuck = True
                labels[e] = merge[e][1]  # keeps the partial design within the allowed labels
        if stuck or n_strands != query.components:
            closest = min(closest, n_strands)
            if partial is not None and (not partial or n_strands < partial[0][0]):
                partial[:] = [(n_strands, labels)]
                if step is not None:
                    step.note(f"greedy merging: closest {plural(n_strands, 'component')}")
            continue
        key = labels.tobytes()
        if key not in seen:
            seen.add(key)
            designs.append(labels)
        if len(designs) == count:
            break
    return designs
