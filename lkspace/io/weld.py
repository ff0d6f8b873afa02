"""Welding: merging vertices that lie closer together than a tolerance.

Modelling tools often export a mesh with its own copy of every vertex per face; such a
mesh has no shared edges and traces as separate faces.  :func:`weld` merges vertices
within ``tol`` of each other (a KD-tree finds the close pairs in about ``n log n``;
chains of close pairs merge into one vertex).  The merged vertex keeps the position and
the place in vertex order of its lowest-numbered copy.  A face two of whose corners
merge collapses: that is an error naming the face.
"""

from __future__ import annotations

from typing import overload

import numpy as np
from numpy.typing import ArrayLike

from ..errors import ScaffoldError
from ..model.scaffold import Scaffold
from ..runtime.progress import task

DEFAULT_WELD = 1e-6
"""Default tolerance of ``--weld`` given without a value, as a fraction of the bounding-box diagonal."""


def default_tolerance(vertices: ArrayLike) -> float:
    """Return :data:`DEFAULT_WELD` times the bounding-box diagonal of ``vertices (n, 3)``."""
    points = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
    if len(points) == 0:
        return 0.0
    return DEFAULT_WELD * float(np.linalg.norm(points.max(axis=0) - points.min(axis=0)))


def weld_map(vertices: ArrayLike, tol: float) -> tuple[np.ndarray, np.ndarray]:
    """Return ``(keep, new_index)``: the vertices kept ``(m,) int64`` and each vertex's new index ``(n,) int64``."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    points = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
    n = len(points)
    with task("welding vertices", total=None):
        pairs = cKDTree(points).query_pairs(tol, output_type="ndarray") if n else np.zeros((0, 2), np.int64)
        graph = coo_matrix((np.ones(len(pairs), np.int8), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
        _, group = connected_components(graph, directed=False)
    first = np.full(group.max() + 1 if n else 0, n, np.int64)
    np.minimum.at(first, group, np.arange(n))  # lowest-numbered copy of each group
    keep = np.sort(first)
    rank = np.empty(len(first), np.int64)
    rank[np.argsort(first)] = np.arange(len(first))
    return keep, rank[group]


@overload
def weld(source: Scaffold, tol: float | None = None) -> Scaffold: ...
@overload
def weld(source: tuple[ArrayLike, list[list[int]]], tol: float | None = None) -> tuple[np.ndarray, list[list[int]]]: ...


def weld(
    source: Scaffold | tuple[ArrayLike, list[list[int]]], tol: float | None = None
) -> Scaffold | tuple[np.ndarray, list[list[int]]]:
    """Merge vertices closer than ``tol`` (default: :func:`default_tolerance`).

    Parameters
    ----------
    source : Scaffold or (vertices, faces)
        A finite scaffold without labels, nulls or radial orders, or vertex positions
        ``(n, 3)`` with faces as lists of vertex indices.
    tol : float, optional
        Distance below which two vertices are one; ``None``: ``1e-6`` times the
        bounding-box diagonal.

    Returns
    -------
    Scaffold or (vertices, faces)
        The same kind as ``source``, with vertices renumbered in order of their first copy.

    Examples
    --------
    >>> square = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
    >>> v, f = weld((square + [[1, 0, 0], [2, 0, 0], [1, 1, 0]], [[0, 1, 2, 3], [4, 5, 6]]))
    >>> len(v), f
    (5, [[0, 1, 2, 3], [1, 4, 2]])
    """
    if isinstance(source, Scaffold):
        if source.periodic or source.labels is not None or source.nulls is not None or source.radial_orders:
            raise ScaffoldError(
                f"{source.name}: only finite scaffolds without labels, nulls or radial orders can be welded"
            )
        vertices, faces = weld((source.vertices, source.faces()), tol)
        return Scaffold.from_faces(vertices, faces, name=source.name)
    points = np.asarray(source[0], dtype=np.float64).reshape(-1, 3)
    tol = default_tolerance(points) if tol is None else float(tol)
    if not np.isfinite(tol) or tol < 0:
        raise ScaffoldError(f"weld tolerance {tol!r} must be a finite number >= 0", usage=True)
    keep, new_index = weld_map(points, tol)
    faces = [new_index[np.asarray(face, dtype=np.int64)].tolist() for face in source[1]]
    for f, face in enumerate(faces):
        if len(set(face)) != len(face):
            raise ScaffoldError(
                f"face {f} collapses when welding with tolerance {tol:g}: two of its corners merge into "
                f"one vertex ({source[1][f]} -> {face}); give a smaller `weld=TOL`",
            )
    return points[keep], faces
