"""How far apart two points may be and still count as one for the symmetry search.

Meshes from modelling tools carry rounded coordinates (``0.866`` for ``sqrt(3)/2``), so
the search accepts a candidate motion when it moves every vertex to within a
**tolerance** ``T`` of the vertex it is matched with (after the best-fitting orthogonal
map is refit on all of them).  ``T`` is a distance in the mesh's own units.

Default rule: ``T = 1/100`` of the shortest edge (:data:`RELATIVE`).  Rounding to 3
decimals moves a point by at most ``0.0005 * sqrt(3) ~ 0.0009``, so a motion of a mesh
with unit-length edges misses by at most about ``0.002``: well inside ``T = 0.01``;
and the ends of every edge stay 100 ``T`` apart, so no motion is accepted that puts a
vertex where its neighbour is.  A given ``T`` must stay below half the shortest edge.  A shape that differs from a
symmetric one by more than 1% of its shortest edge is a different shape (the
``info``/``enumerate`` note says when it misses by a little; see
:mod:`lkspace.symmetry.nearby`).

Geometry only decides *which* candidates are symmetries: an accepted motion must map
vertices, edges, faces and the radial order of the sides around every edge exactly
(:mod:`lkspace.symmetry.finite`), and the group is that of these exact permutations.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import UsageError
from ..model.scaffold import Scaffold

RELATIVE = 0.01
"""Default tolerance as a fraction of the shortest edge."""

FLOOR = 1e-9
"""Smallest tolerance the search uses, relative to the mesh's RMS radius (floating-point noise)."""


def mesh_unit(scaffold: Scaffold) -> float:
    """Mesh units per unit of :func:`~lkspace.symmetry.pointset.standard_position` (largest coordinate x RMS radius).

    Computed without overflow for coordinates near ``1e308``; ``1.0`` for a single point.
    """
    v = np.asarray(scaffold.vertices, np.float64)
    scale = float(np.abs(v).max()) if v.size else 0.0
    if scale == 0.0:
        return 1.0
    x = v / scale
    x = x - x.mean(axis=0)
    rms = float(np.sqrt(np.mean(np.einsum("ij,ij->i", x, x))))
    return scale * rms if rms > 0 else scale


def shortest_edge(scaffold: Scaffold) -> float:
    """Length of the shortest edge of non-zero length (lattice offsets included); 0 if there is none."""
    pts = np.asarray(scaffold.edge_points, np.float64)
    if not pts.size:
        return 0.0
    scale = float(np.abs(pts).max())
    if scale == 0.0 or not math.isfinite(scale):
        return 0.0
    lengths = np.linalg.norm((pts[:, 1] - pts[:, 0]) / scale, axis=1)
    lengths = lengths[lengths > 0]
    return float(lengths.min()) * scale if len(lengths) else 0.0


def default_tolerance(scaffold: Scaffold) -> float:
    """``RELATIVE`` x the shortest edge (mesh units); ``FLOOR`` x :func:`mesh_unit` if that is smaller."""
    return max(RELATIVE * shortest_edge(scaffold), FLOOR * mesh_unit(scaffold))


def check_tolerance(tolerance: float | str) -> float:
    """Return ``tolerance`` as a float if it is a finite number > 0; raise :class:`~lkspace.errors.UsageError` otherwise."""
    try:
        value = float(tolerance)
    except (TypeError, ValueError):
        raise UsageError(f"tolerance {tolerance!r}: expected a number > 0") from None
    if not (value > 0 and math.isfinite(value)):  # NaN fails too
        raise UsageError(f"tolerance {tolerance!r}: expected a finite number > 0")
    return value


def resolve_tolerance(scaffold: Scaffold, tolerance: float | None) -> float:
    """Return the tolerance to use (mesh units): ``tolerance`` if given, else :func:`default_tolerance`.

    Raises :class:`~lkspace.errors.UsageError` unless a given ``tolerance`` is a finite
    number > 0 and below half the shortest edge (past it, an edge's two ends would count as one).
    """
    if tolerance is None:
        return default_tolerance(scaffold)
    value = check_tolerance(tolerance)
    edge = shortest_edge(scaffold)
    if edge > 0 and value >= edge / 2:
        raise UsageError(
            f"tolerance {value:g}: {scaffold.name}'s shortest edge is {edge:.6g} long; use a tolerance below "
            f"half of it ({edge / 2:.3g}) (default {default_tolerance(scaffold):.3g})"
        )
    return value
