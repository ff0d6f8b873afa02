"""Brute-force orbit computation (tests only): every assignment, every group element.

Independent of the residue-class walk of :mod:`lkspace.enumerate`: it codes all
``|SET|^edges`` assignments, applies every signed edge permutation and keeps, per orbit,
the member with the smallest key (residue indices per edge, then label indices per
edge: the catalog's canonical rule).
"""

from __future__ import annotations

import numpy as np


def brute_orbits(space):
    """``(representatives (n, n_edges) int64, orbit_sizes (n,) int64)`` sorted by key."""
    labels = space.walk_labels
    n_e = space.scaffold.n_edges
    k = space.moduli
    n_all = len(labels) ** n_e
    assert n_all <= 2_000_000, "brute force is for small spaces"
    idx = np.stack(np.unravel_index(np.arange(n_all), (len(labels),) * n_e), axis=1)
    t = labels[idx]
    res_sets = [np.unique(labels % kk) for kk in k]
    dims = tuple(len(r) for r in res_sets) + (len(labels),) * n_e

    def key(a):
        res = np.stack([np.searchsorted(res_sets[e], a[:, e] % k[e]) for e in range(n_e)], axis=1)
        lab = np.searchsorted(labels, a)
        return np.ravel_multi_index(tuple(np.concatenate([res, lab], axis=1).T), dims)

    own = key(t)
    best = own.copy()
    stab = np.zeros(n_all, np.int64)
    perms, signs = space.action
    for perm, s in zip(perms, signs, strict=True):
        img = np.empty_like(t)
        img[:, perm] = s * t
        code = key(img)
        np.minimum(best, code, out=best)
        stab += code == own
    reps = np.flatnonzero(best == own)
    return t[reps], len(signs) // stab[reps]
