"""The point group of a lattice: every orthogonal ``Q`` mapping the lattice onto itself.

``Q`` maps the lattice ``L`` (basis rows ``B``, ``dim`` of them) onto itself when
``B Q^T = N B`` for an integer matrix ``N`` (row ``i`` of ``N``: the lattice coordinates
of ``Q b_i``).  ``Q`` preserves lengths, so ``Q b_i`` is a lattice vector as long as
``b_i``: the candidates for the images of a basis are the lattice vectors of those
lengths, found exactly (no bounded grid of ``N``) by enumerating the coordinates allowed
by the dual basis, ``|c_i| <= r * |d_i|`` for a vector of length ``r``.  The basis is
LLL-reduced first (a unimodular change of basis ``U``), which keeps that box small for
any supercell or skewed basis; ``N`` is reported in the caller's basis,
``N = U^-1 N_red U``.  A choice of images is kept when its Gram matrix equals the
basis's (see :func:`point_group` for how the last image is found).

For a 2D lattice in 3D space each in-plane map gives two motions of space: ``Q`` keeps
or reverses the plane's normal (turning the plane over is a rotation of space).
"""

from __future__ import annotations

import itertools

import numpy as np

from ..model.lattice import lll_reduce

PointOperation = tuple[np.ndarray, np.ndarray, int]
"""``(Q (3, 3) float64, N (dim, dim) int64, s)``: ``B Q^T = N B``, ``s = +-1`` the image of a 2D lattice's normal."""


def short_vectors(basis: np.ndarray, radius: float) -> tuple[np.ndarray, np.ndarray]:
    """Every nonzero lattice vector of length at most ``radius``: ``(coords (m, dim) int64, vectors (m, 3))``."""
    gram = basis @ basis.T
    reach = np.floor(radius * np.sqrt(np.diag(np.linalg.inv(gram))) + 1e-9).astype(np.int64)
    axes = [np.arange(-r, r + 1) for r in reach]
    coords = np.array(list(itertools.product(*axes)), dtype=np.int64).reshape(-1, len(basis))
    vectors = coords @ basis
    keep = (np.einsum("ij,ij->i", vectors, vectors) <= radius**2) & np.any(coords != 0, axis=1)
    return coords[keep], vectors[keep]


def point_group(basis: np.ndarray, tol: float) -> list[PointOperation]:
    """Every orthogonal ``Q`` with ``basis Q^T = N basis``, ``N`` integer; the identity first.

    The images of the first ``dim - 1`` reduced basis vectors are picked among the lattice
    vectors of their lengths (with their Gram matrix); they fix ``Q`` up to two signs
    (orientation, and for a 2D lattice the normal's image), and the last basis vector's
    image must then be a lattice vector.  So only vectors up to the second-shortest basis
    length are listed, however long the last one (a ``1 x 1 x 1000`` supercell).  ``tol``
    bounds the position error of an image vector; ``Q`` is the orthogonal matrix nearest
    to the exact fit.
    """
    basis = np.asarray(basis, dtype=np.float64)
    dim = len(basis)
    reduced, u = lll_reduce(basis)
    lengths = np.linalg.norm(reduced, axis=1)
    k = dim - 1  # basis vectors whose images are picked
    coords, vectors = short_vectors(reduced, float(lengths[:k].max()) + 2 * tol)
    norms = np.linalg.norm(vectors, axis=1)
    choices = [np.flatnonzero(np.abs(norms - lengths[i]) <= 2 * tol) for i in range(k)]
    gram = reduced[:k] @ reduced[:k].T
    bound = 2 * tol * (lengths[:k, None] + lengths[None, :k])
    normal = np.cross(reduced[0], reduced[1])
    normal /= np.linalg.norm(normal)
    frame = (
        np.vstack([reduced[0], reduced[1], normal])
        if dim == 3
        else np.vstack([reduced[0], np.cross(normal, reduced[0]), normal])
    )
    inverse = np.linalg.pinv(reduced)
    u_inv = np.rint(np.linalg.inv(u)).astype(np.int64)
    out: list[PointOperation] = []
    for pick in itertools.product(*choices):
        images = vectors[list(pick)]
        if np.any(np.abs(images @ images.T - gram) > bound):
            continue
        for signs in itertools.product((1, -1), repeat=4 - dim):
            if dim == 3:
                cross = np.cross(images[0], images[1])
                target = np.vstack([images[0], images[1], signs[0] * cross / np.linalg.norm(cross)])
            else:
                target = np.vstack([images[0], signs[0] * np.cross(normal, images[0]), signs[1] * normal])
            w, _, vt = np.linalg.svd(np.linalg.solve(frame, target))
            q = (w @ vt).T
            last = q @ reduced[-1]
            n_last = np.rint(last @ inverse).astype(np.int64)
            if np.abs(n_last @ reduced - last).max() > 2 * tol:
                continue
            n_red = np.vstack([coords[list(pick)], n_last])
            s = 1 if dim == 3 else int(signs[1])
            out.append((q, u_inv @ n_red @ u, s))
    out.sort(key=lambda op: not (np.array_equal(op[1], np.eye(dim, dtype=np.int64)) and op[2] == 1))
    return out
