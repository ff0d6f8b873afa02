"""Symmetries just missed: motions that fit a mesh a little worse than the tolerance allows.

A hand-made mesh with rounded or slightly wrong coordinates may miss a symmetry its
designer meant.  :func:`near_symmetry` searches again with a looser tolerance
(:func:`loose_tolerance`: 100 times the tolerance, at most 5% of the shortest edge);
when that finds more motions it says which ``--tolerance`` counts them, and how far the
best-fitting one misses.  Only finite
scaffolds of at most :data:`MAX_VERTICES` vertices are checked (the search runs twice).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..errors import LkspaceWarning, TooLargeError
from ..model.scaffold import Scaffold
from .group import compute_group, symmetry_group
from .pointset import procrustes
from .tolerance import resolve_tolerance, shortest_edge

MAX_VERTICES = 20_000
"""Largest mesh (vertices) checked for near symmetries."""

TIE = 1e-9
"""Misses closer than this (times the shortest edge) are equal when the example is chosen."""


@dataclass(frozen=True)
class NearSymmetry:
    """Motions found with tolerance ``suggested`` but not with ``tolerance`` (mesh units).

    Attributes
    ----------
    tolerance : float
        The tolerance used.
    suggested : float
        A ``--tolerance`` (one significant digit, rounded up) with which the search finds them.
    rotations, isometries : int
        Orders of the group found with ``suggested`` (rotations only; all).
    example : str
        The missed motion that fits best, in words, e.g. ``"a 1/3 turn about the axis (0.00, 0.00, 1.00) ..."``.
    miss : float
        How far that motion moves a vertex from the vertex it is matched with (best fit).
    """

    tolerance: float
    suggested: float
    rotations: int
    isometries: int
    example: str
    miss: float

    def message(self, name: str, rotations: int, isometries: int) -> str:
        """One line for the user: what was missed, by how much, and what to do (``rotations``, ``isometries``: found)."""
        return (
            f"{name} has {self.rotations} rotations ({self.isometries} isometries) if points {self.suggested:g} "
            f"apart count as one, but only {rotations} ({isometries}) within the tolerance "
            f"{self.tolerance:.2g}: e.g. {self.example} misses by {self.miss:.2g}; pass "
            f"`tolerance={self.suggested:g}` to count them, or correct the coordinates (more decimals)"
        )


def loose_tolerance(scaffold: Scaffold, tolerance: float) -> float:
    """Return the tolerance of the second search (mesh units): 100 ``tolerance``, at most 5% of the shortest edge."""
    return min(100 * tolerance, 0.05 * shortest_edge(scaffold))


def round_up(value: float) -> float:
    """``value`` rounded up to one significant digit (``0.0372 -> 0.04``)."""
    unit = 10.0 ** math.floor(math.log10(value))
    return float(f"{math.ceil(value / unit - 1e-9) * unit:.1g}")


def near_symmetry(scaffold: Scaffold, tolerance: float | None = None) -> NearSymmetry | None:
    """Return the motions just missed at ``tolerance`` (default rule), or ``None`` if there are none.

    Examples
    --------
    >>> from lkspace import Scaffold
    >>> s = 0.866  # sqrt(3)/2 rounded: an equilateral triangle, a little off
    >>> tri = Scaffold.from_faces([[1, 0, 0], [-0.5, s, 0], [-0.5, -s, 0]], [[0, 1, 2]])
    >>> near_symmetry(tri) is None  # 0.00003 off: inside the default tolerance (0.017)
    True
    >>> near_symmetry(tri, tolerance=1e-5).rotations
    6
    """
    tol = resolve_tolerance(scaffold, tolerance)
    loose = loose_tolerance(scaffold, tol)
    if scaffold.periodic or scaffold.n_vertices > MAX_VERTICES or loose <= tol:
        return None
    strict = symmetry_group(scaffold, tol)
    try:
        with warnings.catch_warnings():  # the first search has said what there is to say
            warnings.simplefilter("ignore", LkspaceWarning)
            wide = compute_group(scaffold, loose)
    except TooLargeError:
        return None
    if wide.order <= strict.order:
        return None
    known = {(s.tobytes(), bool(p)) for s, p in zip(strict.vertex_perms, strict.proper, strict=True)}
    x = np.asarray(scaffold.vertices, np.float64)
    x = x - x.mean(axis=0)
    misses = []
    for sigma, q, proper in zip(wide.vertex_perms, wide.matrices, wide.proper, strict=True):
        if (sigma.tobytes(), bool(proper)) not in known:
            fit = procrustes(x, x[sigma])
            if (np.linalg.det(fit) > 0) != bool(proper):
                fit = q  # a flat mesh: the fit took the other side; the search's own matrix fits as well
            d = x @ fit.T - x[sigma]
            moved = int(np.count_nonzero(sigma != np.arange(len(sigma))))
            misses.append((float(np.sqrt(np.einsum("ij,ij->i", d, d).max())), not proper, moved, sigma.tolist(), fit))
    miss, fit = example_motion(misses, TIE * shortest_edge(scaffold))
    suggested = round_up(1.1 * min(max(m[0] for m in misses), loose))
    if suggested >= loose or _quiet_order(scaffold, suggested) != wide.order:
        suggested = loose  # products of near motions may miss by more than each: the search's own tolerance
    return NearSymmetry(tol, suggested, wide.n_rotations, wide.order, describe(fit), miss)


def example_motion(
    misses: list[tuple[float, bool, int, list[int], np.ndarray]], tie: float
) -> tuple[float, np.ndarray]:
    """Return the best-fitting missed motion ``(miss, matrix)``, the same on every machine.

    ``misses`` holds ``(miss, improper, vertices moved, vertex permutation, matrix)``.  Misses
    within ``tie`` of the smallest are equal (on a symmetric mesh they differ in the last bits,
    which vary with the BLAS): among them a rotation before a reflection, then the motion that
    moves the fewest vertices, then the smallest vertex permutation.
    """
    least = min(m[0] for m in misses)
    *_, fit = min((m for m in misses if m[0] <= least + tie), key=lambda m: m[1:4])
    return least, fit


def _quiet_order(scaffold: Scaffold, tolerance: float) -> int:
    """Order of the group found with ``tolerance``, without repeating the first search's warnings."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", LkspaceWarning)
        return compute_group(scaffold, tolerance).order


def describe(q: np.ndarray) -> str:
    """Describe a motion fixing the centroid in words: ``"a 1/3 turn about (0, 0, 1)"``, ``"a mirror reflection"``."""
    if np.linalg.det(q) < 0:
        values = np.linalg.eigvals(q)
        mirror = np.sum(np.isclose(values, 1.0, atol=1e-3)) == 2
        return "a mirror reflection" if mirror else "a turn combined with a reflection"
    angle = math.acos(max(-1.0, min(1.0, (float(np.trace(q)) - 1) / 2)))
    values, vectors = np.linalg.eig(q)
    axis = np.real(vectors[:, int(np.argmin(np.abs(values - 1)))])
    axis = axis / np.linalg.norm(axis)
    axis = axis if axis[np.argmax(np.abs(axis))] > 0 else -axis
    order = round(2 * math.pi / angle) if angle > 1e-6 else 1
    turn = (
        f"a 1/{order} turn"
        if order > 1 and abs(2 * math.pi / order - angle) < 0.05
        else f"a {math.degrees(angle):.0f}° turn"
    )
    where = ", ".join(f"{c:.2f}" for c in np.round(axis, 2) + 0.0)  # + 0.0: no "-0.00"
    return f"{turn} about the axis ({where}) through the centroid"
