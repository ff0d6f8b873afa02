"""Candidate symmetries of a finite scaffold from its incidence graph, and the rigid motions that realize them.

Candidates come from the automorphisms of the coloured incidence graph (igraph); a
candidate is kept only when a rigid motion realizes it.  Finite scaffolds take this path
only when coincident vertices leave the faster search of :mod:`lkspace.symmetry.finite`
ambiguous; periodic scaffolds never do (:mod:`lkspace.symmetry.periodic_search` builds their
motions directly).  :mod:`lkspace.symmetry.group` assembles the group.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING, TypeAlias

import numpy as np

from ..errors import ScaffoldError, TooLargeError
from ..model.scaffold import Scaffold
from ..runtime.progress import task
from .tolerance import resolve_tolerance

if TYPE_CHECKING:
    import igraph

MAX_AUTOMORPHISMS = 500_000
"""Most incidence automorphisms listed (their closure is held in memory); past it, :class:`~lkspace.errors.TooLargeError`."""

LatticePart: TypeAlias = tuple[np.ndarray, np.ndarray]
"""Lattice part of a periodic motion: vertex offsets ``(n_vertices, dim) int64`` and ``N (dim, dim) int64``."""
Motion: TypeAlias = tuple[np.ndarray, np.ndarray, np.ndarray, LatticePart | None]
"""A rigid motion: vertex permutation ``sigma``, orthogonal ``Q (3, 3)``, translation ``tau (3,)``, lattice part."""


# ---- combinatorial candidates ---------------------------------------------------------
def incidence_graph(scaffold: Scaffold) -> tuple[igraph.Graph, list[int]]:
    """Return the coloured vertex/edge/face incidence graph as ``(igraph.Graph, colours)``."""
    from ..runtime.graphs import igraph_module

    igraph = igraph_module()

    nv, ne = scaffold.n_vertices, scaffold.n_edges
    ev = scaffold.edge_vertices
    links = set()
    for e, (a, b) in enumerate(ev.tolist()):
        links.add((a, nv + e))
        links.add((b, nv + e))
    for side, e in enumerate(scaffold.side_edge.tolist()):
        links.add((nv + e, nv + ne + int(scaffold.corner_face[side])))
    graph = igraph.Graph(n=nv + ne + scaffold.n_faces, edges=sorted(links))
    colours = [0] * nv + [1] * ne + [2] * scaffold.n_faces
    return graph, colours


def automorphism_count(scaffold: Scaffold) -> int:
    """Count the automorphisms of the coloured incidence graph (BLISS, without listing them)."""
    graph, colours = incidence_graph(scaffold)
    return int(graph.count_automorphisms(color=colours))


def candidate_vertex_perms(scaffold: Scaffold) -> np.ndarray:
    """(n_candidates, n_vertices) int64: vertex parts of the incidence automorphisms.

    BLISS (igraph) gives generators of the automorphism group; the group is their closure,
    built breadth-first with numpy (much faster than listing automorphisms with VF2).
    Raises :class:`~lkspace.errors.TooLargeError` past :data:`MAX_AUTOMORPHISMS`.
    """
    graph, colours = incidence_graph(scaffold)
    count = int(graph.count_automorphisms(color=colours))
    if count > MAX_AUTOMORPHISMS:
        raise TooLargeError(
            f"{scaffold.name}: the incidence structure has {count} automorphisms (more than "
            f"{MAX_AUTOMORPHISMS}); use `symmetry='none'`",
        )
    n = graph.vcount()
    gens = np.array(graph.automorphism_group(color=colours), dtype=np.int64).reshape(-1, n)
    elements = {np.arange(n, dtype=np.int64).tobytes()}
    frontier = np.arange(n, dtype=np.int64)[None, :]
    with task("symmetry search", total=count) as step:
        while len(frontier):
            products = gens[:, frontier].reshape(-1, n)  # g o x for every generator g and element x
            new = []
            for row in products:
                key = row.tobytes()
                if key not in elements:
                    elements.add(key)
                    new.append(row)
            frontier = np.array(new, dtype=np.int64).reshape(-1, n)
            step.update(len(elements))
    if len(elements) != count:  # pragma: no cover - BLISS and the closure disagree
        raise ScaffoldError(f"{scaffold.name}: automorphism closure found {len(elements)} of {count} elements")
    perms = np.frombuffer(b"".join(elements), dtype=np.int64).reshape(-1, n)[:, : scaffold.n_vertices]
    return np.unique(perms, axis=0)


# ---- rigid-motion check ---------------------------------------------------------------
def _tolerance(scaffold: Scaffold, tolerance: float | None = None) -> float:
    """How far (mesh units) a motion may move a vertex from its image: ``tolerance`` or the default rule."""
    return resolve_tolerance(scaffold, tolerance)


def plane_normal(x: np.ndarray) -> tuple[np.ndarray, float]:
    """Return the unit direction of least spread of centred points ``x (n, 3)`` and the spread along it (RMS).

    From the 3 x 3 second-moment matrix (``eigh``): O(n) time and memory.
    """
    values, vectors = np.linalg.eigh(x.T @ x)
    return vectors[:, 0], float(np.sqrt(max(values[0], 0.0) / max(len(x), 1)))


def finite_motions(scaffold: Scaffold, sigmas: np.ndarray, tolerance: float | None = None) -> Iterator[Motion]:
    """Yield the rigid motions of a finite scaffold realizing the candidate vertex permutations ``sigmas``.

    A motion may move each vertex by up to ``tolerance`` (mesh units; default: :mod:`.tolerance`).
    ``Q`` is the orthogonal Procrustes fit about the vertex centroid (and its composition with
    the mirror in the vertices' plane when they are coplanar); the lattice part is ``None``.
    """
    x = scaffold.vertices - scaffold.vertices.mean(axis=0)
    tol = _tolerance(scaffold, tolerance)
    normal, spread = plane_normal(x)
    flat = spread <= tol
    mirror = np.eye(3) - 2 * np.outer(normal, normal)
    for sigma in sigmas:
        y = x[sigma]
        u, _, wt = np.linalg.svd(y.T @ x)
        q0 = u @ wt
        for q in (q0, q0 @ mirror) if flat else (q0,):
            if np.sqrt(np.einsum("ij,ij->i", x @ q.T - y, x @ q.T - y).max()) <= tol:
                yield sigma, q, scaffold.vertices.mean(axis=0) - q @ scaffold.vertices.mean(axis=0), None
