"""Periodic lattices: 2 or 3 basis vectors in 3D space.

A periodic scaffold is the quotient of an infinite periodic mesh by a lattice
``L = {sum_i n_i * basis[i] : n_i integer}``.  Lattice translations are written as
integer vectors ``n`` of length ``dim``; the translation in space is ``n @ basis``.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .errors import ScaffoldError


@dataclass(frozen=True, eq=False)
class Lattice:
    """A Bravais lattice.

    Attributes
    ----------
    basis : (dim, 3) float64
        Linearly independent basis vectors, ``dim`` in {2, 3}.
    """

    basis: np.ndarray

    def __post_init__(self):
        basis = np.array(self.basis, dtype=np.float64)
        if basis.ndim != 2 or basis.shape[1] != 3 or basis.shape[0] not in (2, 3):
            raise ScaffoldError(
                f"lattice: expected 2 or 3 basis vectors of length 3, got shape {basis.shape}"
            )
        if not np.all(np.isfinite(basis)):
            raise ScaffoldError("lattice: basis vectors must be finite numbers")
        if np.linalg.matrix_rank(basis, tol=1e-9 * max(1.0, np.abs(basis).max())) < len(basis):
            raise ScaffoldError("lattice: basis vectors are linearly dependent")
        basis.setflags(write=False)
        object.__setattr__(self, "basis", basis)

    @property
    def dim(self) -> int:
        """Number of basis vectors (2 or 3)."""
        return int(self.basis.shape[0])

    def translate(self, offsets: np.ndarray) -> np.ndarray:
        """Translations in space of integer ``offsets`` ``(..., dim)`` -> ``(..., 3)``."""
        return np.asarray(offsets, dtype=np.float64) @ self.basis

    @cached_property
    def volume(self) -> float:
        """Area (dim 2) or volume (dim 3) of the fundamental cell."""
        if self.dim == 3:
            return float(abs(np.linalg.det(self.basis)))
        return float(np.linalg.norm(np.cross(self.basis[0], self.basis[1])))

    @classmethod
    def cubic(cls, a: float = 1.0) -> Lattice:
        """Simple cubic lattice with edge ``a``."""
        return cls(a * np.eye(3))

    @classmethod
    def square(cls, a: float = 1.0) -> Lattice:
        """Square lattice in the xy plane."""
        return cls(a * np.eye(3)[:2])

    def __eq__(self, other) -> bool:
        return isinstance(other, Lattice) and np.array_equal(self.basis, other.basis)

    def __hash__(self) -> int:
        return hash(self.basis.tobytes())
