"""Scaffolds of the paper's figures: kaleidocycles (rings of tetrahedra meeting only at their
hinges) and the Laves graph with its 10-rings as faces."""

from __future__ import annotations

import numpy as np
import pytest

import lkspace
from lkspace.errors import ScaffoldError
from lkspace.scaffolds.kaleidocycle import kaleidocycle
from lkspace.scaffolds.laves import laves


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


def test_laves_graph_rings():
    s = laves()
    assert (s.n_vertices, s.n_edges, s.n_faces) == (4, 6, 6)
    assert set(s.edge_degrees.tolist()) == {10}  # every edge on 10 rings (the paper)
    assert s.n_corners == 4 * 15  # every vertex on 15 rings
    p = s.corner_positions
    sides = np.linalg.norm(p[s.corner_next] - p, axis=1)
    np.testing.assert_allclose(sides, np.sqrt(2) / 4)  # the net's edges, nearest neighbours
    assert all(len(f) == 10 for f in s.faces())  # skew decagons
    assert [lkspace.trace(s, t).components for t in range(5)] == [6, 4, 15, 4, 6]
    real = lkspace.realize(s, 1)
    assert real.n_curves == 4 and real.min_distance > real.min_separation
