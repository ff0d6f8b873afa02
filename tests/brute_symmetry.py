"""Slow reference for the symmetries of a small mesh within a tolerance (tests only).

Independent of :mod:`lkspace.symmetry`: every permutation of the vertices is tried; it is
kept when it maps the faces (as vertex cycles, up to rotation and reversal) onto the
faces and some orthogonal map (about the centroid) moves every vertex to within ``tol``
of its image.  Designs up to a group are counted with Burnside's lemma over its edge
permutations: ``(1 / |G|) sum_g |SET| ** cycles(g)``.
"""

from __future__ import annotations

import itertools
from fractions import Fraction

import numpy as np


def _cycle_key(face):
    """A face as a cycle of vertices, the same for every rotation and reversal."""
    face = list(face)
    turns = [face[i:] + face[:i] for i in range(len(face))]
    return min(min(tuple(t) for t in turns), min(tuple(reversed(t)) for t in turns))


def brute_motions(vertices, faces, tol):
    """Return ``[(vertex perm tuple, proper bool)]`` of every symmetry of the mesh within ``tol``."""
    x = np.asarray(vertices, float)
    x = x - x.mean(axis=0)
    n = len(x)
    face_keys = sorted(_cycle_key(f) for f in faces)
    edges = {tuple(sorted((f[i], f[(i + 1) % len(f)]))) for f in faces for i in range(len(f))}
    out = []
    for perm in itertools.permutations(range(n)):
        if any(tuple(sorted((perm[a], perm[b]))) not in edges for a, b in edges):
            continue
        if sorted(_cycle_key([perm[v] for v in f]) for f in faces) != face_keys:
            continue
        y = x[list(perm)]
        u, _, wt = np.linalg.svd(y.T @ x)
        for q in (u @ wt, u @ np.diag([1, 1, -1]) @ wt):  # best fits of each handedness
            if np.linalg.norm(x @ q.T - y, axis=1).max() <= tol:
                out.append((perm, bool(np.linalg.det(q) > 0)))
    return sorted(set(out))


def burnside_designs(vertices, faces, motions, n_labels):
    """Designs up to the rotations in ``motions``: orbits of edge labellings with ``n_labels`` labels."""
    edges = sorted({tuple(sorted((f[i], f[(i + 1) % len(f)]))) for f in faces for i in range(len(f))})
    index = {e: i for i, e in enumerate(edges)}
    total, order = Fraction(0), 0
    for perm, proper in motions:
        if not proper:
            continue
        image = [index[tuple(sorted((perm[a], perm[b])))] for a, b in edges]
        seen, cycles = set(), 0
        for e in range(len(edges)):
            if e not in seen:
                cycles += 1
                while e not in seen:
                    seen.add(e)
                    e = image[e]
        total += n_labels**cycles
        order += 1
    assert total % order == 0, "Burnside's sum is a multiple of the group order"
    return int(total / order)
