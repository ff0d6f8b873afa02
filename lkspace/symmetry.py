"""Symmetry group of a scaffold: rigid motions that map it onto itself.

How the group is found
----------------------
1. **Combinatorial candidates.**  The incidence structure is a vertex-coloured graph with
   one node per vertex (colour 0), per edge (colour 1) and per face (colour 2); a vertex
   node is joined to the edges it bounds, an edge node to the faces it lies on.  Its
   automorphisms (python-igraph: BLISS generators, closed into the group) give candidate vertex permutations
   ``sigma`` (duplicates that only permute faces on the same vertex cycle, as in a
   two-sided polygon, collapse).  When there are too many to list (more than
   ``MAX_AUTOMORPHISMS``, e.g. a book of many pages), finite scaffolds fall back to a
   frame search: the images of vertex 0 and two neighbours fix a candidate motion
   (:func:`geometric_vertex_perms`).
2. **Rigid-motion check.**  A candidate survives only if a rigid motion
   ``x -> Q x + tau`` (``Q`` orthogonal) carries every vertex ``v`` onto ``sigma(v)``:

   * finite scaffold: ``Q`` is the orthogonal Procrustes fit about the vertex centroid
     (which every isometry of the scaffold fixes).  When the vertices are coplanar the
     fit is unique only up to the reflection in their plane, and both motions are kept
     (a flat polygon has the in-plane rotations and the half-turns that flip it over);
   * periodic scaffold: ``Q`` must also map the lattice to itself, ``B Q^T = N B`` for an
     integer matrix ``N`` (the lattice point group, searched over ``N`` with entries in
     ``{-1, 0, 1}``, enough for reduced bases); ``tau`` is fixed by one vertex and the
     others must land on their images up to lattice translations.  The image of every
     edge class and every face (as a set of lattice-offset corners) must again be one.
3. **Action on labels.**  Each motion permutes the edges, ``edge_perms[g, e]`` is the
   image of edge ``e``.  A proper motion (rotation, ``det Q = +1``) keeps twist labels: a
   right-handed twist stays right-handed and the rule reads the same from either end; an
   improper one (reflection) maps label ``t`` on ``e`` to ``-t`` on its image edge.

Limitations: an explicit radial order stored in a scaffold file is assumed to agree with
the geometry (the symmetry check is geometric).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .errors import LabelError, ScaffoldError
from .mesh import Scaffold

#: Modes of ``--symmetry`` (SPEC §2).
MODES = ("rotations", "isometries", "none")
MAX_AUTOMORPHISMS = 500_000


@dataclass(frozen=True, eq=False)
class SymmetryGroup:
    """The rigid motions mapping a scaffold onto itself (identity first).

    Attributes
    ----------
    matrices : (n_elements, 3, 3) float64
        Orthogonal part ``Q`` of each motion.
    translations : (n_elements, 3) float64
        Translation part ``tau`` (modulo the lattice for periodic scaffolds).
    vertex_perms : (n_elements, n_vertices) int64
        Image vertex of each vertex.
    edge_perms : (n_elements, n_edges) int64
        Image edge (class) of each edge.
    proper : (n_elements,) bool
        ``det Q = +1`` (a rotation) or not (a reflection / improper motion).
    """

    matrices: np.ndarray
    translations: np.ndarray
    vertex_perms: np.ndarray
    edge_perms: np.ndarray
    proper: np.ndarray

    @property
    def order(self) -> int:
        """Number of isometries (proper and improper)."""
        return int(len(self.proper))

    @property
    def n_rotations(self) -> int:
        """Number of proper motions (the rotation subgroup's order)."""
        return int(self.proper.sum())

    @cached_property
    def edge_signs(self) -> np.ndarray:
        """(n_elements,) int64: +1 for rotations, -1 for reflections (label ``t -> sign * t``)."""
        return np.where(self.proper, 1, -1).astype(np.int64)

    def mode_order(self, mode: str) -> int:
        """Order of the group used by ``mode`` (``rotations``, ``isometries``, ``none``)."""
        check_mode(mode)
        return {"rotations": self.n_rotations, "isometries": self.order, "none": 1}[mode]

    def action(self, mode: str) -> tuple[np.ndarray, np.ndarray]:
        """Distinct signed edge permutations of ``mode``'s group, identity first.

        Returns
        -------
        perms : (n_actions, n_edges) int64
            ``perms[g, e]``: the edge that edge ``e`` goes to.
        signs : (n_actions,) int64
            Label ``t`` on ``e`` becomes ``signs[g] * t`` on ``perms[g, e]``.

        Motions acting identically on labels (e.g. a half-turn that reverses an edge
        class of a periodic tiling onto itself) appear once, so ``n_actions`` divides
        :meth:`mode_order`.
        """
        check_mode(mode)
        n_edges = self.edge_perms.shape[1]
        if mode == "none":
            return np.arange(n_edges, dtype=np.int64)[None, :], np.ones(1, np.int64)
        keep = self.proper if mode == "rotations" else np.ones(self.order, bool)
        perms = self.edge_perms[keep]
        signs = self.edge_signs[keep] if mode == "isometries" else np.ones(int(keep.sum()), np.int64)
        table = np.column_stack([perms, signs])
        _, first = np.unique(table, axis=0, return_index=True)
        first = np.sort(first)  # identity (element 0) stays first
        return np.ascontiguousarray(perms[first]), np.ascontiguousarray(signs[first])


def check_mode(mode: str) -> str:
    if mode not in MODES:
        raise LabelError(f"unknown symmetry mode {mode!r}; choose one of {', '.join(MODES)}")
    return mode


def check_label_set(labels: np.ndarray, mode: str) -> None:
    """Isometries need a label set closed under negation (a mirror maps t to -t)."""
    if mode == "isometries":
        missing = sorted(set((-np.asarray(labels)).tolist()) - set(np.asarray(labels).tolist()))
        if missing:
            raise LabelError(
                f"--symmetry isometries maps label t to -t under reflections, but the label set "
                f"{np.asarray(labels).tolist()} lacks {missing}; use a set closed under negation or --symmetry rotations"
            )


def symmetry_group(scaffold: Scaffold) -> SymmetryGroup:
    """The rigid symmetry group of ``scaffold`` (cached on the scaffold object).

    Examples
    --------
    >>> from lkspace import load
    >>> g = symmetry_group(load("cube"))
    >>> g.order, g.n_rotations
    (48, 24)
    >>> symmetry_group(load("dihedron:5")).order
    20
    """
    cached = scaffold.__dict__.get("_symmetry_group")
    if cached is None:
        cached = _compute(scaffold)
        object.__setattr__(scaffold, "_symmetry_group", cached)
    return cached


# ---- combinatorial candidates ---------------------------------------------------------
def incidence_graph(scaffold: Scaffold):
    """The coloured vertex/edge/face incidence graph as ``(igraph.Graph, colours)``."""
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


def candidate_vertex_perms(scaffold: Scaffold) -> np.ndarray:
    """(n_candidates, n_vertices) int64: vertex parts of the incidence automorphisms.

    BLISS (igraph) gives generators of the automorphism group; the group is their closure,
    built breadth-first with numpy (much faster than listing automorphisms with VF2).
    """
    graph, colours = incidence_graph(scaffold)
    count = int(graph.count_automorphisms(color=colours))
    if count > MAX_AUTOMORPHISMS and not scaffold.periodic:
        return geometric_vertex_perms(scaffold)
    if count > MAX_AUTOMORPHISMS:
        raise ScaffoldError(
            f"{scaffold.name}: the incidence structure has {count} automorphisms (more than "
            f"{MAX_AUTOMORPHISMS}); use --symmetry none"
        )
    n = graph.vcount()
    gens = np.array(graph.automorphism_group(color=colours), dtype=np.int64).reshape(-1, n)
    elements = {np.arange(n, dtype=np.int64).tobytes()}
    frontier = np.arange(n, dtype=np.int64)[None, :]
    while len(frontier):
        products = gens[:, frontier].reshape(-1, n)  # g o x for every generator g and element x
        new = []
        for row in products:
            key = row.tobytes()
            if key not in elements:
                elements.add(key)
                new.append(row)
        frontier = np.array(new, dtype=np.int64).reshape(-1, n)
    if len(elements) != count:  # pragma: no cover - BLISS and the closure disagree
        raise ScaffoldError(f"{scaffold.name}: automorphism closure found {len(elements)} of {count} elements")
    perms = np.frombuffer(b"".join(elements), dtype=np.int64).reshape(-1, n)[:, : scaffold.n_vertices]
    return np.unique(perms, axis=0)


def geometric_vertex_perms(scaffold: Scaffold) -> np.ndarray:
    """Vertex permutations of rigid motions found from a vertex frame (finite scaffolds).

    Used when the incidence structure has too many automorphisms to list (e.g. a book of
    many pages): the images of vertex 0 and two of its neighbours fix the motion; every
    candidate motion maps all vertices by position and is kept when it preserves edges
    and faces.
    """
    from scipy.spatial import cKDTree

    x = scaffold.vertices - scaffold.vertices.mean(axis=0)
    tol = _tolerance(scaffold)
    ev = scaffold.edge_vertices
    nbrs = [set() for _ in range(scaffold.n_vertices)]
    for a, b in ev.tolist():
        nbrs[a].add(b)
        nbrs[b].add(a)
    v0 = 0
    ranked = sorted(nbrs[v0])
    v1 = ranked[0]
    v2 = max(ranked[1:], key=lambda w: np.linalg.norm(np.cross(x[v1] - x[v0], x[w] - x[v0])), default=None)
    frame = [v0, v1] + ([v2] if v2 is not None else [])
    norms = np.linalg.norm(x, axis=1)
    tree = cKDTree(x)
    faces = sorted(tuple(sorted(f)) for f in scaffold.faces())
    edges = {tuple(e) for e in ev.tolist()}
    found = set()

    def close(a, b):
        return abs(a - b) <= tol

    for w0 in range(scaffold.n_vertices):
        if not close(norms[w0], norms[v0]) or len(nbrs[w0]) != len(nbrs[v0]):
            continue
        for w1 in nbrs[w0]:
            if not close(norms[w1], norms[v1]) or not close(
                np.linalg.norm(x[w1] - x[w0]), np.linalg.norm(x[v1] - x[v0])
            ):
                continue
            for w2 in (nbrs[w0] - {w1}) if v2 is not None else [None]:
                if w2 is not None and (
                    not close(norms[w2], norms[v2])
                    or not close(np.linalg.norm(x[w2] - x[w1]), np.linalg.norm(x[v2] - x[v1]))
                ):
                    continue
                src = x[frame]
                dst = x[[w0, w1] + ([w2] if w2 is not None else [])]
                u, _, wt = np.linalg.svd(dst.T @ src)
                q0 = u @ wt
                _, sv, vt = np.linalg.svd(src)
                mirror = np.eye(3) - 2 * np.outer(vt[-1], vt[-1])
                for q in (q0, q0 @ mirror) if len(sv) < 3 or sv[-1] <= tol else (q0,):
                    if np.abs(src @ q.T - dst).max() > tol:
                        continue
                    dist, sigma = tree.query(x @ q.T)
                    if dist.max() > tol or len(np.unique(sigma)) != len(sigma):
                        continue
                    if {tuple(sorted((sigma[a], sigma[b]))) for a, b in ev.tolist()} != edges:
                        continue
                    if sorted(tuple(sorted(sigma[f].tolist())) for f in map(np.array, scaffold.faces())) != faces:
                        continue
                    found.add(sigma.astype(np.int64).tobytes())
    perms = np.frombuffer(b"".join(sorted(found)), dtype=np.int64).reshape(len(found), scaffold.n_vertices)
    return np.unique(perms, axis=0)


# ---- rigid-motion check ---------------------------------------------------------------
def _tolerance(scaffold: Scaffold) -> float:
    return 1e-6 * max(1.0, float(np.abs(scaffold.vertices).max()))


def _finite_motions(scaffold: Scaffold, sigmas: np.ndarray):
    x = scaffold.vertices - scaffold.vertices.mean(axis=0)
    tol = _tolerance(scaffold)
    _, sv, vt = np.linalg.svd(x, full_matrices=True)
    flat = sv[-1] <= tol if len(sv) == 3 else True
    normal = vt[-1]
    mirror = np.eye(3) - 2 * np.outer(normal, normal)
    for sigma in sigmas:
        y = x[sigma]
        u, _, wt = np.linalg.svd(y.T @ x)
        q0 = u @ wt
        for q in (q0, q0 @ mirror) if flat else (q0,):
            if np.abs(x @ q.T - y).max() <= tol:
                yield sigma, q, scaffold.vertices.mean(axis=0) - q @ scaffold.vertices.mean(axis=0), None


def lattice_point_group(scaffold: Scaffold) -> list[tuple[np.ndarray, np.ndarray]]:
    """Orthogonal ``Q`` with integer ``N`` such that ``B Q^T = N B`` (the lattice's point group)."""
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


def _face_keys(corner_keys: np.ndarray, face_starts: np.ndarray):
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


def _periodic_motions(scaffold: Scaffold, sigmas: np.ndarray):
    tol = _tolerance(scaffold)
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


def _edge_perm(scaffold: Scaffold, sigma: np.ndarray, lattice_part) -> np.ndarray | None:
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


def _compute(scaffold: Scaffold) -> SymmetryGroup:
    sigmas = candidate_vertex_perms(scaffold)
    motions = _periodic_motions(scaffold, sigmas) if scaffold.periodic else _finite_motions(scaffold, sigmas)
    rows = []
    seen = set()
    for sigma, q, tau, lattice_part in motions:
        key = (sigma.tobytes(), np.round(q, 6).tobytes())
        if key in seen:
            continue
        perm = _edge_perm(scaffold, sigma, lattice_part)
        if perm is None:
            continue
        seen.add(key)
        rows.append((sigma, q, tau, perm, np.linalg.det(q) > 0))
    # identity first
    rows.sort(key=lambda r: not (np.allclose(r[1], np.eye(3)) and np.array_equal(r[0], np.arange(len(r[0])))))
    if not rows or not np.allclose(rows[0][1], np.eye(3)):
        raise ScaffoldError(f"{scaffold.name}: symmetry search failed to find the identity")  # pragma: no cover
    sig, qs, taus, perms, proper = zip(*rows, strict=True)
    arrays = [
        np.array(sig, np.int64),
        np.array(qs, np.float64),
        np.array(taus, np.float64),
        np.array(perms, np.int64),
        np.array(proper, bool),
    ]
    for a in arrays:
        a.setflags(write=False)
    return SymmetryGroup(
        matrices=arrays[1], translations=arrays[2], vertex_perms=arrays[0], edge_perms=arrays[3], proper=arrays[4]
    )
