"""Symmetries of a periodic scaffold: affine isometries of the infinite mesh, modulo its lattice.

A symmetry of the quotient is a motion ``x -> Q x + tau`` of space that carries the
infinite periodic mesh onto itself and the scaffold's lattice ``L`` onto itself; two
motions differing by a translation of ``L`` are one.  So ``Q`` lies in the point group
of ``L`` (:mod:`~lkspace.symmetry.lattice_group`: every one, whatever the size of the
entries of ``N``), and ``tau`` may be any vector: a lattice translation of the original
cell inside a supercell, a non-lattice translation, a screw or glide part.

Each motion is built directly (no incidence-graph automorphisms):

* a motion maps an *anchor* vertex (from the rarest kind: corner and edge counts) onto a
  vertex of its kind, which fixes ``tau = p_j - Q p_anchor`` for each candidate ``j``;
* every vertex is then mapped and matched with a periodic KD-tree on lattice coordinates;
  a match within the tolerance gives an exact integer key, vertex ``sigma[v]`` plus
  lattice offset ``offsets[v]`` (``Q p_v + tau = p_sigma[v] + offsets[v] @ B``);
* the motion is kept when every face, as a cyclic sequence of (vertex, offset) corners up
  to translation, is again a face, and every edge again an edge.  A corner ``(v, o)`` goes
  to ``(sigma[v], offsets[v] + o @ N)``.

A few sample vertices reject most candidates before the full check.  The group is
``T x reps``: the translation subgroup ``T`` (closed from its verified generators by the
images of the anchor, an integer key per element) and one verified motion per point
operation that has one (a translation ``tau`` works for ``Q`` exactly when ``tau + t``
does for every ``t`` in ``T``, so one target per orbit of ``T`` is tried).  The order
costs ``O(size)`` memory and about ``O(size x (generators + point operations))`` time;
the tables, composed afterwards, ``O(order x size)``.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..model.scaffold import Scaffold, unique_rows
from ..runtime.progress import task
from .lattice_group import PointOperation, point_group

SAMPLE = 16
"""Vertices checked on every candidate motion before the full check."""
CHUNK = 1024
"""Candidate translations sample-checked at once."""
FEW_VERTICES = 64
"""Scaffolds with at most this many vertices are matched by comparing every pair (numpy), not with
scipy's KD-tree, whose import costs more than their whole search."""


@dataclass(frozen=True)
class PeriodicMotion:
    """One verified symmetry of a periodic scaffold.

    Attributes
    ----------
    sigma : (n_vertices,) int64
        Image vertex of each vertex.
    offsets : (n_vertices, dim) int64
        ``Q p_v + tau = p_sigma[v] + offsets[v] @ basis``.
    q : (3, 3) float64
    n : (dim, dim) int64
        ``basis Q^T = n basis``.
    tau : (3,) float64
    edge_perm : (n_edges,) int64
        Image edge of each edge.
    """

    sigma: np.ndarray
    offsets: np.ndarray
    q: np.ndarray
    n: np.ndarray
    tau: np.ndarray
    edge_perm: np.ndarray

    def after(self, other: PeriodicMotion) -> PeriodicMotion:
        """Return the motion ``self o other`` (first ``other``, then ``self``)."""
        return PeriodicMotion(
            sigma=self.sigma[other.sigma],
            offsets=self.offsets[other.sigma] + other.offsets @ self.n,
            q=self.q @ other.q,
            n=other.n @ self.n,
            tau=self.q @ other.tau + self.tau,
            edge_perm=self.edge_perm[other.edge_perm],
        )


class PeriodicSearch:
    """Candidate motions of one periodic scaffold, checked as the module docstring says."""

    def __init__(self, scaffold: Scaffold, tol: float) -> None:
        assert scaffold.lattice is not None, "a periodic search needs a lattice"
        self.scaffold = scaffold
        self.tol = tol
        self.basis = scaffold.lattice.basis
        self.pinv = np.linalg.pinv(self.basis)
        self.positions = scaffold.vertices
        self.fractional = self.positions @ self.pinv
        self.tree = None
        if scaffold.n_vertices > FEW_VERTICES:
            from scipy.spatial import cKDTree

            self.tree = cKDTree(_wrap(self.fractional), boxsize=1.0)
        kinds = np.column_stack(
            [
                np.bincount(scaffold.corners, minlength=scaffold.n_vertices),
                np.bincount(scaffold.edge_vertices.reshape(-1), minlength=scaffold.n_vertices),
            ]
        )
        _, kind = unique_rows(kinds)
        counts = np.bincount(kind)
        self.anchor = int(np.flatnonzero(kind == np.argmin(counts))[0])
        self.targets = np.flatnonzero(kind == kind[self.anchor])
        n = scaffold.n_vertices
        self.sample = np.unique(np.r_[self.anchor, np.linspace(0, n - 1, min(n, SAMPLE)).astype(np.int64)])
        self.faces = face_keys(scaffold.corner_keys, scaffold.face_starts)

    @cached_property
    def operations(self) -> list[PointOperation]:
        """The lattice's point group, the identity first."""
        return point_group(self.basis, self.tol)

    def match(self, images: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Vertex, lattice offset and ``ok`` of points ``images (..., 3)`` (``ok``: a vertex within ``tol``)."""
        frac = images @ self.pinv
        sigma = self.tree.query(_wrap(frac))[1] if self.tree is not None else self._nearest(frac)
        offsets = np.rint(frac - self.fractional[sigma]).astype(np.int64)
        landed = self.positions[sigma] + offsets @ self.basis
        ok = np.all(np.abs(landed - images) <= self.tol, axis=-1)
        return sigma, offsets, ok

    def _nearest(self, frac: np.ndarray) -> np.ndarray:
        """(...,) int64: the vertex nearest each point ``frac (..., dim)`` in lattice coordinates modulo the lattice.

        The KD-tree's answer (the same periodic distance), by comparing every pair.
        """
        diff = frac[..., None, :] - self.fractional
        diff -= np.round(diff)
        return np.argmin(np.einsum("...ij,...ij->...i", diff, diff), axis=-1)

    def candidates(self, q: np.ndarray, targets: np.ndarray) -> np.ndarray:
        """(m,) int64: the ``targets`` whose ``tau = p_j - Q p_anchor`` maps the sample vertices onto vertices."""
        taus = self.positions[targets] - q @ self.positions[self.anchor]
        images = (self.positions[self.sample] @ q.T)[None, :, :] + taus[:, None, :]
        _, _, ok = self.match(images)
        return targets[np.all(ok, axis=1)]

    def verify(self, op: PointOperation, target: int) -> PeriodicMotion | None:
        """Return the motion with point part ``op`` taking the anchor to vertex ``target``, or None if it is no symmetry."""
        q, n, _ = op
        sc = self.scaffold
        tau = self.positions[target] - q @ self.positions[self.anchor]
        sigma, offsets, ok = self.match(self.positions @ q.T + tau)
        if not ok.all() or len(np.unique(sigma)) != len(sigma):
            return None
        assert sc.corner_offsets is not None
        image = np.column_stack([sigma[sc.corners], offsets[sc.corners] + sc.corner_offsets @ n])
        if not np.array_equal(face_keys(image, sc.face_starts), self.faces):
            return None
        perm = edge_permutation(sc, sigma, offsets, n)
        if perm is None:
            return None
        return PeriodicMotion(sigma=sigma, offsets=offsets, q=q, n=n, tau=tau, edge_perm=perm)

    def first(self, op: PointOperation, targets: np.ndarray) -> PeriodicMotion | None:
        """Return the first verified motion with point part ``op`` taking the anchor into ``targets``, or None."""
        for start in range(0, len(targets), CHUNK):
            for target in self.candidates(op[0], targets[start : start + CHUNK]).tolist():
                motion = self.verify(op, target)
                if motion is not None:
                    return motion
        return None


@dataclass(frozen=True)
class PeriodicSymmetry:
    """The symmetry group of a periodic scaffold: translations ``T`` times one motion per point operation.

    Attributes
    ----------
    generators : list of PeriodicMotion
        Verified generators of ``T``.
    translation_tree : (n_translations, 2) int64
        Element ``i`` of ``T`` is ``generators[tree[i, 1]] o element[tree[i, 0]]`` (row 0,
        the identity, is ``(-1, -1)``).
    representatives : list of PeriodicMotion
        One motion per point operation of the group (identity first).
    """

    generators: list[PeriodicMotion]
    translation_tree: np.ndarray
    representatives: list[PeriodicMotion]

    @property
    def order(self) -> int:
        """Number of isometries."""
        return len(self.translation_tree) * len(self.representatives)

    @property
    def n_rotations(self) -> int:
        """Number of proper motions."""
        return len(self.translation_tree) * int(sum(np.linalg.det(r.q) > 0 for r in self.representatives))

    def translations(self) -> list[PeriodicMotion]:
        """Return the elements of ``T``, composed along :attr:`translation_tree`; the identity first."""
        out = [self.representatives[0]]
        for parent, g in self.translation_tree[1:].tolist():
            out.append(self.generators[g].after(out[parent]))
        return out

    def elements(self) -> Iterator[PeriodicMotion]:
        """Yield every motion ``t o r`` (translations inner), the identity first."""
        translations = self.translations()
        for r in self.representatives:
            for t in translations:
                yield t.after(r)


def periodic_symmetry(scaffold: Scaffold, tol: float) -> PeriodicSymmetry:
    """Find the translation subgroup and a motion per point operation (see the module docstring)."""
    search = PeriodicSearch(scaffold, tol)
    identity = search.verify(search.operations[0], search.anchor)
    assert identity is not None, "the identity must be a symmetry"
    generators, tree = _translation_group(search)
    # tau fails for Q iff tau + t fails for every t in T: one target per T-orbit suffices
    orbit = _orbits(scaffold.n_vertices, generators)
    _, first = np.unique(orbit[search.targets], return_index=True)
    targets = search.targets[np.sort(first)]
    representatives = [identity]
    with task("symmetry search", total=len(search.operations)) as step:
        for op in search.operations[1:]:
            motion = search.first(op, targets)
            if motion is not None:
                representatives.append(motion)
            step.advance()
    return PeriodicSymmetry(generators=generators, translation_tree=tree, representatives=representatives)


def _translation_group(search: PeriodicSearch) -> tuple[list[PeriodicMotion], np.ndarray]:
    """Return generators of the translation subgroup and its tree (see :class:`PeriodicSymmetry`).

    Elements are keyed by the anchor's image, an integer: ``g o h`` takes it to
    ``g.sigma[key(h)]``, so closing under the generators costs one integer per element.
    """
    op = search.operations[0]
    keys = [search.anchor]
    index = {search.anchor: 0}
    tree = [(-1, -1)]
    generators: list[PeriodicMotion] = []
    for target in search.candidates(op[0], search.targets).tolist():
        if target in index:
            continue
        motion = search.verify(op, target)
        if motion is None:
            continue
        generators.append(motion)
        frontier = list(range(len(keys)))
        while frontier:
            new = []
            for g, gen in enumerate(generators):
                for h, key in zip(frontier, gen.sigma[[keys[h] for h in frontier]].tolist(), strict=True):
                    if key not in index:
                        index[key] = len(keys)
                        keys.append(key)
                        tree.append((h, g))
                        new.append(index[key])
            frontier = new
    return generators, np.array(tree, np.int64).reshape(-1, 2)


def _orbits(n_vertices: int, generators: list[PeriodicMotion]) -> np.ndarray:
    """(n_vertices,) int64: the orbit label of each vertex under the translations ``generators``."""
    if not generators:  # the identity alone: every vertex is its own orbit (and scipy stays unloaded)
        return np.arange(n_vertices, dtype=np.int64)
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    rows = np.concatenate([np.arange(n_vertices)] * len(generators) or [np.zeros(0, np.int64)])
    cols = np.concatenate([g.sigma for g in generators] or [np.zeros(0, np.int64)])
    graph = coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(n_vertices, n_vertices))
    return connected_components(graph, directed=True, connection="weak")[1].astype(np.int64)


def face_keys(corner_keys: np.ndarray, face_starts: np.ndarray) -> np.ndarray:
    """(n_faces, ...) int64, rows sorted: each face as its cyclic corner sequence, canonical up to translation.

    A face's key is the lexicographically smallest of its corner sequences (every start,
    both directions) with the start's offset subtracted: an exact integer fingerprint.
    A face whose smallest vertex occurs once starts there (one comparison picks the
    direction); the others compare every start (in chunks).  Faces of several sizes are
    padded with -1.
    """
    sizes = np.diff(face_starts)
    width = int(sizes.max()) * corner_keys.shape[1]
    rows = np.full((len(sizes), width), -1, np.int64)
    for m in np.unique(sizes).tolist():
        faces = np.flatnonzero(sizes == m)
        block = corner_keys[face_starts[faces][:, None] + np.arange(m)]  # (f, m, 1 + dim)
        verts = block[:, :, 0]
        first = np.argmin(verts, axis=1)
        unique = np.sum(verts == verts[np.arange(len(faces)), first][:, None], axis=1) == 1
        steps = np.arange(m)
        fwd = block[np.arange(len(faces))[:, None], (first[:, None] + steps) % m]
        rev = block[np.arange(len(faces))[:, None], (first[:, None] - steps) % m]
        fwd[:, :, 1:] -= fwd[:, :1, 1:]
        rev[:, :, 1:] -= rev[:, :1, 1:]
        diff = (fwd - rev).reshape(len(faces), -1)  # the whole sequences: their second corners may tie
        lead = diff[np.arange(len(faces)), np.argmax(diff != 0, axis=1)]
        chosen = np.where((lead <= 0)[:, None, None], fwd, rev).reshape(len(faces), -1)
        rows[faces[unique], : chosen.shape[1]] = chosen[unique]
        for start in range(0, int((~unique).sum()), CHUNK):
            some = faces[~unique][start : start + CHUNK]
            rows[some, : chosen.shape[1]] = _smallest_sequences(block[np.searchsorted(faces, some)])
    return rows[np.lexsort(rows.T[::-1])]


def _smallest_sequences(block: np.ndarray) -> np.ndarray:
    """(f, m * c) int64: per face of ``block (f, m, c)`` the smallest normalized sequence (every start, both ways)."""
    f, m, c = block.shape
    steps = np.arange(m)
    starts = np.r_[(steps[:, None] + steps) % m, (steps[:, None] - steps) % m]  # (2m, m): forward, then backward
    seqs = block[:, starts]  # (f, 2m, m, c)
    seqs[..., 1:] -= seqs[:, :, :1, 1:]
    flat = seqs.reshape(f, 2 * m, m * c)
    alive = np.ones((f, 2 * m), bool)
    for col in range(m * c):  # lexicographic minimum over the 2m sequences of each face
        values = np.where(alive, flat[:, :, col], np.iinfo(np.int64).max)
        alive &= values == values.min(axis=1, keepdims=True)
    return flat[np.arange(f), np.argmax(alive, axis=1)]


def edge_permutation(scaffold: Scaffold, sigma: np.ndarray, offsets: np.ndarray, n: np.ndarray) -> np.ndarray | None:
    """(n_edges,) int64: image edge of each edge under the motion, or None if one is no edge."""
    keys = scaffold.edge_keys
    a, b = sigma[keys[:, 0]], sigma[keys[:, 1]]
    delta = offsets[keys[:, 1]] + keys[:, 2:] @ n - offsets[keys[:, 0]]
    nz = delta != 0
    first = delta[np.arange(len(delta)), np.argmax(nz, axis=1)]
    forward = (a < b) | ((a == b) & (first > 0))
    image = np.column_stack(
        [np.where(forward, a, b), np.where(forward, b, a), np.where(forward[:, None], delta, -delta)]
    )
    _, inverse = unique_rows(np.concatenate([keys, image]))
    slot = np.full(2 * len(keys), -1, np.int64)
    slot[inverse[: len(keys)]] = np.arange(len(keys))
    perm = slot[inverse[len(keys) :]]
    if np.any(perm < 0) or len(np.unique(perm)) != len(perm):
        return None
    return perm


def _wrap(frac: np.ndarray) -> np.ndarray:
    """Lattice coordinates wrapped into ``[0, 1)`` (for the periodic KD-tree)."""
    wrapped = np.mod(frac, 1.0)
    wrapped[wrapped >= 1.0] = 0.0
    return wrapped
