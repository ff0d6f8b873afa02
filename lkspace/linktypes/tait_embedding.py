"""Designs of a table type on a closed scaffold, from the type's diagram: its Tait graph embedded in the scaffold.

A design on a scaffold S whose edges all have two faces draws the link whose Tait graph has
the faces of S as vertices and one edge per non-zero label (label 0: the two faces' strands
do not cross there).  So a table type whose collapsed Tait graph G (the dual of its
checkerboard mesh :func:`~lkspace.scaffolds.diagram_mesh.diagram_mesh`, one edge per twist
region, label = signed twist count) is a subgraph of the dual graph of S has a design on S:
G's labels on the matched edges.  Every face left over is joined to the matched part by one
edge with label 1 along a breadth-first forest of the dual graph: a bridge of the Tait graph,
i.e. a kink (Reidemeister I), which costs 1 in sum |t| and leaves the type alone.

Subgraph embeddings come from python-igraph's LAD; both colourings of the diagram are tried,
more faces (fewer kinks) first.  An embedding may differ from the diagram's own at 2-cuts
(mutants, flypes), by a reflection, or (on a surface of higher genus) by a cycle that does not
bound, so every candidate must be named before it is used: these are candidates, not answers.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

import numpy as np

from ..model.scaffold import Scaffold
from ..scaffolds.diagram_mesh import diagram_mesh

if TYPE_CHECKING:
    import igraph as ig

PD = list[list[int]] | tuple[tuple[int, ...], ...]
"""A PD code: one 4-tuple of arc labels per crossing."""
TaitGraph = tuple[int, list[tuple[int, int, int]]]
"""``(faces, [(f, g, label), ...])``: a collapsed Tait graph, one edge per pair of faces."""


def dual_graph(s: Scaffold) -> tuple[ig.Graph, dict[tuple[int, int], int]] | None:
    """Return the dual graph of ``s`` (faces as vertices) and ``(f, g) -> edge of s`` (``f < g``).

    ``None`` unless every edge of ``s`` has two distinct faces and no two edges join the same
    two faces (the subgraph search needs a simple graph).
    """
    from ..runtime.graphs import igraph_module

    ig = igraph_module()
    sides: dict[int, list[int]] = {}
    for corner, e in enumerate(s.side_edge):
        sides.setdefault(int(e), []).append(int(s.corner_face[corner]))
    edge_of: dict[tuple[int, int], int] = {}
    for e in range(s.n_edges):
        faces = sides.get(e, [])
        if len(faces) != 2 or faces[0] == faces[1]:
            return None
        pair = (min(faces), max(faces))
        if pair in edge_of:
            return None
        edge_of[pair] = e
    return ig.Graph(n=s.n_faces, edges=sorted(edge_of)), edge_of


def tait_graph(pd: PD, colouring: str) -> TaitGraph | None:
    """Return the collapsed Tait graph of one colouring (``"fewer"`` or ``"more"``), parallel edges summed.

    Summing is right for the edges of one twist region that the mesh kept apart, wrong for
    two twist regions between the same faces (a pretzel): naming the design tells.  ``None``
    when an edge has one face on both sides.
    """
    mesh = diagram_mesh([list(x) for x in pd], colouring=colouring)
    sides: dict[frozenset[int], list[int]] = {}
    for f, face in enumerate(mesh.faces):
        for a, b in zip(face, face[1:] + face[:1]):
            sides.setdefault(frozenset((a, b)), []).append(f)
    summed: dict[tuple[int, int], int] = {}
    for (u, v), t in zip(mesh.edges, mesh.labels):
        f, g = sides[frozenset((u, v))]
        if f == g:
            return None
        summed[min(f, g), max(f, g)] = summed.get((min(f, g), max(f, g)), 0) + t
    return len(mesh.faces), [(f, g, t) for (f, g), t in summed.items() if t]


def embedded_designs(
    s: Scaffold, pd: PD, tries: int = 4, max_kinks: int | None = None
) -> Iterator[tuple[int, np.ndarray]]:
    """Yield ``(kinks, (n_edges,) int64 labels)`` on ``s``: the diagram's Tait graphs embedded, fewest kinks first.

    At most ``tries`` distinct designs per colouring, spread over the embeddings LAD finds;
    colourings needing more than ``max_kinks`` kinks are skipped.  Nothing when ``s`` has no
    :func:`dual_graph`.  The negation of a design draws the mirror image.
    """
    dual = dual_graph(s)
    if dual is None:
        return
    host, edge_of = dual
    graphs = [g for g in (tait_graph(pd, c) for c in ("fewer", "more")) if g is not None]
    for n, edges in sorted(graphs, key=lambda g: -g[0]):
        kinks = s.n_faces - n
        if kinks < 0 or (max_kinks is not None and kinks > max_kinks):
            continue
        for labels in _embeddings(n, edges, host, edge_of, s.n_edges, tries):
            yield kinks, labels


def _embeddings(
    n: int,
    edges: list[tuple[int, int, int]],
    host: ig.Graph,
    edge_of: dict[tuple[int, int], int],
    n_edges: int,
    tries: int,
) -> Iterator[np.ndarray]:
    from ..runtime.graphs import igraph_module

    ig = igraph_module()
    pattern = ig.Graph(n=n, edges=[(f, g) for f, g, _ in edges])
    maps = host.get_subisomorphisms_lad(pattern, induced=False)
    seen: set[bytes] = set()
    step = max(1, len(maps) // (4 * tries))
    for m in maps[::step]:
        labels = np.zeros(n_edges, np.int64)
        for f, g, t in edges:
            a, b = m[f], m[g]
            labels[edge_of[min(a, b), max(a, b)]] = t
        covered, frontier = set(m), list(m)
        while frontier:  # breadth first: join every face left over by a kink
            nxt = []
            for a in frontier:
                for b in host.neighbors(a):
                    if b not in covered:
                        covered.add(b)
                        labels[edge_of[min(a, b), max(a, b)]] = 1
                        nxt.append(b)
            frontier = nxt
        if labels.tobytes() in seen:
            continue
        seen.add(labels.tobytes())
        yield labels
        if len(seen) >= tries:
            return
