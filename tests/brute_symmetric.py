"""Brute force for symmetric designs (tests only), sharing no code with ``lkspace.symmetry``.

The symmetries come straight from the vertex coordinates: every orthogonal map sending two
reference vertex vectors (and their cross product, up to sign) to two vertex vectors, kept
when it maps the vertex set and the faces onto themselves.  A motion is its 3x3 matrix
(the scaffolds are finite and centred).  Labels are then pushed around by the matrices.
"""

from __future__ import annotations

import functools
import itertools
from collections import Counter

import numpy as np


def raw_edges(faces):
    """Edges as sorted vertex pairs in lexicographic order (the numbering of SPEC.md)."""
    pairs = {tuple(sorted((f[i], f[(i + 1) % len(f)]))) for f in faces for i in range(len(f))}
    return sorted(pairs)


def key(q):
    """Exact key of a matrix (rounded; ``-0.0`` and ``0.0`` alike)."""
    return (np.round(q, 6) + 0.0).tobytes()


def motions(vertices, faces):
    """List of ``(Q (3,3), sigma (n,) vertex images)`` for every symmetry of a finite scaffold."""
    v = np.asarray(vertices, float)
    v = v - v.mean(axis=0)
    n = len(v)
    a, b = next((i, j) for i, j in itertools.combinations(range(n), 2) if np.linalg.norm(np.cross(v[i], v[j])) > 1e-6)
    face_key = Counter(tuple(sorted(f)) for f in faces)
    src = np.column_stack([v[a], v[b], np.cross(v[a], v[b])])
    found = {}
    for a2, b2 in itertools.permutations(range(n), 2):
        for sign in (1, -1):
            dst = np.column_stack([v[a2], v[b2], sign * np.cross(v[a2], v[b2])])
            q = dst @ np.linalg.inv(src)
            if not np.allclose(q @ q.T, np.eye(3), atol=1e-6):
                continue
            image = v @ q.T
            dist = np.linalg.norm(image[:, None, :] - v[None, :, :], axis=2)
            sigma = dist.argmin(axis=1)
            if not np.allclose(dist[np.arange(n), sigma], 0, atol=1e-6) or len(set(sigma.tolist())) != n:
                continue
            if Counter(tuple(sorted(sigma[x] for x in f)) for f in faces) != face_key:
                continue
            found[key(q)] = (q, sigma)
    return list(found.values())


def signed_edge_action(q, sigma, edges):
    """``(perm, sign)``: edge ``e`` goes to ``perm[e]``; labels are multiplied by ``sign``."""
    index = {e: i for i, e in enumerate(edges)}
    perm = np.array([index[tuple(sorted((int(sigma[a]), int(sigma[b]))))] for a, b in edges])
    return perm, int(round(np.linalg.det(q)))


def apply(labels, perm, sign):
    """Images ``(m, n_edges)`` of label rows ``(m, n_edges)`` under one signed edge permutation."""
    out = np.empty_like(labels)
    out[:, perm] = sign * labels
    return out


@functools.lru_cache(maxsize=4)
def _assignments(label_set, n_edges):
    rows = np.array(list(itertools.product(label_set, repeat=n_edges)), np.int64)
    rows.setflags(write=False)
    return rows


def all_assignments(label_set, n_edges):
    """Every assignment, ``(|SET|^n_edges, n_edges)`` int64, lexicographic (read-only, cached)."""
    return _assignments(tuple(label_set), n_edges)


def fixed_rows(rows, actions):
    """The rows fixed by every signed edge permutation of ``actions``."""
    keep = np.ones(len(rows), bool)
    for perm, sign in actions:
        keep &= np.all(apply(rows, perm, sign) == rows, axis=1)
    return rows[keep]


def normalizer(group, subgroup):
    """Matrices of ``group`` conjugating the matrix set ``subgroup`` onto itself."""
    keys = {key(h) for h in subgroup}
    return [g for g in group if {key(g @ h @ g.T) for h in subgroup} == keys]


def orbit_table(rows, actions, moduli):
    """``{canonical row: orbit size}`` of ``rows`` under ``actions`` (canonical: least (t mod K, t))."""
    keys = []
    for perm, sign in actions:
        img = apply(rows, perm, sign)
        keys.append(np.concatenate([img % moduli, img], axis=1))
    stack = np.stack(keys)  # (n_a, m, 2 n_edges)
    out: Counter = Counter()
    for i in range(len(rows)):
        best = min(tuple(k) for k in stack[:, i, :].tolist())
        out[best[len(moduli) :]] += 1
    return dict(out)
