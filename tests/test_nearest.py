"""The dense nearest-point path against scipy's KD-tree (the reference), and the symmetry search without scipy."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial import cKDTree

from lkspace.symmetry.nearest import FEW_POINTS, NearestPoints

grids = st.integers(1, FEW_POINTS).flatmap(
    lambda n: st.lists(st.tuples(*[st.integers(-3, 3)] * 3), min_size=n, max_size=n)
)


@settings(max_examples=60, deadline=None)
@given(grids, st.lists(st.tuples(*[st.integers(-4, 4)] * 3), min_size=1, max_size=20), st.sampled_from([0.5, 1.0, 1.5]))
def test_dense_queries_agree_with_the_kd_tree(points, queries, r):
    # integer grids: many exact ties and distances equal to the bound, where the conventions differ if any
    x = np.array(points, float) * 0.5
    q = np.array(queries, float) * 0.5
    near, tree = NearestPoints(x), cKDTree(x)
    assert near.tree is None
    dist, idx = near.nearest(q, r)
    want_dist, want_idx = tree.query(q, distance_upper_bound=r)
    np.testing.assert_array_equal(np.isfinite(dist), np.isfinite(want_dist))
    np.testing.assert_allclose(dist[np.isfinite(dist)], want_dist[np.isfinite(want_dist)])
    assert np.all(idx[~np.isfinite(dist)] == len(x))
    assert [sorted(m.tolist()) for m in near.balls(q, r)] == [sorted(m) for m in tree.query_ball_point(q, r)]
    assert {tuple(p) for p in near.pairs(r).tolist()} == set(tree.query_pairs(r))


def test_many_points_use_the_kd_tree():
    x = np.random.default_rng(0).normal(size=(FEW_POINTS + 1, 3))
    near = NearestPoints(x)
    assert near.tree is not None
    assert near.nearest(x[:3], 1e-9)[1].tolist() == [0, 1, 2]


def test_the_symmetry_of_a_small_mesh_is_found_without_scipy():
    code = (
        "import sys, lkspace; from lkspace.symmetry.group import symmetry_group;"
        "g = symmetry_group(lkspace.load('cube')); print(g.order, g.n_rotations, 'scipy.spatial' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["48", "24", "False"]
