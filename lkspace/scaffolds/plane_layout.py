"""Vertex positions for a plane mesh given only by its faces: a flat, two-sided drawing.

The mesh is drawn in the plane z = 0 as the paper's figure-eight mesh is: every face but
the largest lies in front, the largest (the outer face) covers them all from behind.

1. The outer face's vertices go on the unit circle, clockwise seen from +z (its normal,
   by the right-hand rule over its corners, points to -z: the realization offsets its
   strand behind the others).
2. Every other face gets a centre vertex joined to its corners, which makes a
   triangulated disk, and Tutte's barycentric drawing places each inner vertex at the
   mean of its neighbours (one linear solve).  The drawing of a triangulated disk with a
   convex boundary is an embedding with every triangle positively oriented (Tutte;
   Floater 2003).  A centre's neighbours are its face's corners, so the centre *is* the
   face's centroid, and it lies strictly inside every side of its face: the direction from
   an edge toward the face's centroid (which the realization offsets strands along,
   ``docs/geometry.md``) points into the face on every edge.

The positions depend on the faces alone: the same faces give the same bytes.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

FIN = 0.35
"""Height of a vertex of degree 2 above its neighbours' segment, in units of their distance."""
SIDE = 0.15
"""Its shift in the plane, to the side of the segment it was drawn on, in the same unit."""


def _signed_area(points: np.ndarray) -> float:
    x, y = points[:, 0], points[:, 1]
    return 0.5 * float((x * np.roll(y, -1) - np.roll(x, -1) * y).sum())


def largest_face(faces: Sequence[Sequence[int]]) -> int:
    """Return the default outer face: the largest, the first of equals."""
    return max(range(len(faces)), key=lambda f: (len(faces[f]), -f))


def plane_layout(n_vertices: int, faces: Sequence[Sequence[int]], outer: int | None = None) -> np.ndarray:
    """Tutte drawing of a plane mesh (faces as vertex cycles, one orientation): ``(n_vertices, 3) float64``, z = 0.

    Examples
    --------
    >>> pos = plane_layout(4, [[0, 1, 2], [0, 2, 3], [3, 2, 1, 0]])  # the figure-eight mesh's faces
    >>> pos[:, 2].tolist(), round(float(abs(pos[:, :2]).max()), 6)
    ([0.0, 0.0, 0.0, 0.0], 1.0)
    """
    outer = largest_face(faces) if outer is None else outer
    for turn in (-1, 1):
        pos = _tutte(n_vertices, faces, outer, turn, {})
        inner = next(f for f in range(len(faces)) if f != outer)
        if _signed_area(pos[list(faces[inner])]) > 0:  # front faces counter-clockwise, the outer one clockwise
            break
    fins = _fins(n_vertices, faces, outer, pos)
    if fins:
        pos = _tutte(n_vertices, faces, outer, turn, {w: p[:2] for w, p in fins.items()})
    out = np.c_[pos, np.zeros(n_vertices)]
    for w, p in fins.items():
        out[w] = p
    return out


def _fins(n_vertices: int, faces: Sequence[Sequence[int]], outer: int, pos: np.ndarray) -> dict[int, np.ndarray]:
    """Positions ``(x, y, z)`` for inner vertices of degree 2: above the middle of their neighbours.

    A vertex of degree 2 splits a side of a face in two (a triangle made from a digon,
    :mod:`~lkspace.scaffolds.diagram_mesh`).  In the plane that triangle would be flat or a
    sliver with needle angles; raised by ``FIN`` times its neighbours' distance it stands as a
    fin on their segment, and the faces on either side keep their shape in projection.
    """
    neighbours: list[set[int]] = [set() for _ in range(n_vertices)]
    for face in faces:
        for i, v in enumerate(face):
            neighbours[v] |= {face[i - 1], face[(i + 1) % len(face)]}
    boundary = set(faces[outer])
    groups: dict[tuple[int, int, float], list[tuple[float, int]]] = {}
    for w in range(n_vertices):
        if len(neighbours[w]) == 2 and w not in boundary:
            u, v = sorted(neighbours[w])
            mid, span = (pos[u] + pos[v]) / 2, pos[v] - pos[u]
            normal = np.array([-span[1], span[0]]) / np.linalg.norm(span)
            offset = float((pos[w] - mid) @ normal)  # the side Tutte chose, and how far
            groups.setdefault((u, v, 1.0 if offset >= 0 else -1.0), []).append((abs(offset), w))
    out: dict[int, np.ndarray] = {}
    for (u, v, side), members in groups.items():
        mid, span = (pos[u] + pos[v]) / 2, pos[v] - pos[u]
        normal = np.array([-span[1], span[0]]) / np.linalg.norm(span)
        length = float(np.linalg.norm(span))
        for rank, (_, w) in enumerate(sorted(members)):  # nested fins on one segment: the inner one lower
            out[w] = np.r_[mid + side * SIDE * (rank + 1) * length * normal, FIN * (rank + 1) * length]
    return out


def _tutte(
    n_vertices: int, faces: Sequence[Sequence[int]], outer: int, turn: int, placed: dict[int, np.ndarray]
) -> np.ndarray:
    n = n_vertices + len(faces)
    rows: list[set[int]] = [set() for _ in range(n)]
    for f, face in enumerate(faces):
        for i, v in enumerate(face):
            w = face[(i + 1) % len(face)]
            rows[v].add(w)
            rows[w].add(v)
            if f != outer:
                rows[v].add(n_vertices + f)
                rows[n_vertices + f].add(v)
    fixed = list(faces[outer])
    angles = turn * 2 * np.pi * np.arange(len(fixed)) / len(fixed)
    pos = np.zeros((n, 2))
    pos[fixed] = np.c_[np.cos(angles), np.sin(angles)]
    for v, p in placed.items():
        pos[v] = p
    on_circle = set(fixed) | set(placed)
    free = [v for v in range(n) if v not in on_circle and v != n_vertices + outer]
    index = {v: i for i, v in enumerate(free)}
    matrix = np.zeros((len(free), len(free)))
    rhs = np.zeros((len(free), 2))
    for v in free:
        i = index[v]
        matrix[i, i] = len(rows[v])
        for w in rows[v]:
            if w in index:
                matrix[i, index[w]] -= 1
            else:
                rhs[i] += pos[w]
    if free:
        pos[free] = np.linalg.solve(matrix, rhs)
    return pos[:n_vertices]


def lift_to_sphere(points: np.ndarray) -> np.ndarray:
    """Inverse stereographic projection of plane ``points`` ``(n, 2)``, scaled so their centroid has z = 0."""
    radii2 = (points**2).sum(axis=1)
    low, high = 1e-3, 1e3
    for _ in range(100):
        mid = float(np.sqrt(low * high))
        r2 = radii2 * mid**2
        low, high = (mid, high) if float(((r2 - 1) / (r2 + 1)).mean()) < 0 else (low, mid)
    q = points * np.sqrt(low * high)
    r2 = (q**2).sum(axis=1)
    return np.c_[2 * q, r2 - 1] / (r2 + 1)[:, None]


def sphere_layout(n_vertices: int, faces: Sequence[Sequence[int]], outer: int | None = None) -> np.ndarray:
    """Return the drawing of :func:`plane_layout` lifted onto the unit sphere, fins standing out radially."""
    flat = plane_layout(n_vertices, faces, outer)
    out = lift_to_sphere(flat[:, :2])
    for w in np.flatnonzero(flat[:, 2] > 0):  # fins stand out radially
        u, v = sorted(
            {x for face in faces for i, x in enumerate(face) if w in (face[i - 1], face[(i + 1) % len(face)])}
        )
        out[w] *= 1 + FIN * float(np.linalg.norm(out[v] - out[u]))
    return out


def round_layout(n_vertices: int, faces: Sequence[Sequence[int]], outer: int | None = None) -> np.ndarray:
    """Return :func:`sphere_layout`'s positions smoothed on the sphere: each vertex the mean of its neighbours.

    Every face (the outer one too) gets a centre vertex, which makes a triangulation of the
    sphere; 200 rounds move each vertex to the normalized mean of its neighbours and the
    whole set to a zero centroid (a spherical Tutte iteration), which evens out the faces.
    """
    outer = largest_face(faces) if outer is None else outer
    start = sphere_layout(n_vertices, faces, outer)
    fins = np.linalg.norm(start, axis=1) > 1 + 1e-9
    n = n_vertices + len(faces)
    rows: list[set[int]] = [set() for _ in range(n)]
    for f, face in enumerate(faces):
        for i, v in enumerate(face):
            w = face[(i + 1) % len(face)]
            rows[v] |= {w, n_vertices + f}
            rows[w].add(v)
            rows[n_vertices + f].add(v)
    pos = np.zeros((n, 3))
    pos[:n_vertices] = start / np.linalg.norm(start, axis=1, keepdims=True)
    for f, face in enumerate(faces):
        mean = pos[list(face)].mean(axis=0)
        pos[n_vertices + f] = mean / np.linalg.norm(mean) if f != outer else -mean / np.linalg.norm(mean)
    index = [sorted(r) for r in rows]
    for _ in range(200):
        new = np.array([pos[r].sum(axis=0) for r in index])
        new -= new.mean(axis=0)
        pos = new / np.linalg.norm(new, axis=1, keepdims=True)
    out = pos[:n_vertices].copy()
    for fin in np.flatnonzero(fins):
        u, v = sorted(
            {x for face in faces for i, x in enumerate(face) if fin in (face[i - 1], face[(i + 1) % len(face)])}
        )
        out[fin] *= 1 + FIN * float(np.linalg.norm(out[v] - out[u]))
    return out
