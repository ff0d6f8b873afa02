"""Convex polyhedra as scaffolds: the Platonic solids and three Archimedean ones (truncated tetrahedron, cuboctahedron, truncated octahedron).

:func:`convex_polyhedron` takes the facets of the convex hull (scipy / Qhull), coplanar
triangles merged into one polygon, each ordered counter-clockwise seen from outside
(outward normals).  The built-in solids carry the face lists it gives for their points,
written out in :data:`SOLID_FACES` so that loading a solid needs no scipy (a test checks
them against the hull).
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Sequence

import numpy as np
from numpy.typing import ArrayLike

from ..model.scaffold import Scaffold

PHI = (1 + 5**0.5) / 2


def convex_polyhedron(points: ArrayLike, name: str = "polyhedron", decimals: int = 6) -> Scaffold:
    """Scaffold of the convex hull of ``points (n, 3)``; vertices keep the input order.

    Examples
    --------
    >>> convex_polyhedron([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]).n_faces
    4
    """
    from scipy.spatial import ConvexHull

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


SOLID_FACES = {
    "tetrahedron": [[1, 0, 3], [2, 0, 1], [3, 0, 2], [2, 1, 3]],
    "cube": [[1, 0, 4, 5], [2, 0, 1, 3], [4, 0, 2, 6], [3, 1, 5, 7], [6, 2, 3, 7], [5, 4, 6, 7]],
    "octahedron": [[1, 0, 5], [2, 0, 1], [4, 0, 2], [5, 0, 4], [2, 1, 3], [3, 1, 5], [4, 2, 3], [4, 3, 5]],
    "icosahedron": [
        [1, 0, 6],
        [2, 0, 1],
        [4, 0, 8],
        [6, 0, 4],
        [8, 0, 2],
        [2, 1, 7],
        [5, 1, 6],
        [7, 1, 5],
        [3, 2, 7],
        [8, 2, 3],
        [8, 3, 10],
        [9, 3, 7],
        [10, 3, 9],
        [6, 4, 11],
        [10, 4, 8],
        [11, 4, 10],
        [7, 5, 9],
        [9, 5, 11],
        [11, 5, 6],
        [10, 9, 11],
    ],  # fmt: skip
    "dodecahedron": [
        [11, 17, 0, 18, 2],
        [12, 18, 0, 19, 1],
        [13, 19, 0, 17, 4],
        [3, 12, 1, 14, 8],
        [5, 14, 1, 19, 13],
        [3, 16, 2, 18, 12],
        [6, 11, 2, 16, 10],
        [10, 16, 3, 8, 7],
        [5, 13, 4, 15, 9],
        [6, 15, 4, 17, 11],
        [8, 14, 5, 9, 7],
        [9, 15, 6, 10, 7],
    ],  # fmt: skip
    "truncated-octahedron": [
        [2, 0, 1, 3],
        [5, 1, 0, 4, 8, 10],
        [9, 4, 0, 2, 6, 11],
        [7, 3, 1, 5, 12, 14],
        [13, 6, 2, 3, 7, 15],
        [8, 4, 9, 16],
        [12, 5, 10, 17],
        [11, 6, 13, 18],
        [15, 7, 14, 19],
        [17, 10, 8, 16, 20, 21],
        [20, 16, 9, 11, 18, 22],
        [19, 14, 12, 17, 21, 23],
        [22, 18, 13, 15, 19, 23],
        [21, 20, 22, 23],
    ],  # fmt: skip
    "truncated-tetrahedron": [
        [3, 0, 2],
        [5, 1, 0, 3, 8, 9],
        [6, 2, 0, 1, 4, 7],
        [4, 1, 5],
        [8, 3, 2, 6, 10, 11],
        [10, 7, 4, 5, 9, 11],
        [10, 6, 7],
        [9, 8, 11],
    ],  # fmt: skip
    "cuboctahedron": [
        [1, 0, 4],
        [2, 0, 1, 3],
        [4, 0, 5, 8],
        [5, 0, 2],
        [3, 1, 6],
        [6, 1, 4, 9],
        [5, 2, 7, 10],
        [7, 2, 3],
        [7, 3, 6, 11],
        [9, 4, 8],
        [8, 5, 10],
        [11, 6, 9],
        [10, 7, 11],
        [9, 8, 10, 11],
    ],  # fmt: skip
}
"""Faces of the built-in solids, as :func:`convex_polyhedron` gives them for their points."""


def solid(name: str, points: ArrayLike) -> Scaffold:
    """Return the built-in solid ``name`` on ``points`` (every point a vertex, in order)."""
    return Scaffold.from_faces(np.asarray(points, dtype=np.float64), SOLID_FACES[name], name=name)


def _cyclic(vectors: Iterable[ArrayLike]) -> np.ndarray:
    out = []
    for v in vectors:
        for k in range(3):
            out.append(np.roll(v, k))
    return np.array(out, dtype=np.float64)


def _signs(v: Sequence[float]) -> list[tuple[float, ...]]:
    """All sign patterns of ``v`` (zeros kept once)."""
    out = set()
    for signs in itertools.product((1, -1), repeat=len(v)):
        out.add(tuple(s * x for s, x in zip(signs, v)))
    return sorted(out, reverse=True)


def tetrahedron() -> Scaffold:
    """Build the regular tetrahedron: 4 vertices, 6 edges, 4 triangles."""
    return solid("tetrahedron", [[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]])


def cube() -> Scaffold:
    """Build the cube [-1, 1]^3: 8 vertices, 12 edges, 6 squares."""
    return solid("cube", list(itertools.product((-1, 1), repeat=3)))


def octahedron() -> Scaffold:
    """Build the regular octahedron: 6 vertices, 12 edges, 8 triangles."""
    return solid("octahedron", np.vstack([np.eye(3), -np.eye(3)]))


def icosahedron() -> Scaffold:
    """Build the regular icosahedron: 12 vertices, 30 edges, 20 triangles."""
    return solid("icosahedron", _cyclic(_signs((0, 1, PHI))))


def dodecahedron() -> Scaffold:
    """Build the regular dodecahedron: 20 vertices, 30 edges, 12 pentagons."""
    points = np.vstack([list(itertools.product((-1, 1), repeat=3)), _cyclic(_signs((0, 1 / PHI, PHI)))])
    return solid("dodecahedron", points)


def truncated_octahedron() -> Scaffold:
    """Build the truncated octahedron: 24 vertices, 36 edges, 6 squares and 8 hexagons."""
    points = sorted({p for v in itertools.permutations((0, 1, 2)) for p in _signs(v)}, reverse=True)
    return solid("truncated-octahedron", points)


def truncated_tetrahedron() -> Scaffold:
    """Build the truncated tetrahedron: 12 vertices (permutations of (3, 1, 1), even minus signs), 18 edges, 4 triangles and 4 hexagons."""
    points = sorted(
        {p for v in set(itertools.permutations((3, 1, 1))) for p in _signs(v) if sum(x < 0 for x in p) % 2 == 0},
        reverse=True,
    )
    return solid("truncated-tetrahedron", points)


def cuboctahedron() -> Scaffold:
    """Build the cuboctahedron: 12 vertices (permutations of (1, 1, 0)), 24 edges, 8 triangles and 6 squares."""
    points = sorted({p for v in set(itertools.permutations((1, 1, 0))) for p in _signs(v)}, reverse=True)
    return solid("cuboctahedron", points)
