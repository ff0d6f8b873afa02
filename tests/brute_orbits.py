"""Brute-force orbit computation (tests only): every assignment, every group element.

Independent of the residue-class walk of :mod:`lkspace.design.walk`: it codes all
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
    lo = int(labels.min())
    lab_index = np.full(int(labels.max()) - lo + 1, -1, np.int64)
    lab_index[labels - lo] = np.arange(len(labels))
    res_index = np.full((n_e, int(k.max())), -1, np.int64)
    radix = []
    for e in range(n_e):
        res = np.unique(labels % k[e])
        res_index[e, res] = np.arange(len(res))
        radix.append(len(res))
    radix += [len(labels)] * n_e
    weights = np.cumprod([1, *radix[::-1]])[:-1][::-1].astype(np.int64)  # digit 0 most significant
    assert float(np.prod(np.array(radix, np.float64))) < 2**62
    w_res, w_lab = weights[:n_e], weights[n_e:]
    values = np.arange(lo, int(labels.max()) + 1)
    ok = lab_index[values - lo] >= 0
    # table[j, v - lo]: key contribution of label v on edge j (0 where v is not a label)
    table = np.zeros((n_e, len(values)), np.int64)
    for j in range(n_e):
        table[j, ok] = res_index[j, values[ok] % k[j]] * w_res[j] + lab_index[values[ok] - lo] * w_lab[j]
    shifted = (t - lo).astype(np.int64)
    neg = (-t - lo).astype(np.int64) if np.all(np.isin(-labels, labels)) else None

    def image_key(perm, sign):
        src = shifted if sign == 1 else neg
        out = np.zeros(n_all, np.int64)
        for e in range(n_e):
            out += table[perm[e], src[:, e]]
        return out

    own = image_key(np.arange(n_e), 1)
    best = own.copy()
    stab = np.zeros(n_all, np.int64)
    perms, signs = space.action
    for perm, s in zip(perms, signs, strict=True):
        code = image_key(perm, s)
        np.minimum(best, code, out=best)
        stab += code == own
    reps = np.flatnonzero(best == own)
    return t[reps], len(signs) // stab[reps]
