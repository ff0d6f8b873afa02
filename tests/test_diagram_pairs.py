"""The diagram's candidate search (issue 33) against slow references that compare every pair."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from lkspace.knots.diagram import box_pairs, near_pairs, project

from .brute_pairs import box_pairs_every, near_pairs_every


def _pairs(found: tuple[np.ndarray, np.ndarray]) -> list[tuple[int, int]]:
    i, j = found
    assert i.dtype == j.dtype == np.int64
    return list(zip(i.tolist(), j.tolist(), strict=True))


@st.composite
def segment_sets(draw):
    """Short segments, some of zero length or repeated, and a few very long ones."""
    n = draw(st.integers(2, 60))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    grid = draw(st.sampled_from([0.0, 0.25, 1.0]))  # snapped coordinates make ties and touching circles
    p0 = rng.random((n, 3)) * draw(st.sampled_from([1.0, 1e-6, 1e6]))
    p1 = p0 + rng.normal(size=(n, 3)) * draw(st.sampled_from([0.01, 0.1]))
    if grid:
        p0, p1 = np.round(p0 / grid) * grid, np.round(p1 / grid) * grid
    n_long = draw(st.integers(0, min(3, n)))
    p1[:n_long] = p0[:n_long] + rng.normal(size=(n_long, 3)) * draw(st.sampled_from([1.0, 100.0]))
    n_zero = draw(st.integers(0, n // 4))
    p1[n - n_zero :] = p0[n - n_zero :]
    if draw(st.booleans()):
        p0[1], p1[1] = p0[0], p1[0]  # a repeated segment
    order = rng.permutation(n)
    return p0[order], p1[order]


@settings(max_examples=300, deadline=None)
@given(segments=segment_sets())
def test_near_pairs_are_those_of_every_pair(segments):
    p0, p1 = segments
    found = _pairs(near_pairs(p0, p1))
    assert found == sorted(near_pairs_every(p0, p1))


@settings(max_examples=200, deadline=None)
@given(
    boxes=st.lists(
        st.tuples(st.integers(-8, 8), st.integers(-8, 8), st.integers(0, 6), st.integers(0, 6)), min_size=1, max_size=40
    ),
    long=st.lists(st.tuples(st.integers(-8, 8), st.integers(-8, 8), st.integers(20, 400)), max_size=3),
)
def test_box_pairs_are_those_of_every_pair(boxes, long):
    low = [[x, y] for x, y, _, _ in boxes] + [[x, y] for x, y, _ in long]
    high = [[x + w, y + h] for x, y, w, h in boxes] + [[x + s, y + 1] for x, y, s in long]
    found = _pairs(box_pairs(np.array(low, float) / 4, np.array(high, float) / 4))
    assert found == sorted(box_pairs_every(low, high))


def test_one_long_segment_keeps_the_pairs_and_the_crossings():
    t = np.linspace(0, 2 * np.pi, 3000, endpoint=False)
    r = 2 + np.cos(31 * t)
    knot = np.column_stack([r * np.cos(2 * t), r * np.sin(2 * t), np.sin(31 * t)])  # the (2, 31) torus knot
    p0, p1 = knot[20:], np.roll(knot[20:], -1, axis=0)  # the closing segment is ten times the others
    assert _pairs(near_pairs(p0, p1)) == sorted(near_pairs_every(p0, p1))
    diagram = project([knot[20:]], rotation=np.eye(3))  # the standard diagram, q (p - 1) crossings
    assert diagram.n_crossings == 31 and abs(int(diagram.signs.sum())) == diagram.n_crossings
