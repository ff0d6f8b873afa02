"""Radial order of the face-sides around every edge (explained for users in ``docs/model.md``).

Edge ``e = (a, b)`` has axis ``d`` = unit vector from end ``a`` to end ``b``.  A side of
face ``f`` lying on ``e`` gets the direction ``r`` = the component of
``(centroid(f) - p_a)`` perpendicular to ``d`` (centroid and ``p_a`` taken in the same
lattice translate).  The ``K`` sides of ``e`` fill slots ``0..K-1`` in increasing angle of
``r`` about ``d``, counter-clockwise seen from the tip of ``d`` (right-hand rule), the
angle measured from a fixed reference direction; only the cyclic order matters.

For ``K >= 3`` two sides at the same angle (or a face whose centroid lies on the edge's
line) make the order ambiguous: :class:`~lkspace.errors.RadialOrderError` names the
edge, unless the scaffold gives that edge's radial order explicitly.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..errors import RadialOrderError, ScaffoldError

if TYPE_CHECKING:
    from .scaffold import Scaffold

ANGLE_TOLERANCE = 1e-7  # radians; closer angles count as coincident


@dataclass(frozen=True, eq=False)
class RadialOrder:
    """Sides of every edge in slot order.

    Attributes
    ----------
    edge_starts : (n_edges + 1,) int64
        Edge ``e`` owns ``edge_sides[edge_starts[e]:edge_starts[e + 1]]``.
    edge_sides : (n_corners,) int64
        Sides grouped by edge, each group in slot order.
    side_slot : (n_corners,) int64
        Slot of each side on its edge.
    """

    edge_starts: np.ndarray
    edge_sides: np.ndarray
    side_slot: np.ndarray


def perpendicular_frames(axes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Right-handed frames around unit ``axes (n, 3)``: ``u1, u2`` with ``u2 = d x u1``."""
    helper = np.zeros_like(axes)
    smallest = np.argmin(np.abs(axes), axis=1)
    helper[np.arange(len(axes)), smallest] = 1.0
    u1 = np.cross(helper, axes)
    u1 /= np.linalg.norm(u1, axis=1, keepdims=True)
    u2 = np.cross(axes, u1)
    return u1, u2


def side_angles(scaffold: Scaffold, sides: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Return the angles ``(n,) float64`` of ``sides`` (default all) about their edge axes and the lengths of ``r``."""
    sides = np.arange(scaffold.n_corners) if sides is None else sides
    e = scaffold.side_edge[sides]
    points = scaffold.edge_points[e]
    d = points[:, 1] - points[:, 0]
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    u1, u2 = perpendicular_frames(d)
    origin = points[:, 0]
    if scaffold.lattice is not None:
        origin = origin + scaffold.lattice.translate(scaffold.side_translation[sides])
    r = scaffold.face_centroids[scaffold.corner_face[sides]] - origin
    x = np.einsum("ij,ij->i", r, u1)
    y = np.einsum("ij,ij->i", r, u2)
    return np.arctan2(y, x), np.hypot(x, y)


def radial_order(scaffold: Scaffold) -> RadialOrder:
    """Compute the radial order of ``scaffold``; see the module docstring."""
    n_edges = scaffold.n_edges
    degrees = scaffold.edge_degrees
    edge_starts = np.concatenate([[0], np.cumsum(degrees)]).astype(np.int64)
    # K <= 2: any order is the same cyclic order; sides stay in side order
    order = np.argsort(scaffold.side_edge, kind="stable")
    ordered = degrees[scaffold.side_edge[order]] >= 3
    high = order[ordered]
    angles, radii = side_angles(scaffold, high)
    resort = np.lexsort((angles, scaffold.side_edge[high]))
    order[ordered] = high[resort]
    sorted_angles = angles[resort]
    sorted_edges = scaffold.side_edge[high][resort]

    explicit = np.zeros(n_edges, bool)
    edge_sides = order.copy()
    if scaffold.radial_orders:
        index = {tuple(k): i for i, k in enumerate(scaffold.edge_keys.tolist())}
        for key, sides in scaffold.radial_orders.items():
            flat_key = (key[0], key[1], *key[2]) if len(key) == 3 else tuple(key)
            e = index.get(flat_key)
            if e is None:
                raise ScaffoldError(f"{scaffold.name}: radial order given for {key[0]}-{key[1]}, which is not an edge")
            sides = np.asarray(sides, dtype=np.int64)
            expected = np.sort(np.flatnonzero(scaffold.side_edge == e))
            if sides.shape != expected.shape or not np.array_equal(np.sort(sides), expected):
                raise ScaffoldError(
                    f"{scaffold.name}: radial order of edge {scaffold.edge_name(e)} must list its "
                    f"{len(expected)} face-sides {expected.tolist()}, got {sides.tolist()}"
                )
            edge_sides[edge_starts[e] : edge_starts[e + 1]] = sides
            explicit[e] = True

    check = (degrees >= 3) & ~explicit
    scale = max(1.0, float(np.abs(scaffold.edge_points).max()))
    degenerate = np.flatnonzero(check[scaffold.side_edge[high]] & (radii <= 1e-9 * scale))
    if len(degenerate):
        s = high[degenerate[0]]
        e = scaffold.side_edge[s]
        raise RadialOrderError(
            f"{scaffold.name}: ambiguous radial order at edge {e} ({scaffold.edge_name(e)}): "
            f"face {scaffold.corner_face[s]} has its centroid on the edge's line"
        )
    gaps = np.diff(sorted_angles)
    same_edge = sorted_edges[1:] == sorted_edges[:-1]
    close = same_edge & (gaps < ANGLE_TOLERANCE) & check[sorted_edges[1:]]
    group_start = np.r_[len(sorted_edges) > 0, ~same_edge]
    first_of_group = np.flatnonzero(group_start)
    last_of_group = np.r_[first_of_group[1:], len(sorted_edges)][: len(first_of_group)] - 1
    wrap = sorted_angles[first_of_group] + 2 * np.pi - sorted_angles[last_of_group] < ANGLE_TOLERANCE
    wrap &= check[sorted_edges[first_of_group]]
    if close.any() or wrap.any():
        if close.any():
            i = np.flatnonzero(close)[0]
            s1, s2 = high[resort][i], high[resort][i + 1]
        else:
            g = np.flatnonzero(wrap)[0]
            s1, s2 = high[resort][first_of_group[g]], high[resort][last_of_group[g]]
        e = scaffold.side_edge[s1]
        raise RadialOrderError(
            f"{scaffold.name}: ambiguous radial order at edge {e} ({scaffold.edge_name(e)}): "
            f"faces {scaffold.corner_face[s1]} and {scaffold.corner_face[s2]} lie at the same angle; "
            "give the order explicitly in a scaffold file"
        )
    side_slot = np.empty(scaffold.n_corners, np.int64)
    side_slot[edge_sides] = np.arange(scaffold.n_corners) - np.repeat(edge_starts[:-1], degrees)
    for arr in (edge_starts, edge_sides, side_slot):
        arr.setflags(write=False)
    return RadialOrder(edge_starts, edge_sides, side_slot)
