"""Where strands run: per face-side tracks beside the edges, and helper curves.

Every face-side owns a track parallel to its edge, offset into its face and along the
face normal (:func:`side_tracks`); :mod:`lkspace.geometry.realization` joins the tracks
with helices along edges and Bézier turns at face corners.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..errors import GeometryError
from ..model.radial import perpendicular_frames
from ..model.scaffold import Scaffold


def face_normals(scaffold: Scaffold) -> np.ndarray:
    """(n_faces, 3) float64: unit normals by Newell's method over the corner order."""
    p = scaffold.corner_positions
    q = p[scaffold.corner_next]
    terms = np.column_stack(
        [
            (p[:, 1] - q[:, 1]) * (p[:, 2] + q[:, 2]),
            (p[:, 2] - q[:, 2]) * (p[:, 0] + q[:, 0]),
            (p[:, 0] - q[:, 0]) * (p[:, 1] + q[:, 1]),
        ]
    )
    normals = np.add.reduceat(terms, scaffold.face_starts[:-1], axis=0)
    norms = np.linalg.norm(normals, axis=1, keepdims=True)
    return normals / np.where(norms > 0, norms, 1.0)


def lattice_shift(scaffold: Scaffold, offsets: np.ndarray) -> np.ndarray:
    """Return the translations in space ``(n, 3) float64`` of lattice ``offsets (n, dim)`` (zeros if finite)."""
    if scaffold.lattice is None:
        return np.zeros((len(offsets), 3))
    return scaffold.lattice.translate(offsets)


@dataclass(frozen=True, eq=False)
class Tracks:
    """Label-independent per-side and per-edge arrays of the construction."""

    pa: np.ndarray  # (n_edges, 3)
    pb: np.ndarray  # (n_edges, 3)
    axis: np.ndarray  # (n_edges, 3) unit
    length: np.ndarray  # (n_edges,)
    u1: np.ndarray  # (n_edges, 3)
    u2: np.ndarray  # (n_edges, 3)
    margin: np.ndarray  # (n_edges, 2) fraction of the edge kept straight at ends a, b
    side_shift: np.ndarray  # (n_corners, 3) lattice shift of each side's copy
    slot_angle: np.ndarray  # (n_corners,) unwrapped angle, slot order per edge
    slot_gap: np.ndarray  # (n_corners,) angle to the next slot
    slot_radius: np.ndarray  # (n_corners,)
    port_point: np.ndarray  # (2 n_corners, 3) end of each side's straight track
    port_dir: np.ndarray  # (2 n_corners, 3) unit direction toward the corner


def side_tracks(scaffold: Scaffold, rho: float, h: float, margin: float, near_angle: float | None = None) -> Tracks:
    """Compute the :class:`Tracks` of ``scaffold``: tracks at in-face offset ``rho`` and normal offset ``h``.

    ``margin`` is the least length kept straight at each edge end (more at acute corners).
    With ``near_angle`` (radians) the normal offset is applied only on edges where two
    faces meet at a smaller angle (a two-sided polygon): elsewhere it is not needed, and
    leaving it out keeps the tracks independent of the faces' orientation, so that a
    motion reversing a face's corner order still maps the tracks onto tracks.
    Raises :class:`~lkspace.errors.GeometryError` when a face's centroid lies on an edge's
    line or the normal offset reorders the strands around an edge.
    """
    pa, pb = scaffold.edge_points[:, 0], scaffold.edge_points[:, 1]
    vec = pb - pa
    length = np.linalg.norm(vec, axis=1)
    axis = vec / length[:, None]
    u1, u2 = perpendicular_frames(axis)
    e = scaffold.side_edge
    d = axis[e]
    shift = (
        lattice_shift(scaffold, scaffold.side_translation) if scaffold.periodic else np.zeros((scaffold.n_corners, 3))
    )
    r = scaffold.face_centroids[scaffold.corner_face] - (pa[e] + shift)
    r = r - np.sum(r * d, axis=1, keepdims=True) * d
    r_norm = np.linalg.norm(r, axis=1)
    bad = np.flatnonzero(r_norm <= 1e-9 * max(1.0, float(length.max())))
    if len(bad):
        s = bad[0]
        raise GeometryError(
            f"{scaffold.name}: face {scaffold.corner_face[s]} has its centroid on the line of "
            f"edge {scaffold.edge_name(e[s])}; cannot place its strand"
        )
    r /= r_norm[:, None]
    n = face_normals(scaffold)[scaffold.corner_face]
    n = n - np.sum(n * d, axis=1, keepdims=True) * d
    n_norm = np.linalg.norm(n, axis=1, keepdims=True)
    n = np.where(n_norm > 1e-9, n / np.where(n_norm > 0, n_norm, 1), 0.0)
    h_side = np.full(len(e), float(h))
    if near_angle is not None:
        h_side *= min_face_angle(scaffold, r, u1, u2)[e] < near_angle
    w = rho * r + h_side[:, None] * n  # (n_corners, 3) track offsets
    slot_angle, gap, slot_radius = slot_angles(scaffold, w, u1, u2, h)
    frac = end_margins(scaffold, length, rho, h, margin)
    # straight track ends: each port's point and the direction toward its corner
    n_ports = 2 * scaffold.n_corners
    ports = np.arange(n_ports)
    ps = ports // 2
    at_a = (ports % 2 == 0) == scaffold.side_forward[ps]
    pe = e[ps]
    par = np.where(at_a, frac[pe, 0], 1.0 - frac[pe, 1])
    port_point = pa[pe] + par[:, None] * vec[pe] + shift[ps] + w[ps]
    port_dir = np.where(at_a[:, None], -axis[pe], axis[pe])
    return Tracks(pa, pb, axis, length, u1, u2, frac, shift, slot_angle, gap, slot_radius, port_point, port_dir)


def slot_angles(
    scaffold: Scaffold, w: np.ndarray, u1: np.ndarray, u2: np.ndarray, h: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return the tracks' slots around their edges, in slot order: ``(angle, gap, radius)``, each ``(n_corners,)``.

    ``w`` (n_corners, 3) are the track offsets from the edges; the angles about each edge
    (frame ``u1``, ``u2``) are unwrapped to increase strictly within one turn, ``gap`` is
    the angle to the next slot.  Raises :class:`~lkspace.errors.GeometryError` when the
    normal offset ``h`` reorders the strands around an edge.
    """
    e = scaffold.side_edge
    radial = scaffold.radial
    ang = np.arctan2(np.sum(w * u2[e], axis=1), np.sum(w * u1[e], axis=1))
    rad = np.linalg.norm(w, axis=1)
    # unwrap the angles of each edge in slot order: strictly increasing within one turn
    sides = radial.edge_sides
    starts = radial.edge_starts
    edge_of = e[sides]
    first = ang[sides[starts[edge_of]]]
    slot_angle = first + np.mod(ang[sides] - first, 2 * np.pi)
    nxt = np.arange(len(sides)) + 1
    last = nxt == starts[edge_of + 1]
    nxt[last] = starts[edge_of[last]]
    gap = slot_angle[nxt] - slot_angle
    gap[last] += 2 * np.pi
    not_single = scaffold.edge_degrees[edge_of] > 1
    broken = np.flatnonzero(not_single & ((gap <= 1e-9) | (gap >= 2 * np.pi - 1e-9)) & ~last)
    if len(broken):
        k = edge_of[broken[0]]
        raise GeometryError(
            f"{scaffold.name}: edge {scaffold.edge_name(k)}: the normal offset {h:.3g} reorders the strands "
            "around the edge; use a smaller `normal_offset`",
            parameter="normal_offset",
        )
    return slot_angle, gap, rad[sides]


def end_margins(scaffold: Scaffold, length: np.ndarray, rho: float, h: float, margin: float) -> np.ndarray:
    """Return the fraction ``(n_edges, 2)`` of each edge kept straight at its ends a and b.

    At least ``margin``, longer at acute corners so that the corner turn ends before the
    helix starts (the inset corner lies ``rho * cot(alpha / 2)`` from the vertex); at most
    0.42 of the edge.
    """
    e = scaffold.side_edge
    pos = scaffold.corner_positions
    to_prev = pos[scaffold.corner_prev] - pos
    to_next = pos[scaffold.corner_next] - pos
    cosang = np.sum(to_prev * to_next, axis=1) / (np.linalg.norm(to_prev, axis=1) * np.linalg.norm(to_next, axis=1))
    half = 0.5 * np.arccos(np.clip(cosang, -1.0, 1.0))
    need = np.maximum(margin, 1.4 * np.hypot(rho, h) / np.tan(np.maximum(half, 1e-3)))  # per corner
    side_need = np.column_stack([need, need[scaffold.corner_next]])  # first, second corner
    fwd_side = scaffold.side_forward
    need_a = np.where(fwd_side, side_need[:, 0], side_need[:, 1])
    need_b = np.where(fwd_side, side_need[:, 1], side_need[:, 0])
    ends_need = np.zeros((len(length), 2))
    np.maximum.at(ends_need[:, 0], e, need_a)
    np.maximum.at(ends_need[:, 1], e, need_b)
    return np.minimum(ends_need / length[:, None], 0.42)


def min_face_angle(scaffold: Scaffold, r: np.ndarray, u1: np.ndarray, u2: np.ndarray) -> np.ndarray:
    """(n_edges,) the smallest angle between two faces about each edge (``2 pi`` for a lone face)."""
    e = scaffold.side_edge
    ang = np.arctan2(np.sum(r * u2[e], axis=1), np.sum(r * u1[e], axis=1))
    order = np.lexsort((ang, e))
    se, sa = e[order], ang[order]
    gaps = np.full(scaffold.n_edges, 2 * np.pi)
    same = se[1:] == se[:-1]
    np.minimum.at(gaps, se[1:][same], np.diff(sa)[same])
    first = np.r_[True, ~same]
    last = np.r_[~same, True]
    wrap = sa[first] + 2 * np.pi - sa[last]  # from each edge's last face back to its first
    multi = np.bincount(e, minlength=scaffold.n_edges)[se[first]] > 1
    np.minimum.at(gaps, se[first][multi], wrap[multi])
    return gaps


def bezier_controls(a: np.ndarray, da: np.ndarray, c: np.ndarray, dc: np.ndarray) -> np.ndarray:
    """Return the control points ``(n, 3)`` where the line ``a + s*da`` meets ``c - u*dc`` (closest approach)."""
    w0 = a - c
    b = -np.sum(da * dc, axis=1)
    dd = np.sum(w0 * da, axis=1)
    ee = -np.sum(w0 * dc, axis=1)
    denom = 1.0 - b * b
    ok = denom > 1e-6
    safe = np.where(ok, denom, 1.0)
    s = np.where(ok, (b * ee - dd) / safe, 0.0)
    u = np.where(ok, (ee - b * dd) / safe, 0.0)
    span = np.linalg.norm(c - a, axis=1)
    s = np.clip(s, 0.0, 2.0 * span)
    u = np.clip(u, 0.0, 2.0 * span)
    q = 0.5 * ((a + s[:, None] * da) + (c - u[:, None] * dc))
    return np.where(ok[:, None], q, 0.5 * (a + c))


def default_scale(scaffold: Scaffold) -> float:
    """Shortest edge length: the unit of every default parameter."""
    p = scaffold.edge_points
    return float(np.linalg.norm(p[:, 1] - p[:, 0], axis=1).min())


def place_name(scaffold: Scaffold, point: ArrayLike) -> str:
    """Name the scaffold vertex or edge nearest to ``point``."""
    point = np.asarray(point)
    pa, pb = scaffold.edge_points[:, 0], scaffold.edge_points[:, 1]
    v = pb - pa
    s = np.clip(np.sum((point - pa) * v, axis=1) / np.sum(v * v, axis=1), 0, 1)
    dist = np.linalg.norm(pa + s[:, None] * v - point, axis=1)
    e = int(np.argmin(dist))
    if s[e] < 0.15:
        return f"vertex {scaffold.edge_vertices[e, 0]} (edge {scaffold.edge_name(e)})"
    if s[e] > 0.85:
        return f"vertex {scaffold.edge_vertices[e, 1]} (edge {scaffold.edge_name(e)})"
    return f"edge {scaffold.edge_name(e)}"
