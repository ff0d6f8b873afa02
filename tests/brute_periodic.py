"""Brute-force symmetry group of a periodic scaffold and Burnside design counts (tests only).

Independent of :mod:`lkspace.symmetry`: it reads only the scaffold's raw data (vertex
positions, lattice basis, face corners with their lattice offsets) and

1. lists every integer matrix ``N`` with entries in ``-bound..bound`` whose rows ``N B``
   are lattice vectors as long as the basis vectors, and keeps those for which
   ``Q^T = B^-1 N B`` (with the plane's normal sent to ``+-`` itself for a 2D lattice)
   is orthogonal;
2. for each such ``Q`` tries every translation taking vertex 0 onto some vertex,
   ``tau = p_j - Q p_0``, and keeps the motion when every vertex lands on a vertex up to
   a lattice vector (checked against every vertex), every face (a cyclic corner sequence
   up to translation) on a face and every edge on an edge;
3. counts designs (orbits of label assignments) with Burnside's lemma over that group:
   a cycle of ``L`` edges under a motion of sign ``s`` fixes ``|S|`` labellings if
   ``s^L = 1`` and only the all-zero one otherwise.
"""

from __future__ import annotations

import itertools
from fractions import Fraction

import numpy as np

TOL = 1e-6


def lattice_maps(basis: np.ndarray, bound: int) -> list[tuple[np.ndarray, np.ndarray]]:
    """Every ``(Q, N)``, ``N`` with entries in ``-bound..bound``, such that ``B Q^T = N B`` and ``Q`` is orthogonal."""
    dim = len(basis)
    rows = np.array(list(itertools.product(range(-bound, bound + 1), repeat=dim)))
    lengths = np.linalg.norm(rows @ basis, axis=1)
    choices = [rows[np.abs(lengths - np.linalg.norm(b)) < TOL] for b in basis]
    normal = np.cross(basis[0], basis[1])
    normal = normal / np.linalg.norm(normal)
    out = []
    for combo in itertools.product(*choices):
        n = np.array(combo)
        for s in (1, -1) if dim == 2 else (1,):
            frame = np.vstack([basis, normal]) if dim == 2 else basis
            target = np.vstack([n @ basis, s * normal]) if dim == 2 else n @ basis
            qt = np.linalg.solve(frame, target)
            if np.allclose(qt.T @ qt, np.eye(3), atol=1e-9):
                out.append((qt.T, n))
    return out


def _locate(x, positions, basis, pinv):
    """``(u, k)``: vertex ``u`` and integer offset ``k`` with ``p_u + k B = x``, or None."""
    f = (x - positions) @ pinv
    k = np.round(f)
    err = np.abs(positions + k @ basis - x).max(axis=1)
    hits = np.flatnonzero(err < TOL)
    if len(hits) != 1:
        return None
    return int(hits[0]), tuple(int(c) for c in k[hits[0]])


def _cyclic_key(corners):
    """Canonical cyclic sequence of ``(vertex, offset)`` corners, up to rotation, reversal and translation."""
    best = None
    m = len(corners)
    for d in (1, -1):
        seq = corners[::d]
        for r in range(m):
            rot = seq[r:] + seq[:r]
            o0 = np.array(rot[0][1])
            key = tuple((v, tuple((np.array(o) - o0).tolist())) for v, o in rot)
            best = key if best is None or key < best else best
    return best


def _edge_key(u, ou, w, ow):
    """Undirected edge between corners ``(u, ou)`` and ``(w, ow)``, up to translation."""
    d = tuple((np.array(ow) - np.array(ou)).tolist())
    minus = tuple(-c for c in d)
    zero = (0,) * len(d)
    return min(((u, zero), (w, d)), ((w, zero), (u, minus)))


def _faces_and_edges(scaffold):
    corners = scaffold.corners.tolist()
    offsets = [tuple(o) for o in scaffold.corner_offsets.tolist()]
    starts = scaffold.face_starts.tolist()
    faces = []
    for f in range(len(starts) - 1):
        faces.append([(corners[c], offsets[c]) for c in range(starts[f], starts[f + 1])])
    edges = set()
    for face in faces:
        for (u, ou), (w, ow) in zip(face, face[1:] + face[:1], strict=True):
            edges.add(_edge_key(u, ou, w, ow))
    return faces, sorted(edges)


def brute_group(scaffold, bound: int) -> list[tuple[int, tuple[int, ...]]]:
    """Every symmetry of the quotient as ``(sign of det Q, edge permutation)`` over the brute edge order."""
    positions = scaffold.vertices
    basis = scaffold.lattice.basis
    pinv = np.linalg.pinv(basis)
    faces, edges = _faces_and_edges(scaffold)
    face_set = {_cyclic_key(face) for face in faces}
    edge_index = {e: i for i, e in enumerate(edges)}
    out = []
    for q, n in lattice_maps(basis, bound):
        for j in range(len(positions)):
            tau = positions[j] - q @ positions[0]
            where = [_locate(q @ p + tau, positions, basis, pinv) for p in positions]
            if any(w is None for w in where) or len({w[0] for w in where}) != len(where):
                continue

            def image(v, o, where=where, n=n):
                u, k = where[v]
                return u, tuple((np.array(k) + np.array(o) @ n).tolist())

            if {_cyclic_key([image(v, o) for v, o in face]) for face in faces} != face_set:
                continue
            perm = []
            for (u, ou), (w, ow) in edges:
                key = _edge_key(*image(u, ou), *image(w, ow))
                perm.append(edge_index.get(key, -1))
            if -1 in perm or len(set(perm)) != len(perm):
                continue
            out.append((1 if np.linalg.det(q) > 0 else -1, tuple(perm)))
    return out


def burnside(group, labels, mode: str) -> int:
    """Number of orbits of labellings (each edge a label of ``labels``) under ``group`` in ``mode``."""
    if mode == "rotations":
        group = [(1, perm) for sign, perm in group if sign == 1]
    size = len(labels)
    total = Fraction(0)
    for sign, perm in group:
        seen = [False] * len(perm)
        fixed = 1
        for start in range(len(perm)):
            length, e = 0, start
            while not seen[e]:
                seen[e] = True
                e = perm[e]
                length += 1
            if length:
                fixed *= size if sign**length == 1 else int(0 in labels)
        total += fixed
    count = total / len(group)
    assert count.denominator == 1
    return int(count)
