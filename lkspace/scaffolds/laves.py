"""The Laves graph (the srs net) as a periodic scaffold: its 10-rings are the faces.

The Laves graph is the chiral, 3-regular net of space group I4_132: in the conventional
cube (a = 1) its 8 vertices sit at ``(1, 1, 1) / 8``, ``(3, 7, 5) / 8``, ``(7, 5, 3) / 8``,
``(5, 3, 7) / 8`` and these shifted by ``(1, 1, 1) / 2``, each joined to its 3 nearest
neighbours at distance ``sqrt(2) / 4``; its lattice is body-centred cubic (4 vertices and
6 edges per primitive cell).  As in the paper, the faces are the shortest cycles, the
**10-rings**: every vertex lies on 15 of them and every edge on 10, so the scaffold has
6 skew decagons per cell and every edge has degree 10.  The rings are found by a
depth-first search from each vertex, pruned by distance; translates and repeats are
merged by :func:`~lkspace.scaffolds.periodic.quotient_scaffold`.
"""

from __future__ import annotations

import itertools

import numpy as np

from ..model.lattice import Lattice
from ..model.scaffold import Scaffold
from .periodic import quotient_scaffold

RING = 10
"""Length of the cycles taken as faces."""

SITES = np.array([[1, 1, 1], [3, 7, 5], [7, 5, 3], [5, 3, 7]]) / 8.0
"""Half of the vertices in the conventional cube; the others are these plus (1, 1, 1) / 2."""


def rings(points: np.ndarray, neighbours: list[list[int]], start: int, length: int, step: float) -> list[list[int]]:
    """Every cycle of ``length`` vertices through ``start`` (both directions), as vertex lists."""
    found: list[list[int]] = []
    path = [start]
    reach = np.linalg.norm(points - points[start], axis=1)  # a ring must be able to close

    def extend() -> None:
        v = path[-1]
        if len(path) == length:
            if start in neighbours[v]:
                found.append(list(path))
            return
        for w in neighbours[v]:
            if w in path or reach[w] > step * (length - len(path)) + 1e-9:
                continue
            path.append(w)
            extend()
            path.pop()

    extend()
    return found


def laves() -> Scaffold:
    """Build the Laves graph scaffold (see the module docstring).

    Examples
    --------
    >>> s = laves()
    >>> s.n_vertices, s.n_edges, s.n_faces, sorted(set(s.edge_degrees.tolist()))
    (4, 6, 6, [10])
    """
    from scipy.spatial import cKDTree  # here: loading the built-in names must not import scipy

    conventional = np.vstack([SITES, (SITES + 0.5) % 1.0])
    shifts = np.array(list(itertools.product(range(-2, 3), repeat=3)), np.float64)
    cloud = (conventional[None] + shifts[:, None]).reshape(-1, 3)
    step = np.sqrt(2) / 4
    near = cKDTree(cloud).query_ball_point(cloud, step * 1.01)
    neighbours = [[j for j in sorted(n) if j != i] for i, n in enumerate(near)]
    zero = int(np.flatnonzero(~shifts.any(axis=1))[0]) * len(conventional)
    polygons = [
        cloud[ring]
        for start in range(zero, zero + len(conventional))
        for ring in rings(cloud, neighbours, start, RING, step)
    ]
    return quotient_scaffold(Lattice.body_centred_cubic(1.0), polygons, "laves")
