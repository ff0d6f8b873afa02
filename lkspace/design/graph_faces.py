"""From a graph to face sets: its cycles, its automorphisms, and the covers that become scaffolds.

A graph is ``(n_vertices, edges)`` with ``edges`` a list of vertex pairs (simple, undirected).
A **face** is a simple cycle of the graph, stored as a vertex tuple starting at its smallest
vertex and running towards the smaller of its two neighbours there; a cycle is known by
that tuple.  A **face set** is a sorted tuple of cycle indices; a **cover** is a face set
where every edge of the graph lies on exactly ``per_edge`` faces (``per_edge = 2``: a closed
surface, possibly with vertices where it pinches; 3 or more: a non-manifold scaffold whose
edges need radial orders).

Automorphisms are the graph's vertex permutations keeping the edge set (python-igraph,
VF2); they act on cycles, and face sets are listed up to them: a face set is kept when it
is the lexicographically smallest image of itself.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..errors import TooLargeError, UsageError
from ..model.scaffold import Scaffold

NAMED_GRAPHS = ("K4", "cube", "K3,3", "petersen", "octahedron", "K5")
MAX_CYCLES = 4096
"""Most cycles a graph may offer as faces (the cover search is exponential in them)."""

MAX_GRAPH_EDGES = 10_000
"""Most edges of a graph whose face sets are sought (its cycles and automorphisms are listed)."""

MAX_AUTOMORPHISM_ENTRIES = 1 << 24
"""Most ``automorphisms x vertices`` listed (128 MB of vertex images; a ring of 10^5 vertices has 2 x 10^5
automorphisms, 2 x 10^10 entries): counted first, refused past this before any is listed."""

MAX_STEPS = 2_000_000
"""Most branches the cover search takes before it gives up with :class:`~lkspace.errors.TooLargeError`."""


def named_graph(name: str) -> tuple[int, list[tuple[int, int]]]:
    """``(n_vertices, edges)`` of a small named graph (``K4``, ``cube``, ``K3,3``, ``petersen``, ...)."""
    from ..runtime.graphs import igraph_module

    ig = igraph_module()
    makers = {
        "K4": lambda: ig.Graph.Full(4),
        "K5": lambda: ig.Graph.Full(5),
        "cube": lambda: ig.Graph.Famous("Cubical"),
        "octahedron": lambda: ig.Graph.Famous("Octahedral"),
        "K3,3": lambda: ig.Graph.Full_Bipartite(3, 3),
        "petersen": lambda: ig.Graph.Famous("Petersen"),
    }
    if name not in makers:
        raise UsageError(f"unknown graph {name!r}; choose one of {', '.join(NAMED_GRAPHS)}")
    g = makers[name]()
    return g.vcount(), sorted((min(a, b), max(a, b)) for a, b in g.get_edgelist())


def canonical_cycle(cycle: Sequence[int]) -> tuple[int, ...]:
    """Return the cycle's tuple: from its smallest vertex, towards the smaller neighbour."""
    c = list(cycle)
    i = c.index(min(c))
    c = c[i:] + c[:i]
    if len(c) > 2 and c[-1] < c[1]:
        c = [c[0], *reversed(c[1:])]
    return tuple(c)


def simple_cycles(n_vertices: int, edges: Sequence[tuple[int, int]], max_length: int) -> list[tuple[int, ...]]:
    """Every simple cycle of length 3..``max_length``, as canonical tuples, sorted by (length, tuple)."""
    adj: list[list[int]] = [[] for _ in range(n_vertices)]
    for a, b in edges:
        adj[a].append(b)
        adj[b].append(a)
    found: set[tuple[int, ...]] = set()
    for start in range(n_vertices):
        stack = [(start, [start])]
        while stack:
            v, path = stack.pop()
            for w in adj[v]:
                if w == start and len(path) >= 3:
                    found.add(canonical_cycle(path))
                elif w > start and w not in path and len(path) < max_length:
                    stack.append((w, [*path, w]))
                    if len(found) > MAX_CYCLES:
                        raise UsageError(f"more than {MAX_CYCLES} cycles up to length {max_length}; lower the length")
    return sorted(found, key=lambda c: (len(c), c))


def check_graph(n_vertices: int, edges: Sequence[tuple[int, int]]) -> None:
    """Refuse a graph past :data:`MAX_GRAPH_EDGES` edges (or vertices) before any work (one line)."""
    size = max(n_vertices, len(edges))
    if size > MAX_GRAPH_EDGES:
        raise TooLargeError(
            f"a graph of {n_vertices:,} vertices and {len(edges):,} edges: face sets are sought on graphs of at most "
            f"{MAX_GRAPH_EDGES:,} vertices and edges (their cycles and automorphisms are listed); use a smaller graph"
        )


def graph_automorphisms(n_vertices: int, edges: Sequence[tuple[int, int]]) -> np.ndarray:
    """``(n_aut, n_vertices) int64``: every automorphism of the graph (vertex images), identity first.

    Counted first (BLISS, without listing them): past :data:`MAX_AUTOMORPHISM_ENTRIES` it
    is a :class:`~lkspace.errors.TooLargeError`, before memory grows.
    """
    from ..runtime.graphs import igraph_module

    ig = igraph_module()
    check_graph(n_vertices, edges)
    graph = ig.Graph(n=n_vertices, edges=list(edges))
    count = int(graph.count_automorphisms())
    if count * max(n_vertices, 1) > MAX_AUTOMORPHISM_ENTRIES:
        raise TooLargeError(
            f"the graph ({n_vertices:,} vertices) has {count:,} automorphisms: too many to list "
            f"(at most {MAX_AUTOMORPHISM_ENTRIES:,} vertex images); use a less symmetric or smaller graph"
        )
    perms = np.array(graph.get_automorphisms_vf2(), np.int64)
    order = np.lexsort(perms.T[::-1])  # the identity is the lexicographically smallest
    return perms[order]


@dataclass(frozen=True, eq=False)
class CycleSpace:
    """A graph, its cycles up to a length, and how its automorphisms permute them.

    Attributes
    ----------
    n_vertices : int
    edges : list of (int, int)
    cycles : list of tuple of int
    automorphisms : (n_aut, n_vertices) int64
    """

    n_vertices: int
    edges: list[tuple[int, int]]
    cycles: list[tuple[int, ...]]
    automorphisms: np.ndarray

    @cached_property
    def cycle_perms(self) -> np.ndarray:
        """``(n_aut, n_cycles) int64``: the image of every cycle under every automorphism."""
        index = {c: i for i, c in enumerate(self.cycles)}
        return np.array(
            [[index[canonical_cycle([int(p[v]) for v in c])] for c in self.cycles] for p in self.automorphisms],
            np.int64,
        ).reshape(len(self.automorphisms), len(self.cycles))

    @cached_property
    def cycle_edges(self) -> list[list[int]]:
        """Per cycle, the indices of its edges."""
        index = {e: i for i, e in enumerate(self.edges)}
        return [[index[(min(a, b), max(a, b))] for a, b in zip(c, c[1:] + c[:1], strict=True)] for c in self.cycles]

    def canonical(self, faces: Sequence[int]) -> tuple[tuple[int, ...], int]:
        """Smallest image of the face set ``faces`` under the automorphisms, and its stabilizer's order."""
        images = np.sort(self.cycle_perms[:, list(faces)], axis=1)
        keys = [tuple(r) for r in images.tolist()]
        best = min(keys)
        return best, sum(1 for k in keys if k == tuple(sorted(faces)))

    def stabilizer(self, faces: Sequence[int]) -> np.ndarray:
        """Return the indices of the automorphisms mapping the face set onto itself."""
        target = np.sort(np.asarray(faces, np.int64))
        images = np.sort(self.cycle_perms[:, list(faces)], axis=1)
        return np.flatnonzero(np.all(images == target[None, :], axis=1))


def cycle_space(n_vertices: int, edges: Sequence[tuple[int, int]], max_length: int) -> CycleSpace:
    """Return the :class:`CycleSpace` of a graph with cycles of length up to ``max_length``."""
    edges = sorted((min(a, b), max(a, b)) for a, b in edges)
    check_graph(n_vertices, edges)
    return CycleSpace(
        n_vertices, edges, simple_cycles(n_vertices, edges, max_length), graph_automorphisms(n_vertices, edges)
    )


def covers(space: CycleSpace, per_edge: int) -> Iterator[tuple[int, ...]]:
    """Every face set covering each edge exactly ``per_edge`` times.

    An exact cover with multiplicities: branch on the first available cycle through the
    edge with the fewest available cycles per missing face (include it, or rule it out);
    a cycle through an edge that needs no more faces is ruled out, and a branch ends when
    some edge has fewer available cycles than it needs.
    """
    cycle_edges = [np.asarray(c, np.int64) for c in space.cycle_edges]
    n_e = len(space.edges)
    through: list[list[int]] = [[] for _ in range(n_e)]
    for i, c in enumerate(cycle_edges):
        for e in c.tolist():
            through[e].append(i)
    need = np.full(n_e, per_edge, np.int64)
    avail = np.ones(len(cycle_edges), bool)
    n_avail = np.array([len(t) for t in through], np.int64)
    chosen: list[int] = []
    steps = [0]

    def drop(i: int, undo: list[int]) -> None:
        avail[i] = False
        n_avail[cycle_edges[i]] -= 1
        undo.append(i)

    def restore(undo: list[int]) -> None:
        for i in reversed(undo):
            avail[i] = True
            n_avail[cycle_edges[i]] += 1

    def walk() -> Iterator[tuple[int, ...]]:
        steps[0] += 1
        if steps[0] > MAX_STEPS:
            raise TooLargeError(
                f"the cover search passed {MAX_STEPS:,} steps over {len(cycle_edges)} cycles; lower `max_length`",
            )
        open_edges = np.flatnonzero(need > 0)
        if not len(open_edges):
            yield tuple(sorted(chosen))
            return
        if np.any(n_avail[open_edges] < need[open_edges]):
            return
        e = int(open_edges[np.argmin(n_avail[open_edges] - need[open_edges])])
        c = next(i for i in through[e] if avail[i])
        undo: list[int] = []
        drop(c, undo)  # decided either way
        need[cycle_edges[c]] -= 1
        chosen.append(c)
        for f in cycle_edges[c][need[cycle_edges[c]] == 0].tolist():
            for i in through[f]:
                if avail[i]:
                    drop(i, undo)
        yield from walk()
        chosen.pop()
        need[cycle_edges[c]] += 1
        restore(undo[1:])
        undo = undo[:1]
        yield from walk()
        restore(undo)

    yield from walk()


def cover_orbits(space: CycleSpace, per_edge: int) -> list[tuple[tuple[int, ...], int]]:
    """Covers up to automorphism: ``(canonical face set, orbit size)`` per class, sorted."""
    n_aut = len(space.automorphisms)
    out = []
    for faces in covers(space, per_edge):
        best, stab = space.canonical(faces)
        if best == faces:
            out.append((faces, n_aut // stab))
    return sorted(out)


def scaffold_of(space: CycleSpace, faces: Sequence[int], orders: dict[int, tuple[int, ...]] | None = None) -> Scaffold:
    """Build a scaffold on the face set, vertices at generic points, with explicit radial orders.

    ``orders`` maps an edge index to the face indices (positions in ``faces``) in slot
    order, seen along the edge from its lower vertex; edges of degree >= 3 not given get
    the order of the face indices.  Only the combinatorics matter: the coordinates are a
    seeded generic placement, not a geometric realization.
    """
    polys = [list(space.cycles[f]) for f in faces]
    starts = np.concatenate([[0], np.cumsum([len(p) for p in polys])])
    sides: dict[int, list[tuple[int, int]]] = {}
    for k, poly in enumerate(polys):
        for j, (a, b) in enumerate(zip(poly, poly[1:] + poly[:1], strict=True)):
            sides.setdefault(space.edges.index((min(a, b), max(a, b))), []).append((k, int(starts[k]) + j))
    radial: dict[tuple, tuple[int, ...]] = {}
    for e, on_edge in sides.items():
        if len(on_edge) < 3:
            continue
        side_of = dict(on_edge)
        order = (orders or {}).get(e, tuple(k for k, _ in on_edge))
        a, b = space.edges[e]
        radial[(a, b, ())] = tuple(side_of[k] for k in order)
    points = np.random.default_rng(0).normal(size=(space.n_vertices, 3))
    return Scaffold.from_faces(points, polys, radial_orders=radial or None, name="graph surface")
