"""The view of a 3D picture: its direction, the picture plane, and the frame on the strands.

A view is ``(azimuth, elevation)`` in degrees, matplotlib's convention (z up): the eye
looks from :func:`direction` toward the origin.  Pictures are orthographic: a point ``p``
lands at ``(p @ right, p @ up)`` of :func:`screen_axes` and lies at depth ``p @ view``
(larger is nearer the eye), the same in the PNG (matplotlib) and the SVG (line art).
The frame fits the strands and their tubes (:func:`frame`), not the scaffold.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ..geometry.realization import Realization
    from .render import Look

FILL = 0.92
"""Share of the picture's width or height the strands (with their tubes) fill on their tighter axis."""


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
        return clear_view(real.curves, radius)
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


def clear_view(curves: list[np.ndarray], radius: float) -> tuple[float, float]:
    """``(azimuth, elevation)`` in degrees among 48 directions where the strands overlap least in projection.

    A view scores the share of point pairs of distinct pieces (other curve, or far along
    one) that project within two tube diameters of each other: the fewer, the cleaner the
    crossings read.  Ties go to the wider picture.
    """
    from scipy.spatial import cKDTree

    from ..geometry.clearance import samples

    closed = np.ones(len(curves), bool)
    total = sum(float(np.linalg.norm(np.diff(c, axis=0), axis=1).sum()) for c in curves)
    pts, arc, owner, lengths = samples(curves, closed, max(total / 600, 1e-12))
    best, choice = (np.inf, 0.0), (-58.0, 24.0)
    for elev in (20.0, 40.0, 60.0, 80.0):
        for azim in np.arange(-180.0, 180.0, 30.0):
            right, up = screen_axes(direction(float(azim), elev))
            flat = np.column_stack([pts @ right, pts @ up])
            pairs = cKDTree(flat).query_pairs(4 * radius, output_type="ndarray")
            along = np.abs(arc[pairs[:, 0]] - arc[pairs[:, 1]]) if len(pairs) else np.zeros(0)
            if len(pairs):
                o = owner[pairs[:, 0]]
                along = np.minimum(along, lengths[o] - along)
                far = (o != owner[pairs[:, 1]]) | (along > 8 * radius)
                overlap = float(far.sum())
            else:
                overlap = 0.0
            score = (overlap, -float(np.ptp(flat[:, 0]) * np.ptp(flat[:, 1])))
            if score < best:
                best, choice = score, (float(azim), elev)
    return choice
