"""Nearest-point queries on a fixed point set: dense numpy for a few points, scipy's KD-tree for many.

The symmetry search of a small mesh (a cube: 8 sites) is over in milliseconds, while
importing :mod:`scipy.spatial` costs about 0.3 s in a fresh process; point sets of at most
:data:`FEW_POINTS` points are therefore answered by comparing every pair.  Both paths
follow :class:`scipy.spatial.cKDTree`'s conventions: a nearest neighbour counts when it is
strictly closer than the bound (else distance ``inf`` and index ``n``), a ball holds the
points at distance at most ``r``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

FEW_POINTS = 64
"""Point sets of at most this many points are queried densely (numpy), without scipy."""

ROWS = 4096
"""Query points compared with every point at once on the dense path (bounded memory)."""


class NearestPoints:
    """The points ``(n, 3)``, ``n >= 1``, of a set, queried for nearest neighbours and balls."""

    def __init__(self, points: np.ndarray) -> None:
        self.points = np.asarray(points, np.float64)
        self.tree: Any = None
        if len(self.points) > FEW_POINTS:
            from scipy.spatial import cKDTree

            self.tree = cKDTree(self.points)

    def _distances(self, queries: np.ndarray) -> np.ndarray:
        """``(m, n)`` distances from each query point to each point."""
        d = queries[:, None, :] - self.points[None, :, :]
        return np.sqrt(np.einsum("mnk,mnk->mn", d, d))

    def nearest(self, queries: np.ndarray, bound: float) -> tuple[np.ndarray, np.ndarray]:
        """``(dist (m,), idx (m,) int64)``: each query's nearest point closer than ``bound`` (else ``inf``, ``n``)."""
        queries = np.asarray(queries, np.float64).reshape(-1, 3)
        if self.tree is not None:
            dist, idx = self.tree.query(queries, distance_upper_bound=bound)
            return dist, idx.astype(np.int64)
        dist, idx = np.full(len(queries), np.inf), np.full(len(queries), len(self.points), np.int64)
        for start in range(0, len(queries), ROWS):
            block = self._distances(queries[start : start + ROWS])
            best = np.argmin(block, axis=1)
            found = block[np.arange(len(block)), best]
            near = found < bound
            dist[start : start + len(block)][near] = found[near]
            idx[start : start + len(block)][near] = best[near]
        return dist, idx

    def balls(self, queries: np.ndarray, r: float) -> list[np.ndarray]:
        """Return the indices (int64) of the points within ``r`` of each query point (ascending on the dense path)."""
        queries = np.asarray(queries, np.float64).reshape(-1, 3)
        if self.tree is not None:
            return [np.asarray(m, np.int64) for m in self.tree.query_ball_point(queries, r)]
        out: list[np.ndarray] = []
        for start in range(0, len(queries), ROWS):
            inside = self._distances(queries[start : start + ROWS]) <= r
            out.extend(np.flatnonzero(row) for row in inside)
        return out

    def pairs(self, r: float) -> np.ndarray:
        """``(k, 2) int64``: pairs ``i < j`` of points within ``r`` of each other."""
        if self.tree is not None:
            return np.asarray(self.tree.query_pairs(r, output_type="ndarray"), np.int64).reshape(-1, 2)
        close = np.triu(self._distances(self.points) <= r, k=1)
        return np.argwhere(close).astype(np.int64).reshape(-1, 2)


def components(n: int, pairs: np.ndarray) -> np.ndarray:
    """``(n,) int64`` connected-component ids of ``n`` nodes joined by ``pairs (k, 2)`` (ids ordered as scipy's)."""
    if not len(pairs):
        return np.arange(n, dtype=np.int64)
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    return connected_components(graph, directed=False)[1].astype(np.int64)
