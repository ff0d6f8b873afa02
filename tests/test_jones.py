"""The compiled Jones polynomial against regina: the knot and link tables, mirrors, random diagrams.

regina's ``Link.jones()`` is the reference (a Laurent polynomial in ``x = sqrt(t)``).  Random
diagrams reach regina through ``Link.fromData`` (signs and the crossings each component
passes, read from the projection here), so no PD reading of lkspace's is trusted.
"""

from __future__ import annotations

import ast

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

regina = pytest.importorskip("regina")
dki = pytest.importorskip("database_knotinfo")

from lkspace.knots.diagram import project  # noqa: E402
from lkspace.knots.jones import MAX_FRONTIER, jones, jones_buffer_size, jones_into, jones_kernel  # noqa: E402


def regina_jones(link) -> tuple[int, tuple[int, ...]]:
    """regina's Jones polynomial as ``(lowest exponent of x, coefficients)``; ``(0, ())`` when zero."""
    poly = link.jones()
    if poly.isZero():
        return 0, ()
    return poly.minExp(), tuple(int(str(poly[e])) for e in range(poly.minExp(), poly.maxExp() + 1))


def regina_link(pd, signs, n_components: int):
    """A regina link from a PD code and its signs, through ``fromData`` (each component's passages)."""
    head = {}  # edge -> (crossing, over?, the edge leaving there)
    for c, (a, b, k, d) in enumerate(np.asarray(pd, np.int64).reshape(-1, 4).tolist()):
        head[a] = (c, False, k)
        head[d if signs[c] > 0 else b] = (c, True, b if signs[c] > 0 else d)
    seen: set[int] = set()
    components = []
    for first in sorted(head):
        passages, edge = [], first
        while edge not in seen:
            seen.add(edge)
            c, over, edge = head[edge]
            passages.append(c + 1 if over else -(c + 1))
        if passages:
            components.append(passages)
    components += [[] for _ in range(n_components - len(components))]
    return regina.Link.fromData([int(s) for s in signs], components)


def mirror(pd: list[list[int]]) -> list[list[int]]:
    """The PD code of the mirror image of a knot: every over strand becomes the under one.

    The over strand of ``[a, b, c, d]`` runs ``d -> b`` when ``b`` follows ``d`` along the knot.
    """
    n_edges = 2 * len(pd)
    return [[d, a, b, c] if b == d % n_edges + 1 else [b, c, d, a] for a, b, c, d in pd]


def table_rows(proper_links: bool):
    for row in dki.link_list(proper_links=proper_links):
        text = row.get("pd_notation_vector" if proper_links else "pd_notation")
        if row.get("name") in (None, "Name") or not text:
            continue
        yield row["name"], ast.literal_eval(text.replace("{", "[").replace("}", "]"))


KNOTS = [(name, pd) for name, pd in table_rows(False) if name != "0_1" and len(pd) <= 10]
LINKS = list(table_rows(True))[::7]


def test_every_knot_to_ten_crossings_and_its_mirror_matches_regina():
    assert len(KNOTS) == 249
    for name, pd in KNOTS:
        assert jones(pd) == regina_jones(regina.Link.fromPD(pd)), name
        mirrored = regina.Link.fromPD(pd)
        mirrored.changeAll()
        assert jones(mirror(pd)) == regina_jones(mirrored), f"mirror of {name}"


def test_linkinfo_sample_and_mirrors_match_regina():
    assert len(LINKS) > 200
    for name, pd in LINKS:
        reference = regina.Link.fromPD(pd)
        assert jones(pd) == regina_jones(reference), name
        reference.changeAll()
        lowest, coefficients = jones(pd)
        mirror_lowest = -(lowest + len(coefficients) - 1)  # V(mirror)(x) = V(1/x)
        assert (mirror_lowest, coefficients[::-1]) == regina_jones(reference), f"mirror of {name}"


def test_hand_checked_values():
    # skein t^-1 V(L+) - t V(L-) = (t^1/2 - t^-1/2) V(L0): Hopf+ = -t^1/2 - t^5/2, trefoil+ = t + t^3 - t^4
    assert jones([[1, 1, 2, 2]]) == (0, (1,))  # unknot with a positive kink
    assert jones([[2, 1, 3, 2], [4, 4, 1, 3]]) == (0, (1,))  # two kinks
    assert jones([[4, 1, 3, 2], [2, 3, 1, 4]], signs=[-1, -1]) == (-5, (-1, 0, 0, 0, -1))  # Hopf-: -x^-5 - x^-1
    assert jones([[1, 3, 2, 4], [3, 1, 4, 2]]) == (1, (-1, 0, 0, 0, -1))  # Hopf+: -x - x^5
    assert jones([[1, 5, 2, 4], [3, 1, 4, 6], [5, 3, 6, 2]]) == (2, (1, 0, 0, 0, 1, 0, -1))  # x^2 + x^6 - x^8
    assert jones(mirror([[1, 5, 2, 4], [3, 1, 4, 6], [5, 3, 6, 2]])) == (-8, (-1, 0, 1, 0, 0, 0, 1))
    figure_eight = [[4, 2, 5, 1], [8, 6, 1, 5], [6, 3, 7, 4], [2, 7, 3, 8]]
    assert jones(figure_eight) == (-4, (1, 0, -1, 0, 1, 0, -1, 0, 1))  # t^-2 - t^-1 + 1 - t + t^2
    assert jones([], n_components=1) == (0, (1,))
    assert jones([], n_components=3) == (-2, (1, 0, 2, 0, 1))  # (-x - 1/x)^2
    assert jones([[1, 1, 2, 2]], n_components=2) == (-1, (-1, 0, -1))
    assert jones([]) == (0, ())  # the empty link, as regina


def test_hand_checked_diagrams_agree_with_regina():
    for pd in ([[1, 1, 2, 2]], [[2, 1, 3, 2], [4, 4, 1, 3]], [[4, 2, 5, 1], [8, 6, 1, 5], [6, 3, 7, 4], [2, 7, 3, 8]]):
        assert jones(pd) == regina_jones(regina.Link.fromPD(pd))
    for pd in ([[4, 1, 3, 2], [2, 3, 1, 4]], [[1, 3, 2, 4], [3, 1, 4, 2]]):  # Hopf- and Hopf+
        signs = [-1, -1] if pd[0][0] == 4 else [1, 1]
        assert jones(pd) == jones(pd, signs=signs) == regina_jones(regina_link(pd, signs, 2))


def polygons(seed: int, n_components: int) -> list[np.ndarray]:
    """Closed polygons of 6..40 vertices wandering around circles with random centres (many R1/R2 moves)."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n_components):
        n = int(rng.integers(6, 41))
        angles = np.sort(rng.uniform(0, 2 * np.pi, n))
        radii = 1 + 0.6 * rng.standard_normal(n)
        points = np.column_stack([radii * np.cos(angles), radii * np.sin(angles), 0.8 * rng.standard_normal(n)])
        out.append(points + rng.uniform(-1.5, 1.5, 3))
    return out


@settings(max_examples=40, derandomize=True)
@given(seed=st.integers(0, 2**32 - 1), n_components=st.integers(1, 4))
def test_random_diagrams_match_regina(seed, n_components):
    d = project(polygons(seed, n_components), seed=seed)
    n_free = len(d.free_components)
    out = np.zeros(jones_buffer_size(d.n_crossings, n_free), np.int64)
    lowest, length = jones_kernel(np.asarray(d.pd, np.int64).reshape(-1, 4), d.signs, n_free, out)
    if length == -1:  # too wide: the caller's slow path
        return
    expected = regina_jones(regina_link(d.pd, d.signs, d.n_components))
    assert (lowest, tuple(out[:length].tolist())) == expected
    assert jones(d.pd, n_components=d.n_components) == expected  # signs read from the code
    mirrored = project([c * [1, 1, -1] for c in polygons(seed, n_components)], seed=seed + 1)  # another diagram
    out = np.zeros(jones_buffer_size(mirrored.n_crossings, len(mirrored.free_components)), np.int64)
    code = np.asarray(mirrored.pd, np.int64).reshape(-1, 4)
    lowest, length = jones_kernel(code, mirrored.signs, len(mirrored.free_components), out)
    if length != -1:  # V(mirror)(x) = V(1/x), whatever the diagram
        assert (-(lowest + length - 1), tuple(out[:length].tolist())[::-1]) == expected


def test_two_edge_and_free_components_match_regina():
    t = np.linspace(0, 2 * np.pi, 60, endpoint=False)
    circle = np.column_stack([np.cos(t), np.sin(t), 0 * t])
    hopf = [circle, np.column_stack([1 + np.cos(t), 0 * t, np.sin(t)])]  # two components of 2 edges
    trefoil = np.column_stack([np.sin(t) + 2 * np.sin(2 * t), np.cos(t) - 2 * np.cos(2 * t), -np.sin(3 * t)])
    for curves in (
        [*hopf, circle + [10, 0, 0]],
        [trefoil + [0, -10, 0], circle + [10, 0, 0], circle + [20, 0, 0], *hopf[::-1]],
    ):
        for seed in range(3):
            d = project(curves, seed=seed)
            assert d.free_components and 2 in np.bincount(d.crossing_components.ravel()).tolist()  # a 2-edge one
            expected = regina_jones(regina_link(d.pd, d.signs, d.n_components))
            assert jones(d.pd, d.signs, d.n_components) == jones(d.pd, n_components=d.n_components) == expected


def test_a_component_over_everything_leaves_its_signs_free_and_the_answer_fixed():
    t = np.linspace(0, 2 * np.pi, 60, endpoint=False)
    trefoil = np.column_stack([np.sin(t) + 2 * np.sin(2 * t), np.cos(t) - 2 * np.cos(2 * t), -np.sin(3 * t)])
    for centre, radius, n_crossings in (((0, 0, 5), 2.0, 9), ((0, -1, 5), 0.3, 5)):  # the small ring has 2 edges
        ring = np.column_stack([radius * np.cos(t), radius * np.sin(t), 0 * t]) + centre
        d = project([trefoil, ring], rotation=np.eye(3))
        assert d.n_crossings == n_crossings and (d.crossing_components[:, 1] == 0).all()  # the ring is never under
        expected = regina_jones(regina_link(d.pd, d.signs, 2))
        assert expected == (-9, (1, 0, 0, 0, -1, 0, -1, 0, -1))  # a trefoil and a split circle
        assert jones(d.pd, d.signs) == jones(d.pd) == expected


def test_plain_python_helper_agrees_with_the_compiled_one():
    cases = [([[1, 5, 2, 4], [3, 1, 4, 6], [5, 3, 6, 2]], [1, 1, 1], 0), ([[4, 1, 3, 2], [2, 3, 1, 4]], [-1, -1], 2)]
    cases += [([[4, 2, 5, 1], [8, 6, 1, 5], [6, 3, 7, 4], [2, 7, 3, 8]], [-1, -1, 1, 1], 1), ([], [], 2)]
    for pd, signs, n_free in cases:
        code, crossing_signs = np.asarray(pd, np.int64).reshape(-1, 4), np.asarray(signs, np.int64)
        plain = np.zeros(jones_buffer_size(len(code), n_free), np.int64)
        compiled = plain.copy()
        assert jones_into(code, crossing_signs, n_free, plain) == jones_kernel(code, crossing_signs, n_free, compiled)
        assert plain.tolist() == compiled.tolist()


def wide_diagram():
    """A knotted tangle of 60 random points in a cube: hundreds of crossings, no narrow order."""
    return project([np.random.default_rng(7).uniform(-1, 1, (60, 3))], seed=0)


def test_a_wide_diagram_returns_minus_one_and_leaves_out_alone():
    d = wide_diagram()
    code = np.asarray(d.pd, np.int64)
    assert d.n_crossings > 100
    out = np.full(jones_buffer_size(d.n_crossings), 99, np.int64)
    assert jones_kernel(code, d.signs, 0, out)[1] == -1
    assert jones_into(code, d.signs, 0, out)[1] == -1
    assert (out == 99).all()
    with pytest.raises(ValueError, match=f"too wide for the state sum \\(frontier over {MAX_FRONTIER} edges\\)"):
        jones(d.pd, d.signs)


def test_malformed_input_is_refused():
    trefoil = np.array([[1, 5, 2, 4], [3, 1, 4, 6], [5, 3, 6, 2]], np.int64)
    signs = np.ones(3, np.int64)
    out = np.zeros(jones_buffer_size(3), np.int64)
    assert jones_kernel(np.array([[1, 5, 2, 4], [3, 1, 4, 6], [5, 3, 6, 7]]), signs, 0, out)[1] == -2
    assert jones_kernel(trefoil, signs[:2], 0, out)[1] == -2
    assert jones_kernel(trefoil, signs, 0, out[:3])[1] == -2  # out too short for the 7 coefficients
    with pytest.raises(ValueError, match="every label 1..6 must appear exactly twice"):
        jones([[1, 5, 2, 4], [3, 1, 4, 6], [5, 3, 6, 5]])
    with pytest.raises(ValueError, match="signs: expected 3 values"):
        jones(trefoil, signs=[1, 0, 1])
    with pytest.raises(ValueError, match="the PD code draws 2 components"):
        jones([[4, 1, 3, 2], [2, 3, 1, 4]], signs=[1, 1], n_components=1)
