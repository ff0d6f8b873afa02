"""Symmetries just missed: motions that fit a mesh a little worse than the tolerance allows.

A hand-made mesh with rounded or slightly wrong coordinates may miss a symmetry its
designer meant.  :func:`near_symmetry` searches again with a looser tolerance
(:func:`loose_tolerance`: ten times the tolerance or 5% of the shortest edge, whichever
is larger, but at most a quarter of it); when that finds more motions it reports how far
the mesh is from having them and which ``--tolerance`` would count them.  Only finite
scaffolds of at most :data:`MAX_VERTICES` vertices are checked (the search runs twice).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import TooLargeError
from ..model.scaffold import Scaffold
from .group import SymmetryGroup, compute_group, symmetry_group
from .pointset import procrustes
from .tolerance import resolve_tolerance, shortest_edge

MAX_VERTICES = 20_000
"""Largest mesh (vertices) checked for near symmetries."""


@dataclass(frozen=True)
class NearSymmetry:
    """Motions that fit within ``needed`` but not within ``tolerance`` (mesh units).

    Attributes
    ----------
    tolerance : float
        The tolerance used.
    needed : float
        The largest distance one of the missed motions moves a vertex from its match.
    suggested : float
        A ``--tolerance`` that counts them (``needed`` rounded up, with a margin).
    rotations, isometries : int
        Orders of the group with them (rotations only; with reflections).
    example : str
        The missed motion that fits best, in words, e.g. ``"a 1/3 turn about the axis (0.00, 0.00, 1.00) ..."``.
    """

    tolerance: float
    needed: float
    suggested: float
    rotations: int
    isometries: int
    example: str

    def message(self, name: str, group: SymmetryGroup) -> str:
        """One line for the user: what was missed, by how much, and what to do."""
        return (
            f"{name} is within {self.needed:.2g} of having {self.rotations} rotations ({self.isometries} isometries), "
            f"not {group.n_rotations} ({group.order}), e.g. {self.example}; that is more than the "
            f"tolerance {self.tolerance:.2g}: pass --tolerance {self.suggested:g} to count them, or correct the "
            "coordinates (more decimals)"
        )


def loose_tolerance(scaffold: Scaffold, tolerance: float) -> float:
    """Return the looser tolerance of the second search (mesh units); at most a quarter of the shortest edge."""
    edge = shortest_edge(scaffold)
    return min(max(10 * tolerance, 0.05 * edge), 0.25 * edge)


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
        wide = compute_group(scaffold, loose)
    except TooLargeError:
        return None
    if wide.order <= strict.order:
        return None
    known = {(s.tobytes(), bool(p)) for s, p in zip(strict.vertex_perms, strict.proper, strict=True)}
    x = np.asarray(scaffold.vertices, np.float64)
    x = x - x.mean(axis=0)
    best: tuple[float, np.ndarray] | None = None
    needed = 0.0
    for sigma, q, proper in zip(wide.vertex_perms, wide.matrices, wide.proper, strict=True):
        if (sigma.tobytes(), bool(proper)) in known:
            continue
        fit = procrustes(x, x[sigma])
        if (np.linalg.det(fit) > 0) != bool(proper):
            fit = q  # a flat mesh: the fit picked the other side; the search's own matrix fits as well
        miss = float(np.sqrt(np.einsum("ij,ij->i", x @ fit.T - x[sigma], x @ fit.T - x[sigma]).max()))
        needed = max(needed, miss)
        if best is None or (miss, not proper) < (best[0], np.linalg.det(best[1]) < 0):
            best = (miss, fit)
    assert best is not None, "a larger group has a motion the smaller one lacks"
    suggested = float(f"{1.2 * needed:.1g}")
    suggested = suggested if suggested > needed else float(f"{2 * needed:.1g}")
    return NearSymmetry(tol, needed, suggested, wide.n_rotations, wide.order, describe(best[1]))


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
