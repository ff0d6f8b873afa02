"""Tube meshes around polylines (rotation-minimizing frames), for mesh formats and pictures."""

from __future__ import annotations

from typing import TypeAlias

import numpy as np
from numpy.typing import ArrayLike

from ..geometry.clearance import resample
from ..geometry.realization import Realization

TubeMesh: TypeAlias = tuple[np.ndarray, np.ndarray, np.ndarray]
"""``(vertices (n, 3) float64, normals (n, 3) float64, faces (m, 3) int64)`` of one tube."""


def rotation_minimizing_frames(points: np.ndarray, closed: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Rotation-minimizing frames ``(tangent, normal, binormal)``, each ``(n, 3)``."""
    nxt = np.roll(points, -1, axis=0) if closed else np.vstack([points[1:], 2 * points[-1] - points[-2]])
    prv = np.roll(points, 1, axis=0) if closed else np.vstack([2 * points[0] - points[1], points[:-1]])
    tan = nxt - prv
    tan /= np.maximum(np.linalg.norm(tan, axis=1, keepdims=True), 1e-300)
    n = len(points)
    normal = np.empty_like(points)
    helper = np.eye(3)[np.argmin(np.abs(tan[0]))]
    v = np.cross(tan[0], helper)
    normal[0] = v / np.linalg.norm(v)
    for i in range(1, n):  # parallel transport (double reflection)
        v1 = points[i] - points[i - 1]
        c1 = v1 @ v1
        if c1 < 1e-300:
            normal[i] = normal[i - 1]
            continue
        r_l = normal[i - 1] - (2 / c1) * (v1 @ normal[i - 1]) * v1
        t_l = tan[i - 1] - (2 / c1) * (v1 @ tan[i - 1]) * v1
        v2 = tan[i] - t_l
        c2 = v2 @ v2
        normal[i] = r_l - (2 / c2) * (v2 @ r_l) * v2 if c2 > 1e-300 else r_l
    binormal = np.cross(tan, normal)
    if closed and n > 2:  # spread the closing twist along the curve
        angle = np.arctan2(np.cross(normal[-1], normal[0]) @ tan[0], normal[-1] @ normal[0])
        phi = angle * np.arange(n) / n
        c, s = np.cos(phi)[:, None], np.sin(phi)[:, None]
        normal, binormal = c * normal + s * binormal, -s * normal + c * binormal
    return tan, normal, binormal


def tube(points: ArrayLike, closed: bool, radius: float, sides: int = 12) -> TubeMesh:
    """Build the tube mesh around a polyline.

    Returns
    -------
    vertices : (n * sides + caps, 3) float64
    normals : same shape, unit outward normals
    faces : (n_faces, 3) int64 triangles, counter-clockwise seen from outside
    """
    points = np.asarray(points, np.float64)
    n = len(points)
    _, normal, binormal = rotation_minimizing_frames(points, closed)
    ang = 2 * np.pi * np.arange(sides) / sides
    ring = np.cos(ang)[None, :, None] * normal[:, None] + np.sin(ang)[None, :, None] * binormal[:, None]
    verts = (points[:, None] + radius * ring).reshape(-1, 3)
    norms = ring.reshape(-1, 3)
    i = np.arange(n if closed else n - 1)
    j = np.arange(sides)
    i0 = i[:, None] * sides + j[None, :]
    i1 = ((i[:, None] + 1) % n) * sides + j[None, :]
    j1 = (j[None, :] + 1) % sides
    i0n = i[:, None] * sides + j1
    i1n = ((i[:, None] + 1) % n) * sides + j1
    faces = np.concatenate([np.stack([i0, i0n, i1], -1).reshape(-1, 3), np.stack([i0n, i1n, i1], -1).reshape(-1, 3)])
    if not closed:  # flat caps
        t0 = points[1] - points[0]
        t1 = points[-1] - points[-2]
        c0, c1 = len(verts), len(verts) + 1
        verts = np.vstack([verts, points[0], points[-1]])
        norms = np.vstack([norms, -t0 / np.linalg.norm(t0), t1 / np.linalg.norm(t1)])
        cap0 = np.column_stack([np.full(sides, c0), j1[0], j])
        cap1 = np.column_stack([np.full(sides, c1), (n - 1) * sides + j, (n - 1) * sides + j1[0]])
        faces = np.vstack([faces, cap0, cap1])
    return verts, norms, faces.astype(np.int64)


def tube_meshes(real: Realization, radius: float | None, sides: int, spacing: float | None = None) -> list[TubeMesh]:
    """Build one :func:`tube` per curve of ``real`` (optionally resampled at ``spacing`` first)."""
    radius = real.tube_radius if radius is None else radius
    out = []
    for curve, closed in zip(real.curves, real.closed, strict=False):
        pts = curve if spacing is None else resample(curve, bool(closed), spacing)[0]
        out.append(tube(pts, bool(closed), radius, sides))
    return out
