"""The view of a 3D picture: its direction, the picture plane, and the frame on the strands.

A view is ``(azimuth, elevation)`` in degrees, matplotlib's convention (z up): the eye
looks from :func:`direction` toward the origin.  Pictures are orthographic: a point ``p``
lands at ``(p @ right, p @ up)`` of :func:`screen_axes` and lies at depth ``p @ view``
(larger is nearer the eye), the same in the PNG (matplotlib) and the SVG (line art).
The frame fits the strands and their tubes (:func:`frame`), not the scaffold.  The
default view of a finite design looks down a rotation axis of its strands when they have
one of order 3 or more (:func:`clear_view`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ..geometry.realization import Realization
    from .render import Look

FILL = 0.92
"""Share of the picture's width or height the strands (with their tubes) fill on their tighter axis."""
TITLE_HEIGHT = 36
"""Pixels kept free above the strands for a title."""


def direction(azim: float, elev: float) -> np.ndarray:
    """(3,) unit vector from the origin toward the eye of view ``(azim, elev)`` in degrees."""
    e, a = np.radians(elev), np.radians(azim)
    return np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])


def screen_axes(view: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors ``(right, up)`` spanning the picture plane of view direction ``view`` (z stays up)."""
    right = np.cross([0.0, 0.0, 1.0], view)
    right = right / np.linalg.norm(right) if np.linalg.norm(right) > 1e-9 else np.array([1.0, 0.0, 0.0])
    return right, np.cross(view, right)


def view_angles(real: Realization, look: Look, radius: float) -> tuple[float, float]:
    """``(azimuth, elevation)`` of a picture: the look's, else the clearest (finite) or ``iso`` (block).

    A block without a given elevation is seen from 55 degrees when it is flat (its
    height under a quarter of its width), else from 24.
    """
    if look.azim is None and look.elev is None and real.block is None and real.curves:
        return clear_view(real, radius)
    pts = np.vstack(real.curves) if real.curves else np.zeros((1, 3))
    extent = np.ptp(pts, axis=0)
    elev = look.elev if look.elev is not None else (55.0 if extent[2] < 0.25 * extent.max() else 24.0)
    azim = look.azim if look.azim is not None else -58.0
    return azim, elev


def frame(points: np.ndarray, view: np.ndarray, radius: float) -> tuple[np.ndarray, np.ndarray]:
    """Return the strands' box in the picture plane: ``(centre (2,), half sizes (2,))``, tubes of ``radius`` included."""
    right, up = screen_axes(view)
    flat = np.column_stack([points @ right, points @ up])
    lo, hi = flat.min(axis=0) - radius, flat.max(axis=0) + radius
    return (lo + hi) / 2, np.maximum((hi - lo) / 2, 1e-12)


def pixels_per_unit(half: np.ndarray, width: float, height: float) -> float:
    """Scale (pixels per scaffold unit) at which a box of ``half`` sizes fills :data:`FILL` of the picture."""
    return float(FILL * min(width / 2 / half[0], height / 2 / half[1]))


def overlap(
    pts: np.ndarray, arc: np.ndarray, owner: np.ndarray, lengths: np.ndarray, view: np.ndarray, radius: float
) -> tuple[float, float]:
    """Score of a view (lower is clearer): ``(pairs of distinct pieces within two tube diameters, -area)``.

    ``pts`` are samples of the strands (``arc`` along ``owner``'s curve of length
    ``lengths[owner]``); a pair is of distinct pieces on two curves, or far along one.
    """
    from scipy.spatial import cKDTree

    right, up = screen_axes(view)
    flat = np.column_stack([pts @ right, pts @ up])
    pairs = cKDTree(flat).query_pairs(4 * radius, output_type="ndarray")
    far = 0.0
    if len(pairs):
        o = owner[pairs[:, 0]]
        along = np.abs(arc[pairs[:, 0]] - arc[pairs[:, 1]])
        along = np.minimum(along, lengths[o] - along)
        far = float(((o != owner[pairs[:, 1]]) | (along > 8 * radius)).sum())
    return far, -float(np.ptp(flat[:, 0]) * np.ptp(flat[:, 1]))


def angles(view: np.ndarray) -> tuple[float, float]:
    """``(azimuth, elevation)`` in degrees of a view direction (seen from its upper side)."""
    view = view if view[2] >= 0 else -view
    elev = float(np.degrees(np.arcsin(np.clip(view[2], -1, 1))))
    return (-90.0, 90.0) if elev > 89.99 else (float(np.degrees(np.arctan2(view[1], view[0]))), elev)


def clear_view(real: Realization, radius: float) -> tuple[float, float]:
    """``(azimuth, elevation)`` in degrees: down the strands' rotation axis, else the clearest of 48 directions.

    Every view is scored by :func:`overlap` (samples every 1/600 of the strands' length).
    A rotation axis of order 3 or more (:func:`rotation_axes`) is taken, the clearest of
    the highest order, unless its score is over 1.5 times the clearest direction's; the
    48 directions are 12 azimuths by 4 elevations.
    """
    from ..geometry.clearance import samples

    curves = real.curves
    closed = np.ones(len(curves), bool)
    total = sum(float(np.linalg.norm(np.diff(c, axis=0), axis=1).sum()) for c in curves)
    spacing = max(total / 600, 1e-12)
    pts, arc, owner, lengths = samples(curves, closed, spacing)
    best, choice = (np.inf, 0.0), (-58.0, 24.0)
    for elev in (20.0, 40.0, 60.0, 80.0):
        for azim in np.arange(-180.0, 180.0, 30.0):
            score = overlap(pts, arc, owner, lengths, direction(float(azim), elev), radius)
            if score < best:
                best, choice = score, (float(azim), elev)
    axes = rotation_axes(pts, real.scaffold.vertices, spacing)
    if axes:
        scored = sorted((overlap(pts, arc, owner, lengths, a, radius), k) for k, a in enumerate(axes))
        if scored[0][0][0] <= 1.5 * best[0]:
            return angles(axes[scored[0][1]])
    return choice


ORDERS = (6, 5, 4, 3)
"""Rotation orders a picture looks down, highest first."""


def rotation_axes(pts: np.ndarray, vertices: np.ndarray, spacing: float) -> list[np.ndarray]:
    """Return the axes (unit, through the centroid) that turn ``pts`` onto themselves, of the highest order found.

    Candidates: the principal axes of ``pts`` and the directions to the scaffold's
    ``vertices`` (at most 200).  An axis of order n holds when every point turned by
    360/n degrees lies within ``spacing`` of a point.
    """
    from scipy.spatial import cKDTree

    centre = pts.mean(axis=0)
    rel = pts - centre
    _, vecs = np.linalg.eigh(rel.T @ rel)
    toward = vertices[:200] - centre
    norms = np.linalg.norm(toward, axis=1)
    candidates = np.vstack([vecs.T, toward[norms > 1e-9] / norms[norms > 1e-9, None]])
    tree = cKDTree(rel)
    for n in ORDERS:
        found: list[np.ndarray] = []
        for a in candidates:
            if any(abs(float(a @ b)) > 0.999 for b in found):
                continue
            c, s = np.cos(2 * np.pi / n), np.sin(2 * np.pi / n)
            turned = rel * c + np.cross(a, rel) * s + np.outer(rel @ a, a) * (1 - c)  # Rodrigues
            if tree.query(turned, distance_upper_bound=spacing)[0].max() <= spacing:
                found.append(a)
        if found:
            return found
    return []
