"""The compiled rope-flow iteration and neighbour search against plain references."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lkspace.geometry import flow
from lkspace.geometry.cell import Cell
from lkspace.geometry.flow_steps import flow_candidates, flow_iteration, resample_ring

from .brute_flow import flow_iteration_numpy


def _every_close_pair(points: np.ndarray, radius: float) -> set[tuple[int, int]]:
    n = len(points)
    return {
        (i, j)
        for i in range(n)
        for j in range(i + 1, n)
        if sum((points[i][k] - points[j][k]) ** 2 for k in range(3)) <= radius * radius
    }


@settings(max_examples=150, deadline=None)
@given(
    sizes=st.lists(st.integers(3, 30), min_size=1, max_size=4),
    seed=st.integers(0, 2**32 - 1),
    scale=st.sampled_from([1e-6, 1.0, 1e6]),
    radius=st.sampled_from([0.0, 0.05, 0.2, 0.7, 3.0]),
    repeated=st.integers(0, 5),
)
def test_flow_candidates_are_the_close_pairs_of_every_pair(sizes, seed, scale, radius, repeated):
    curves = [np.random.default_rng(seed + k).random((size, 3)) * scale for k, size in enumerate(sizes)]
    curves[0][: min(repeated, sizes[0])] = curves[0][0]  # coincident points
    ring, points = flow.Ring.of(curves), np.vstack(curves)
    i, j, owner, share = flow_candidates(points, radius * scale, ring.owner, ring.index, ring.sizes)
    assert i.dtype == j.dtype == owner.dtype == np.int64 and bool(np.all(i < j))
    found = list(zip(i.tolist(), j.tolist(), strict=True))
    assert len(found) == len(set(found))
    assert set(found) == _every_close_pair(points, radius * scale)
    for a, b, c, s in zip(i.tolist(), j.tolist(), owner.tolist(), share.tolist(), strict=True):
        size, steps = sizes[c], abs(int(ring.index[a]) - int(ring.index[b]))
        same = c == ring.owner[b]
        assert c == ring.owner[a] and s == (min(steps, size - steps) / size if same else np.inf)


def _rings():
    t = np.linspace(0, 2 * np.pi, 90, endpoint=False)
    a = np.column_stack([np.cos(t), np.sin(t), 0 * t])
    b = np.column_stack([1 + np.cos(t), 0 * t, np.sin(t)])  # linked with a, squeezed by a thick rope
    kinked = np.column_stack([np.cos(t), np.sin(2 * t), 0.3 * np.sin(3 * t)])  # tight bends, folds near itself
    return [a, b], [kinked]


def _threads():
    x = np.linspace(0, 2, 40, endpoint=False)
    one = np.column_stack([x, 0.1 * np.sin(np.pi * x), 0 * x])
    two = np.column_stack([x, 0.25 + 0 * x, 0.05 * np.cos(np.pi * x)])
    return [one, two], Cell(np.diag([2.0, 0.6, 0.6]), np.array([[1, 0, 0], [1, 0, 0]]))


@pytest.mark.parametrize("grow", [0.0, 0.01])
@pytest.mark.parametrize("case", ["linked", "kinked", "threads"])
def test_flow_iteration_matches_the_numpy_iteration(case, grow):
    linked, kinked = _rings()
    curves, cell = {"linked": (linked, None), "kinked": (kinked, None), "threads": _threads()}[case]
    ring, points = flow.Ring.of(curves, cell), np.vstack(curves)
    h = 2 * np.pi / 90 if cell is None else 0.05
    for diameter in (0.4, 3.0, 8 * h) if cell is None else (0.1, 0.3):  # a thick rope squeezes the rings
        reach = max(diameter, 4 * h)
        near = flow._neighbour_list(points, ring, reach, flow.RESAMPLE_EVERY, h, grow)
        lengths = flow.closed_lengths(curves, None if cell is None else cell.offsets())
        want = flow_iteration_numpy(points, ring, lengths, near, reach, diameter, h, 0.25, grow)
        for run in (flow_iteration, flow_iteration.py_func):
            got = run(points, *ring.frame(), lengths, *near.arrays(), reach, diameter, h, 0.25, grow, flow.FOLD)
            assert np.allclose(got[0], want[0], rtol=0, atol=1e-12) and np.allclose(got[1], want[1], rtol=1e-12)
            assert got[2:] == pytest.approx(want[2:], rel=1e-12)
        assert not np.allclose(want[0], points)  # the step moved the points


@pytest.mark.parametrize("spacing", [0.01, 0.07, 2.0])
def test_resample_ring_is_resample_closed_per_curve(spacing):
    linked, kinked = _rings()
    threads, cell = _threads()
    for curves, offsets in ((linked + kinked, np.zeros((3, 3))), (threads, cell.offsets())):
        curves = [c.copy() for c in curves]
        curves[0][5] = curves[0][4]  # a segment of length zero
        ring = flow.Ring.of(curves)
        offsets = np.ascontiguousarray(offsets)
        points, sizes = resample_ring(np.vstack(curves), ring.starts, ring.sizes, offsets, spacing, flow.RESAMPLE_LEAST)
        want = [flow.resample_closed(c, spacing, offset=o) for c, o in zip(curves, offsets, strict=True)]
        assert sizes.tolist() == [len(w) for w in want]
        assert np.allclose(points, np.vstack(want), rtol=0, atol=1e-14)
