"""Tube meshes around polylines (rotation-minimizing frames), for mesh formats and pictures.

Everything is numpy-vectorized: the frames come from one reference normal per point
(perpendicular to the tangent) corrected by the accumulated rotation of parallel
transport (a cumulative sum of per-segment angles), so no Python loop runs per point.
"""

from __future__ import annotations

from typing import TypeAlias

import numpy as np
from numpy.typing import ArrayLike

from ..geometry.clearance import resample
from ..geometry.realization import Realization

TubeMesh: TypeAlias = tuple[np.ndarray, np.ndarray, np.ndarray]
"""``(vertices (n, 3) float64, normals (n, 3) float64, faces (m, 3) int64)`` of one tube."""


def tangents(points: np.ndarray, closed: bool) -> np.ndarray:
    """(n, 3) unit tangents by central differences (one-sided at the ends of an open polyline)."""
    nxt = np.roll(points, -1, axis=0) if closed else np.vstack([points[1:], 2 * points[-1] - points[-2]])
    prv = np.roll(points, 1, axis=0) if closed else np.vstack([2 * points[0] - points[1], points[:-1]])
    tan = nxt - prv
    return tan / np.maximum(np.linalg.norm(tan, axis=1, keepdims=True), 1e-300)


def reflect_twice(vec: np.ndarray, p0: np.ndarray, p1: np.ndarray, t0: np.ndarray, t1: np.ndarray) -> np.ndarray:
    """Carry ``vec`` (3,) from point ``p0`` (tangent ``t0``) to ``p1`` (tangent ``t1``) by double reflection."""
    v1 = p1 - p0
    c1 = v1 @ v1
    if c1 < 1e-300:
        return vec
    r_l = vec - (2 / c1) * (v1 @ vec) * v1
    t_l = t0 - (2 / c1) * (v1 @ t0) * v1
    v2 = t1 - t_l
    c2 = v2 @ v2
    return r_l - (2 / c2) * (v2 @ r_l) * v2 if c2 > 1e-300 else r_l


def rotation_minimizing_frames(points: np.ndarray, closed: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Rotation-minimizing frames ``(tangent, normal, binormal)``, each ``(n, 3)`` float64.

    Each point gets a reference normal ``cross(t, e)`` (``e`` the coordinate axis least
    aligned with ``t``); the reference of point ``i - 1`` carried to point ``i`` by the
    double reflection of Wang et al. differs from the reference of ``i`` by an angle
    about ``t_i``; the cumulative sum of these angles turns the references into the
    parallel-transported frame.  A closed curve spreads its closing twist evenly.
    """
    points = np.asarray(points, np.float64)
    tan = tangents(points, closed)
    n = len(points)
    helper = np.eye(3)[np.argmin(np.abs(tan), axis=1)]
    ref = np.cross(tan, helper)
    ref /= np.linalg.norm(ref, axis=1, keepdims=True)
    other = np.cross(tan, ref)
    # carry ref[i - 1] from point i - 1 to point i (double reflection)
    v1 = np.diff(points, axis=0)
    c1 = np.einsum("ij,ij->i", v1, v1)
    safe1 = np.where(c1 > 1e-300, c1, 1.0)
    r_l = ref[:-1] - (2 / safe1 * np.einsum("ij,ij->i", v1, ref[:-1]))[:, None] * v1
    t_l = tan[:-1] - (2 / safe1 * np.einsum("ij,ij->i", v1, tan[:-1]))[:, None] * v1
    v2 = tan[1:] - t_l
    c2 = np.einsum("ij,ij->i", v2, v2)
    safe2 = np.where(c2 > 1e-300, c2, 1.0)
    carried = r_l - np.where(c2 > 1e-300, 2 / safe2 * np.einsum("ij,ij->i", v2, r_l), 0.0)[:, None] * v2
    carried = np.where((c1 > 1e-300)[:, None], carried, ref[:-1])
    # angle of the carried vector in the frame (ref, other) of point i
    step = np.arctan2(np.einsum("ij,ij->i", carried, other[1:]), np.einsum("ij,ij->i", carried, ref[1:]))
    theta = np.concatenate([[0.0], np.cumsum(step)])
    if closed and n > 2:  # spread the closing twist along the curve
        last = np.cos(theta[-1]) * ref[-1] + np.sin(theta[-1]) * other[-1]
        carried_last = reflect_twice(last, points[-1], points[0], tan[-1], tan[0])
        closing = np.arctan2(carried_last @ other[0], carried_last @ ref[0])
        theta = theta - closing * np.arange(n) / n
    cos_t, sin_t = np.cos(theta)[:, None], np.sin(theta)[:, None]
    normal = cos_t * ref + sin_t * other
    binormal = np.cross(tan, normal)
    return tan, normal, binormal


def tube(points: ArrayLike, closed: bool, radius: float, sides: int = 12) -> TubeMesh:
    """Build the tube mesh around a polyline (flat caps on an open one).

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
        pts = curve if spacing is None else resample(curve, bool(closed), spacing).points
        out.append(tube(pts, bool(closed), radius, sides))
    return out


def merged(meshes: list[TubeMesh]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Concatenate tube meshes: ``(vertices, faces, body (n_faces,) int64)``, faces renumbered."""
    if not meshes:
        return np.zeros((0, 3)), np.zeros((0, 3), np.int64), np.zeros(0, np.int64)
    counts = np.array([len(v) for v, _, _ in meshes])
    base = np.concatenate([[0], np.cumsum(counts)[:-1]])
    verts = np.vstack([v for v, _, _ in meshes])
    faces = np.vstack([f + b for (_, _, f), b in zip(meshes, base, strict=True)])
    body = np.repeat(np.arange(len(meshes)), [len(f) for _, _, f in meshes])
    return verts, faces, body
