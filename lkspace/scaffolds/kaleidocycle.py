"""Kaleidocycles: rings of tetrahedra hinged edge to edge (the paper's flexagon-like scaffolds).

``kaleidocycle:N`` (N even, 4 <= N) is a ring of N tetrahedra.  Its N **hinges** are
segments of length 1 centred on a circle of radius :data:`RING_RADIUS` about the z axis,
at angles ``2 pi i / N``; they stand alternately vertical and radial, so consecutive
hinges are perpendicular, as in a kaleidocycle.  Tetrahedron ``i`` is the convex hull of
hinges ``i`` and ``i + 1``: its four triangles each hold one hinge.  Every hinge is
shared by two tetrahedra (degree 4); the other edges have degree 2.  Each tetrahedron
lies in the wedge between its hinges' half-planes, so tetrahedra meet only at hinges.
"""

from __future__ import annotations

import numpy as np

from ..errors import ScaffoldError
from ..model.scaffold import Scaffold

RING_RADIUS = 1.2
"""Distance of the hinges' centres from the ring's axis (the hinges have length 1)."""


def kaleidocycle(n: int) -> Scaffold:
    """Build the ring of ``n`` tetrahedra hinged at alternately vertical and radial edges.

    Examples
    --------
    >>> s = kaleidocycle(6)
    >>> s.n_vertices, s.n_faces, sorted(set(s.edge_degrees.tolist()))
    (12, 24, [2, 4])
    """
    if n < 4 or n % 2:
        raise ScaffoldError(f"kaleidocycle:{n}: needs an even number of tetrahedra, at least 4")
    angles = 2 * np.pi * np.arange(n) / n
    centres = RING_RADIUS * np.column_stack([np.cos(angles), np.sin(angles), np.zeros(n)])
    radial = np.column_stack([np.cos(angles), np.sin(angles), np.zeros(n)])
    up = np.tile([0.0, 0.0, 1.0], (n, 1))
    direction = np.where((np.arange(n) % 2 == 0)[:, None], up, radial)
    a = centres - 0.5 * direction  # hinge i runs from vertex 2i to vertex 2i + 1
    b = centres + 0.5 * direction
    vertices = np.empty((2 * n, 3))
    vertices[0::2], vertices[1::2] = a, b
    faces = []
    for i in range(n):
        j = (i + 1) % n
        ai, bi, aj, bj = 2 * i, 2 * i + 1, 2 * j, 2 * j + 1
        tet = vertices[[ai, bi, aj, bj]]
        centre = tet.mean(axis=0)
        for tri in ((ai, bi, aj), (bi, ai, bj), (aj, bj, ai), (bj, aj, bi)):
            p = vertices[list(tri)]
            outward = np.cross(p[1] - p[0], p[2] - p[0]) @ (p.mean(axis=0) - centre) > 0
            faces.append(list(tri) if outward else list(tri[::-1]))
    return Scaffold.from_faces(vertices, faces, name=f"kaleidocycle:{n}")
