"""Scaffolds of the paper's classical examples, each carrying its design as default labels.

``figure-eight``
    A square split by its diagonal 0-2 into two triangles on the front, with one
    quadrilateral on the back (the same 4-cycle, reversed): a two-sided polygon whose
    sides are triangulated differently.  5 edges, all of degree 2, in the order
    ``0-1, 0-2, 0-3, 1-2, 2-3``.  Default labels ``1, 1, 1, 1, 0`` realize the
    figure-eight knot 4_1.
``whitehead``
    A 2-manifold with boundary: the square fanned into four triangles around its
    centre 4, nothing on the back.  8 edges in the order ``0-1, 0-3, 0-4, 1-2, 1-4, 2-3,
    2-4, 3-4``; the rim edges have degree 1, the spokes degree 2.  Default labels
    ``0, 0, -2, 0, -1, 0, -1, 2`` (spokes 0-4, 1-4, 2-4, 3-4: -2, -1, -1, 2) realize the Whitehead link L5a1.
"""

from __future__ import annotations

import numpy as np

from ..model.scaffold import Scaffold

_SQUARE = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]]


def figure_eight() -> Scaffold:
    """Two triangles on the front of a square, a quadrilateral on its back (knot 4_1).

    Examples
    --------
    >>> s = figure_eight()
    >>> s.n_faces, s.edge_degrees.tolist(), s.labels.tolist()
    (3, [2, 2, 2, 2, 2], [1, 1, 1, 1, 0])
    """
    base = Scaffold.from_faces(_SQUARE, [[0, 1, 2], [0, 2, 3], [3, 2, 1, 0]], name="figure-eight")
    return base.with_labels(np.array([1, 1, 1, 1, 0]))


def whitehead() -> Scaffold:
    """Four triangles fanned around the centre of a square, no back (Whitehead link L5a1).

    Examples
    --------
    >>> s = whitehead()
    >>> s.n_faces, s.edge_degrees.tolist()
    (4, [1, 1, 2, 1, 2, 1, 2, 2])
    """
    base = Scaffold.from_faces(
        _SQUARE + [[0.0, 0.0, 0.0]], [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]], name="whitehead"
    )
    return base.with_labels(np.array([0, 0, -2, 0, -1, 0, -1, 2]))
