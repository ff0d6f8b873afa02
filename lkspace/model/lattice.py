"""Periodic lattices: 2 or 3 basis vectors in 3D space.

A periodic scaffold is the quotient of an infinite periodic mesh by a lattice
``L = {sum_i n_i * basis[i] : n_i integer}``.  Lattice translations are written as
integer vectors ``n`` of length ``dim``; the translation in space is ``n @ basis``.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike

from ..errors import ScaffoldError
from .validation import MAX_COORDINATE


@dataclass(frozen=True, eq=False, repr=False)
class Lattice:
    """A Bravais lattice.

    Attributes
    ----------
    basis : (dim, 3) float64
        Linearly independent basis vectors, ``dim`` in {2, 3}.
    """

    basis: np.ndarray

    def __post_init__(self) -> None:
        try:
            basis = np.array(self.basis, dtype=np.float64)
        except (TypeError, ValueError, OverflowError):
            raise ScaffoldError("lattice: expected 2 or 3 basis vectors of 3 numbers each") from None
        if basis.ndim != 2 or basis.shape[1] != 3 or basis.shape[0] not in (2, 3):
            raise ScaffoldError(f"lattice: expected 2 or 3 basis vectors of length 3, got shape {basis.shape}")
        if not np.all(np.abs(basis) <= MAX_COORDINATE):
            raise ScaffoldError(f"lattice: basis vectors must be finite numbers within +-{MAX_COORDINATE:g}")
        if np.linalg.matrix_rank(basis, tol=1e-9 * max(1.0, np.abs(basis).max())) < len(basis):
            raise ScaffoldError("lattice: basis vectors are linearly dependent")
        basis.setflags(write=False)
        object.__setattr__(self, "basis", basis)

    def __repr__(self) -> str:
        rows = "\n".join(f"    {' '.join(f'{x:9.4f}' for x in row)}" for row in self.basis)
        return f"Lattice(dim={self.dim}, volume={self.volume:.4f}, basis=\n{rows})"

    @property
    def dim(self) -> int:
        """Number of basis vectors (2 or 3)."""
        return int(self.basis.shape[0])

    def translate(self, offsets: ArrayLike) -> np.ndarray:
        """Return the translations in space ``(..., 3) float64`` of integer ``offsets (..., dim)``."""
        return np.asarray(offsets, dtype=np.float64) @ self.basis

    @cached_property
    def volume(self) -> float:
        """Area (dim 2) or volume (dim 3) of the fundamental cell."""
        if self.dim == 3:
            return float(abs(np.linalg.det(self.basis)))
        return float(np.linalg.norm(np.cross(self.basis[0], self.basis[1])))

    @classmethod
    def square(cls, a: float = 1.0) -> Lattice:
        """Square lattice in the xy plane: ``a x, a y``."""
        return cls(a * np.eye(3)[:2])

    @classmethod
    def hexagonal2d(cls, a: float = 1.0) -> Lattice:
        """Hexagonal lattice in the xy plane: ``a (1, 0, 0), a (1/2, sqrt(3)/2, 0)``."""
        return cls(a * np.array([[1.0, 0, 0], [0.5, 3**0.5 / 2, 0]]))

    @classmethod
    def cubic(cls, a: float = 1.0) -> Lattice:
        """Primitive cubic (cP): ``a x, a y, a z``."""
        return cls(a * np.eye(3))

    @classmethod
    def hexagonal(cls, a: float = 1.0, c: float = 1.0) -> Lattice:
        """Primitive hexagonal (hP): ``a (1, 0, 0), a (1/2, sqrt(3)/2, 0), c z``."""
        return cls(np.array([[a, 0, 0], [a / 2, a * 3**0.5 / 2, 0], [0, 0, c]]))

    @classmethod
    def face_centred_orthorhombic(cls, a: float = 1.0, b: float = 1.25, c: float = 1.5) -> Lattice:
        """Face-centred orthorhombic (oF), conventional cell ``a x b x c``.

        Primitive vectors ``(0, b, c)/2, (a, 0, c)/2, (a, b, 0)/2``.
        """
        return cls(np.array([[0, b / 2, c / 2], [a / 2, 0, c / 2], [a / 2, b / 2, 0]]))

    @classmethod
    def face_centred_cubic(cls, a: float = 1.0) -> Lattice:
        """Face-centred cubic (cF), conventional cube ``a``: ``(0,1,1)a/2, (1,0,1)a/2, (1,1,0)a/2``."""
        return cls(a / 2 * np.array([[0.0, 1, 1], [1, 0, 1], [1, 1, 0]]))

    @classmethod
    def body_centred_cubic(cls, a: float = 1.0) -> Lattice:
        """Body-centred cubic (cI), conventional cube ``a``: ``(-1,1,1)a/2, (1,-1,1)a/2, (1,1,-1)a/2``."""
        return cls(a / 2 * np.array([[-1.0, 1, 1], [1, -1, 1], [1, 1, -1]]))

    def fractional(self, points: ArrayLike) -> np.ndarray:
        """Lattice coordinates ``(..., dim)`` of ``points (..., 3)`` (least squares in 2D)."""
        return np.asarray(points, dtype=np.float64) @ np.linalg.pinv(self.basis)

    def supercell(self, sizes: ArrayLike) -> Lattice:
        """Return the lattice spanned by ``sizes[i] * basis[i]``."""
        return Lattice(self.basis * np.asarray(sizes, dtype=np.float64)[:, None])

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Lattice) and np.array_equal(self.basis, other.basis)

    def __hash__(self) -> int:
        return hash(self.basis.tobytes())


def lll_reduce(basis: np.ndarray, delta: float = 0.99) -> tuple[np.ndarray, np.ndarray]:
    """LLL-reduce the rows of ``basis (dim, 3)``: ``(reduced (dim, 3) float64, U (dim, dim) int64)``, ``reduced = U basis``."""
    b = np.array(basis, dtype=np.float64)
    dim = len(b)
    u = np.eye(dim, dtype=np.int64)
    k = 1
    while k < dim:
        for j in range(k - 1, -1, -1):
            star, _ = _gram_schmidt(b)
            mu = round(float(b[k] @ star[j] / (star[j] @ star[j])))
            if mu:
                b[k] -= mu * b[j]
                u[k] -= mu * u[j]
        star, mus = _gram_schmidt(b)
        if star[k] @ star[k] >= (delta - mus[k, k - 1] ** 2) * (star[k - 1] @ star[k - 1]):
            k += 1
        else:
            b[[k, k - 1]] = b[[k - 1, k]]
            u[[k, k - 1]] = u[[k - 1, k]]
            k = max(k - 1, 1)
    return b, u


def _gram_schmidt(b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Gram–Schmidt vectors ``(dim, 3)`` and coefficients ``mu (dim, dim)`` of the rows of ``b``."""
    star = np.array(b, dtype=np.float64)
    mus = np.zeros((len(b), len(b)))
    for i in range(len(b)):
        for j in range(i):
            mus[i, j] = b[i] @ star[j] / (star[j] @ star[j])
            star[i] -= mus[i, j] * star[j]
    return star, mus
