"""Candidate symmetries of a scaffold and the rigid motions that realize them.

Candidates come from the automorphisms of the coloured incidence graph (igraph); a
candidate is kept only when a rigid motion realizes it (for periodic scaffolds: a lattice
point-group element plus a translation).  Periodic scaffolds always take this path;
finite ones only when coincident vertices leave the faster search of
:mod:`lkspace.symmetry.finite` ambiguous.  :mod:`lkspace.symmetry.group` assembles the group.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING, Any, TypeAlias

import numpy as np

from ..errors import ScaffoldError, TooLargeError
from ..model.scaffold import Scaffold
from ..progress import task
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
    import igraph

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
            f"{MAX_AUTOMORPHISMS}); use --symmetry none"
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


def lattice_point_group(scaffold: Scaffold) -> list[tuple[np.ndarray, np.ndarray]]:
    """Orthogonal ``Q`` with integer ``N`` such that ``B Q^T = N B`` (the lattice's point group)."""
    assert scaffold.lattice is not None, "the lattice point group needs a periodic scaffold"
    basis = scaffold.lattice.basis
    dim = len(basis)
    tol = 1e-8
    grid = np.array(np.meshgrid(*[[-1, 0, 1]] * (dim * dim), indexing="ij")).reshape(dim * dim, -1).T
    ns = grid.reshape(-1, dim, dim).astype(np.float64)
    if dim == 3:
        frame = basis
        targets = ns @ basis  # (m, 3, 3): rows N B
        qts = np.linalg.solve(frame, targets)  # Q^T = B^-1 N B
        out = []
        for n, qt in zip(ns, qts, strict=True):
            if np.abs(qt.T @ qt - np.eye(3)).max() < tol:
                out.append((qt.T, n.astype(np.int64)))
        return out
    normal = np.cross(basis[0], basis[1])
    normal /= np.linalg.norm(normal)
    frame = np.vstack([basis, normal])
    out = []
    for n in ns:
        for s in (1.0, -1.0):
            target = np.vstack([n @ basis, s * normal])
            qt = np.linalg.solve(frame, target)
            if np.abs(qt.T @ qt - np.eye(3)).max() < tol:
                out.append((qt.T, n.astype(np.int64)))
    return out


def _face_keys(corner_keys: np.ndarray, face_starts: np.ndarray) -> np.ndarray | tuple[Any, ...]:
    """Faces as translation-normalized corner sets, sorted: an exact integer fingerprint.

    Vectorized when all faces have one size and each face's smallest vertex occurs once
    (anchor: that corner); otherwise every corner is tried as anchor (Python).
    """
    sizes = np.diff(face_starts)
    m = int(sizes[0])
    if np.all(sizes == m):
        block = corner_keys.reshape(len(sizes), m, -1)
        verts = block[:, :, 0]
        first = np.argmin(verts, axis=1)
        if np.all(np.sum(verts == verts[np.arange(len(sizes)), first][:, None], axis=1) == 1):
            moved = block.copy()
            moved[:, :, 1:] -= block[np.arange(len(sizes)), first][:, None, 1:]
            flat = moved.reshape(len(sizes) * m, -1)
            order = np.lexsort(flat.T[::-1])  # sort corners within faces: by face, then key
            face_of = np.repeat(np.arange(len(sizes)), m)
            order = order[np.argsort(face_of[order], kind="stable")]
            rows = flat[order].reshape(len(sizes), -1)
            return rows[np.lexsort(rows.T[::-1])]
    out = []
    for f in range(len(face_starts) - 1):
        block = corner_keys[face_starts[f] : face_starts[f + 1]]
        best = None
        for anchor in block:
            moved = block.copy()
            moved[:, 1:] -= anchor[1:]
            key = tuple(sorted(map(tuple, moved.tolist())))
            best = key if best is None or key < best else best
        out.append(best)
    return tuple(sorted(out))  # faces of mixed sizes: compare as nested tuples


def periodic_motions(scaffold: Scaffold, sigmas: np.ndarray, tolerance: float | None = None) -> Iterator[Motion]:
    """Yield the rigid motions of a periodic scaffold realizing the candidate vertex permutations ``sigmas``.

    ``Q`` runs over the lattice point group; ``tau`` is fixed by vertex 0 and every face must
    map onto a face.  The lattice part holds the vertex offsets and ``N`` (``B Q^T = N B``).
    """
    assert scaffold.lattice is not None and scaffold.corner_offsets is not None, "periodic motions need a lattice"
    tol = _tolerance(scaffold, tolerance)
    pos = scaffold.vertices
    basis = scaffold.lattice.basis
    pinv = np.linalg.pinv(basis)  # x = c @ basis  ->  c = x @ pinv
    faces = _face_keys(scaffold.corner_keys, scaffold.face_starts)
    for q, n in lattice_point_group(scaffold):
        taus = pos[sigmas[:, 0]] - q @ pos[0]  # (n_sigma, 3)
        diffs = (pos @ q.T)[None, :, :] + taus[:, None, :] - pos[sigmas]  # (n_sigma, n_vertices, 3)
        coords = np.round(diffs @ pinv)
        ok = np.all(np.abs(coords @ basis - diffs) <= tol, axis=(1, 2))
        for i in np.flatnonzero(ok):
            sigma, offsets = sigmas[i], coords[i].astype(np.int64)
            image = np.column_stack([sigma[scaffold.corners], offsets[scaffold.corners] + scaffold.corner_offsets @ n])
            image_faces = _face_keys(image, scaffold.face_starts)
            same = image_faces == faces if isinstance(faces, tuple) else np.array_equal(image_faces, faces)
            if not same:
                continue
            yield sigma, q, taus[i], (offsets, n)


def edge_permutation(scaffold: Scaffold, sigma: np.ndarray, lattice_part: LatticePart | None) -> np.ndarray | None:
    """(n_edges,) int64: image edge of each edge under the motion, or None if one is no edge."""
    keys = scaffold.edge_keys
    a, b = sigma[keys[:, 0]], sigma[keys[:, 1]]
    if lattice_part is None:
        image = np.column_stack([np.minimum(a, b), np.maximum(a, b)])
    else:
        offsets, n = lattice_part
        delta = offsets[keys[:, 1]] + keys[:, 2:] @ n - offsets[keys[:, 0]]
        nz = delta != 0
        first = delta[np.arange(len(delta)), np.argmax(nz, axis=1)]
        forward = (a < b) | ((a == b) & (first > 0))
        image = np.column_stack(
            [np.where(forward, a, b), np.where(forward, b, a), np.where(forward[:, None], delta, -delta)]
        )
    both = np.concatenate([keys, image])
    _, inverse = np.unique(both, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    slot = np.full(len(both), -1, np.int64)
    slot[inverse[: len(keys)]] = np.arange(len(keys))
    perm = slot[inverse[len(keys) :]]
    if np.any(perm < 0) or len(np.unique(perm)) != len(perm):
        return None
    return perm
