"""Small non-manifold scaffolds: two-sided polygons and books of quads."""

from __future__ import annotations

import numpy as np

from ..errors import ScaffoldError
from ..model.scaffold import Scaffold


def dihedron(n: int) -> Scaffold:
    """Two-sided regular ``n``-gon: two faces on one vertex cycle (front and back).

    Vertices lie on the unit circle in the xy plane; face 0 runs counter-clockwise seen
    from +z, face 1 is the same cycle reversed.  Every edge has degree 2.
    """
    if n < 3:
        raise ScaffoldError(f"dihedron:{n}: a polygon needs at least 3 vertices")
    angles = 2 * np.pi * np.arange(n) / n
    vertices = np.column_stack([np.cos(angles), np.sin(angles), np.zeros(n)])
    cycle = list(range(n))
    return Scaffold.from_faces(vertices, [cycle, cycle[::-1]], name=f"dihedron:{n}")


def book(k: int) -> Scaffold:
    """``k`` unit quads ("pages") sharing the edge 0-1 on the z axis, at equal angles.

    Page ``j`` spans angle ``2*pi*j/k`` about +z, so it fills slot ``j`` of edge 0-1; its
    vertices are ``0, 2 + 2j, 3 + 2j, 1``.  The spine has degree ``k``; every other edge
    is a boundary edge.
    """
    if k < 1:
        raise ScaffoldError(f"book:{k}: a book needs at least one page")
    vertices = [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
    faces = []
    for j in range(k):
        a = 2 * np.pi * j / k
        vertices += [[np.cos(a), np.sin(a), 0.0], [np.cos(a), np.sin(a), 1.0]]
        faces.append([0, 2 + 2 * j, 3 + 2 * j, 1])
    return Scaffold.from_faces(vertices, faces, name=f"book:{k}")
