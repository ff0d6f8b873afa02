"""Ropelength of polylines read from an exported OBJ, written independently of lkspace.

Ropelength = total length / thickness, where the thickness is the smaller of

* the smallest **curvature radius**: the radius of the circle through three consecutive
  points (the discrete curvature of the polyline), and
* half the smallest **doubly critical** distance between two points (a local minimum
  of the distance as either point moves along its curve; ropelength literature: the
  thickness is the smaller of these two bounds).

Used by the tests and ``experiments/bench_geometry.py``; shares no code with
``lkspace.geometry``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree


def read_obj_polylines(path: str | Path) -> list[tuple[np.ndarray, bool]]:
    """Polylines of an OBJ file: ``[(points (n, 3), closed), ...]`` from its ``v`` and ``l`` lines."""
    verts: list[list[float]] = []
    lines: list[list[int]] = []
    for row in Path(path).read_text().splitlines():
        parts = row.split()
        if not parts:
            continue
        if parts[0] == "v":
            verts.append([float(p) for p in parts[1:4]])
        elif parts[0] == "l":
            lines.append([int(p) - 1 for p in parts[1:]])
    v = np.array(verts)
    out = []
    for idx in lines:
        closed = len(idx) > 2 and idx[0] == idx[-1]
        out.append((v[idx[:-1] if closed else idx], closed))
    return out


def curvature_radii(points: np.ndarray, closed: bool) -> np.ndarray:
    """Circumradius of every triple of consecutive points, ``(n,)`` (``inf`` where straight)."""
    p = np.vstack([points[-1:], points, points[:1]]) if closed else points
    a, b, c = p[:-2], p[1:-1], p[2:]
    ab, bc, ca = (np.linalg.norm(x, axis=1) for x in (b - a, c - b, a - c))
    area2 = np.linalg.norm(np.cross(b - a, c - a), axis=1)  # twice the triangle's area
    with np.errstate(divide="ignore", invalid="ignore"):
        r = ab * bc * ca / (2.0 * area2)
    return np.where(area2 > 1e-15 * np.maximum(ab * bc, 1e-300), r, np.inf)


def _dense(points: np.ndarray, closed: bool, spacing: float) -> tuple[np.ndarray, np.ndarray, float]:
    p = np.vstack([points, points[:1]]) if closed else points
    seg = np.linalg.norm(np.diff(p, axis=0), axis=1)
    cum = np.concatenate([[0.0], np.cumsum(seg)])
    m = max(3, int(np.ceil(cum[-1] / spacing)))
    s = np.linspace(0.0, cum[-1], m, endpoint=not closed)
    return np.column_stack([np.interp(s, cum, p[:, i]) for i in range(3)]), s, float(cum[-1])


def _doubly_critical(pts: np.ndarray, prev: np.ndarray, nxt: np.ndarray, i: np.ndarray, j: np.ndarray) -> np.ndarray:
    """Mask of pairs whose distance is a local minimum when either point moves one step along its curve."""
    d = np.linalg.norm(pts[i] - pts[j], axis=1)
    ok = np.ones(len(i), bool)
    for a, b in ((prev[i], j), (nxt[i], j), (i, prev[j]), (i, nxt[j])):
        ok &= d <= np.linalg.norm(pts[a] - pts[b], axis=1)
    return ok


def ropelength(curves: list[tuple[np.ndarray, bool]], n_points: int = 6000) -> dict[str, float]:
    """``{"length", "curvature_radius", "half_distance", "thickness", "ropelength"}`` of closed curves.

    ``half_distance`` is half the smallest **doubly critical** distance: between points
    (resampled, ``n_points`` in all) at least three steps apart whose distance is a
    local minimum in both (no shorter distance when either moves one step along its
    curve).  Near a point the distance to its own curve grows with the arc, so only
    real approaches (another strand, a fold back) count.
    """
    seg_len = [
        float(np.linalg.norm(np.diff(np.vstack([c, c[:1]]) if cl else c, axis=0), axis=1).sum()) for c, cl in curves
    ]
    total = sum(seg_len)
    rc = min(float(curvature_radii(c, cl).min()) for c, cl in curves)
    spacing = total / n_points
    chunks = [_dense(c, cl, spacing) for c, cl in curves]
    pts = np.vstack([x[0] for x in chunks])
    sizes = np.array([len(x[0]) for x in chunks])
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
    owner = np.repeat(np.arange(len(chunks)), sizes)
    index = np.arange(len(pts)) - starts[owner]
    prev = starts[owner] + (index - 1) % sizes[owner]
    nxt = starts[owner] + (index + 1) % sizes[owner]
    tree = cKDTree(pts)
    best = np.inf
    radius = min(2 * rc, 0.05 * total)
    while not np.isfinite(best) and radius < 4 * rc:  # farther pairs cannot limit the thickness
        pairs = tree.query_pairs(radius, output_type="ndarray")
        if len(pairs):
            i, j = pairs[:, 0], pairs[:, 1]
            steps = np.abs(index[i] - index[j])
            steps = np.minimum(steps, sizes[owner[i]] - steps)
            keep = (owner[i] != owner[j]) | (steps > 3)
            i, j = i[keep], j[keep]
            crit = _doubly_critical(pts, prev, nxt, i, j)
            if crit.any():
                best = float(np.linalg.norm(pts[i[crit]] - pts[j[crit]], axis=1).min())
        radius *= 1.25  # the first radius holding a doubly critical pair holds the least one
    half = best / 2  # inf when no approach is closer than twice the curvature radius
    thickness = min(rc, half)
    return {
        "length": total,
        "curvature_radius": rc,
        "half_distance": half,
        "thickness": thickness,
        "ropelength": total / thickness,
    }


def most_turning(points: np.ndarray, closed: bool, arc: float) -> float:
    """The most a polyline turns (sum of its exterior angles, radians) along any stretch of length ``arc``.

    A stretch ``arc`` long turns ``arc / r`` along a circle of radius ``r``: a full loop
    (``2 pi``) within ``2 pi r`` of arc is a curl of radius ``r`` or less.
    """
    p = np.vstack([points, points[:1]]) if closed else points
    seg = np.diff(p, axis=0)
    length = np.linalg.norm(seg, axis=1)
    tangent = seg / length[:, None]
    after = np.roll(tangent, -1, axis=0) if closed else tangent[1:]
    angle = np.arccos(np.clip(np.sum(tangent[: len(after)] * after, axis=1), -1.0, 1.0))
    if closed:  # go round twice so that every stretch starts in the first round
        angle, length = np.tile(angle, 2), np.tile(length, 2)
    at = np.concatenate([[0.0], np.cumsum(length)])  # angle[k] is at the end of segment k
    turned = np.concatenate([[0.0], np.cumsum(angle)])
    starts = at[: len(angle)]
    ends = np.minimum(np.searchsorted(at[1:], starts + arc, side="right"), len(angle))  # angles up to start + arc
    first = np.arange(len(angle))
    return float((turned[ends] - turned[first]).max())
