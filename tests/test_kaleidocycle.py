"""The kaleidocycle scaffolds: rings of tetrahedra that meet only at their hinges."""

from __future__ import annotations

import numpy as np
import pytest

import lkspace
from lkspace.errors import ScaffoldError
from lkspace.scaffolds.kaleidocycle import kaleidocycle


@pytest.mark.parametrize("n", [4, 6, 8])
def test_ring_of_tetrahedra(n):
    s = kaleidocycle(n)
    assert (s.n_vertices, s.n_edges, s.n_faces) == (2 * n, 5 * n, 4 * n)
    assert sorted(np.bincount(s.edge_degrees)[[2, 4]].tolist()) == [n, 4 * n]  # n hinges of degree 4
    # consecutive hinges (vertex pairs 2i, 2i+1) are perpendicular and of length 1
    hinges = s.vertices[1::2] - s.vertices[0::2]
    assert np.allclose(np.linalg.norm(hinges, axis=1), 1)
    assert np.allclose(np.einsum("ij,ij->i", hinges, np.roll(hinges, -1, axis=0)), 0)
    # untwisted, every face is its own loop; a twist of 1 merges them
    assert lkspace.trace(s, 0).components == 4 * n
    assert lkspace.trace(s, 1).components < 4 * n


def test_a_single_knot_realizes_cleanly():
    found = lkspace.solve("kaleidocycle:6", 1)
    labels = found.solutions[0].labels
    real = lkspace.realize("kaleidocycle:6", labels)
    assert real.n_curves == 1 and real.min_distance > real.min_separation


@pytest.mark.parametrize("name", ["kaleidocycle:5", "kaleidocycle:2"])
def test_odd_or_tiny_rings_are_refused(name):
    with pytest.raises(ScaffoldError, match="even number of tetrahedra"):
        lkspace.load(name)
