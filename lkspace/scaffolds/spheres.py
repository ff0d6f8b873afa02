"""Large sphere meshes for benchmarks: geodesic (triangles) and cube spheres (quads).

Both are closed 2-manifolds with every edge of degree 2, any size, vertices on the unit
sphere; faces are oriented outward.

Examples
--------
>>> geodesic_sphere(1).n_faces, cube_sphere(3).n_faces
(80, 54)
"""

from __future__ import annotations

import numpy as np

from ..errors import ScaffoldError
from ..model.scaffold import Scaffold
from .polyhedra import icosahedron


def geodesic_sphere(level: int) -> Scaffold:
    """Build the icosahedron with each triangle split into 4, ``level`` times: ``20 * 4**level`` faces."""
    if level < 0:
        raise ScaffoldError(f"geodesic sphere level {level}: must be >= 0")
    base = icosahedron()
    vertices = base.vertices / np.linalg.norm(base.vertices, axis=1, keepdims=True)
    faces = np.array(base.faces(), np.int64)
    for _ in range(level):
        edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
        unique, inverse = np.unique(edges, axis=0, return_inverse=True)
        mid = vertices[unique].sum(axis=1)
        mid /= np.linalg.norm(mid, axis=1, keepdims=True)
        m = len(vertices) + inverse.reshape(3, -1)  # midpoints of sides 01, 12, 20
        vertices = np.vstack([vertices, mid])
        a, b, c = faces.T
        faces = np.concatenate(
            [np.column_stack(f) for f in ((a, m[0], m[2]), (m[0], b, m[1]), (m[2], m[1], c), (m[0], m[1], m[2]))]
        )
    return Scaffold.from_faces(vertices, faces.tolist(), name=f"geodesic-sphere:{level}")


def cube_sphere(n: int) -> Scaffold:
    """Each face of the cube cut into an ``n x n`` grid, projected to the sphere: ``6 n^2`` quads."""
    if n < 1:
        raise ScaffoldError(f"cube sphere n={n}: must be >= 1")
    grid = np.linspace(-1.0, 1.0, n + 1)
    index: dict[tuple[int, ...], int] = {}
    vertices: list[np.ndarray] = []
    faces = []

    def vertex(p: np.ndarray) -> int:
        key = tuple(int(round(x * n)) for x in p)
        if key not in index:
            index[key] = len(vertices)
            vertices.append(p / np.linalg.norm(p))
        return index[key]

    for axis in range(3):
        u_axis, v_axis = (axis + 1) % 3, (axis + 2) % 3
        for sign in (1.0, -1.0):
            for i in range(n):
                for j in range(n):
                    quad = []
                    for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        p = np.zeros(3)
                        p[axis], p[u_axis], p[v_axis] = sign, grid[i + di], grid[j + dj]
                        quad.append(vertex(p))
                    faces.append(quad if sign > 0 else quad[::-1])
    return Scaffold.from_faces(np.array(vertices), faces, name=f"cube-sphere:{n}")
