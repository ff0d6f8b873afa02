"""Prisms and antiprisms: the numbered convex solids ``prism:N`` and ``antiprism:N``.

Both have two regular N-gons (circumradius 1) as caps, face 0 the top (``z > 0``) and
face 1 the bottom, then the sides in order around the z axis; every face runs
counter-clockwise seen from outside.  The solids are uniform: a prism's sides are
squares, an antiprism's equilateral triangles (``antiprism:3`` is the octahedron).

``prism:N``: 2N vertices, 3N edges, N + 2 faces.  ``antiprism:N``: 2N vertices, 4N
edges, 2N + 2 faces.
"""

from __future__ import annotations

import numpy as np

from ..errors import ScaffoldError
from ..model.scaffold import Scaffold


def _ring(n: int, z: float, turn: float = 0.0) -> np.ndarray:
    angles = 2 * np.pi * (np.arange(n) + turn) / n
    return np.column_stack([np.cos(angles), np.sin(angles), np.full(n, z)])


def prism(n: int) -> Scaffold:
    """Build the uniform ``n``-gonal prism: top ring vertices ``0..n-1``, bottom ``n..2n-1``."""
    if n < 3:
        raise ScaffoldError(f"prism:{n}: a prism needs N >= 3")
    h = np.sin(np.pi / n)  # half the side of the cap: square sides
    top, bottom = list(range(n)), list(range(n, 2 * n))
    faces = [top, bottom[::-1]]
    faces += [[k, n + k, n + (k + 1) % n, (k + 1) % n] for k in range(n)]
    return Scaffold.from_faces(np.vstack([_ring(n, h), _ring(n, -h)]), faces, name=f"prism:{n}")


def antiprism(n: int) -> Scaffold:
    """Build the uniform ``n``-gonal antiprism: top ring ``0..n-1``, bottom ring ``n..2n-1`` turned by half a step."""
    if n < 3:
        raise ScaffoldError(f"antiprism:{n}: an antiprism needs N >= 3")
    h = float(np.sqrt(4 * np.sin(np.pi / n) ** 2 - 2 + 2 * np.cos(np.pi / n))) / 2
    top, bottom = list(range(n)), list(range(n, 2 * n))
    faces = [top, bottom[::-1]]
    for k in range(n):
        faces.append([k, n + k, (k + 1) % n])
        faces.append([(k + 1) % n, n + k, n + (k + 1) % n])
    return Scaffold.from_faces(np.vstack([_ring(n, h), _ring(n, -h, 0.5)]), faces, name=f"antiprism:{n}")
