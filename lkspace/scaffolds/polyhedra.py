"""Convex polyhedra as scaffolds: the Platonic solids and the truncated octahedron.

Faces are the facets of the convex hull (scipy / Qhull), coplanar triangles merged into
one polygon, each ordered counter-clockwise seen from outside (outward normals).
"""

from __future__ import annotations

import itertools

import numpy as np
from scipy.spatial import ConvexHull

from ..mesh import Scaffold

PHI = (1 + 5**0.5) / 2


def convex_polyhedron(points, name: str = "polyhedron", decimals: int = 6) -> Scaffold:
    """Scaffold of the convex hull of ``points (n, 3)``; vertices keep the input order.

    Examples
    --------
    >>> convex_polyhedron([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]).n_faces
    4
    """
    points = np.asarray(points, dtype=np.float64)
    hull = ConvexHull(points)
    planes = np.round(hull.equations, decimals) + 0.0
    _, facet_of_simplex = np.unique(planes, axis=0, return_inverse=True)
    used = np.unique(hull.simplices)
    renumber = -np.ones(len(points), np.int64)
    renumber[used] = np.arange(len(used))
    faces = []
    for facet in range(facet_of_simplex.max() + 1):
        members = np.flatnonzero(facet_of_simplex.reshape(-1) == facet)
        verts = np.unique(hull.simplices[members])
        normal = hull.equations[members[0], :3]
        center = points[verts].mean(axis=0)
        u = points[verts[0]] - center
        u /= np.linalg.norm(u)
        v = np.cross(normal, u)
        rel = points[verts] - center
        angles = np.arctan2(rel @ v, rel @ u)
        ordered = verts[np.argsort(angles)]
        faces.append(renumber[ordered].tolist())
    faces.sort(key=lambda f: (min(f), f))
    return Scaffold.from_faces(points[used], faces, name=name)


def _cyclic(vectors):
    out = []
    for v in vectors:
        for k in range(3):
            out.append(np.roll(v, k))
    return np.array(out, dtype=np.float64)


def _signs(v):
    """All sign patterns of ``v`` (zeros kept once)."""
    out = set()
    for signs in itertools.product((1, -1), repeat=len(v)):
        out.add(tuple(s * x for s, x in zip(signs, v)))
    return sorted(out, reverse=True)


def tetrahedron() -> Scaffold:
    """Regular tetrahedron: 4 vertices, 6 edges, 4 triangles."""
    return convex_polyhedron([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], "tetrahedron")


def cube() -> Scaffold:
    """Cube [-1, 1]^3: 8 vertices, 12 edges, 6 squares."""
    return convex_polyhedron(list(itertools.product((-1, 1), repeat=3)), "cube")


def octahedron() -> Scaffold:
    """Regular octahedron: 6 vertices, 12 edges, 8 triangles."""
    return convex_polyhedron(np.vstack([np.eye(3), -np.eye(3)]), "octahedron")


def icosahedron() -> Scaffold:
    """Regular icosahedron: 12 vertices, 30 edges, 20 triangles."""
    return convex_polyhedron(_cyclic(_signs((0, 1, PHI))), "icosahedron")


def dodecahedron() -> Scaffold:
    """Regular dodecahedron: 20 vertices, 30 edges, 12 pentagons."""
    points = np.vstack([list(itertools.product((-1, 1), repeat=3)), _cyclic(_signs((0, 1 / PHI, PHI)))])
    return convex_polyhedron(points, "dodecahedron")


def truncated_octahedron() -> Scaffold:
    """Truncated octahedron: 24 vertices, 36 edges, 6 squares and 8 hexagons."""
    points = sorted({p for v in itertools.permutations((0, 1, 2)) for p in _signs(v)}, reverse=True)
    return convex_polyhedron(points, "truncated-octahedron")
