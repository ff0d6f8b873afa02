"""Built-in scaffolds: counts, geometry sanity, unambiguous radial orders."""

from __future__ import annotations

import numpy as np
import pytest

import lkspace
from lkspace import trace
from lkspace.scaffolds import builtin_names

SOLIDS = {  # name: (V, E, F, face sizes)
    "tetrahedron": (4, 6, 4, {3}),
    "cube": (8, 12, 6, {4}),
    "octahedron": (6, 12, 8, {3}),
    "dodecahedron": (20, 30, 12, {5}),
    "icosahedron": (12, 30, 20, {3}),
    "truncated-octahedron": (24, 36, 14, {4, 6}),
    "truncated-tetrahedron": (12, 18, 8, {3, 6}),
    "cuboctahedron": (12, 24, 14, {3, 4}),
    "prism:3": (6, 9, 5, {3, 4}),
    "prism:4": (8, 12, 6, {4}),
    "prism:7": (14, 21, 9, {4, 7}),
    "antiprism:3": (6, 12, 8, {3}),
    "antiprism:5": (10, 20, 12, {3, 5}),
}


@pytest.mark.parametrize("name", list(SOLIDS))
def test_solids(name):
    s = lkspace.load(name)
    v, e, f, sizes = SOLIDS[name]
    assert (s.n_vertices, s.n_edges, s.n_faces) == (v, e, f)
    assert set(s.face_sizes.tolist()) == sizes
    assert set(s.edge_degrees.tolist()) == {2}
    # faces are planar, regular-edged and wound counter-clockwise seen from outside
    lengths = np.linalg.norm(s.corner_positions[s.corner_next] - s.corner_positions, axis=1)
    assert np.allclose(lengths, lengths[0])
    for face in s.faces():
        p = s.vertices[face]
        normal = np.cross(p[1] - p[0], p[2] - p[1])
        assert normal @ p.mean(axis=0) > 0


EXAMPLES = {"knot:NAME": "knot:8_17", "link:NAME": "link:L6a4"}


@pytest.mark.parametrize(
    "name", [EXAMPLES.get(n) or n.replace(":N", ":5").replace(":K", ":4") for n in builtin_names()]
)
def test_every_builtin_has_an_unambiguous_radial_order_and_traces(name):
    s = lkspace.load(name)
    s.radial
    for t in (-1, 0, 1, 2):
        r = trace(s, t)
        assert r.strand_lengths.sum() == s.n_corners


@pytest.mark.parametrize(
    "name, v, e, f, degrees",
    [
        ("cube-net", 14, 19, 6, {1: 14, 2: 5}),
        ("cube-lid", 10, 15, 6, {1: 6, 2: 9}),
        ("cubes:piano", 14, 23, 12, {2: 22, 4: 1}),
        ("cubes:vertex", 15, 24, 12, {2: 24}),
    ],
)
def test_hinged(name, v, e, f, degrees):
    s = lkspace.load(name)
    assert (s.n_vertices, s.n_edges, s.n_faces) == (v, e, f)
    hist = np.bincount(s.edge_degrees)
    assert {k: int(n) for k, n in enumerate(hist) if n} == degrees


def test_vertex_hinged_cubes_always_fall_apart():
    s = lkspace.load("cubes:vertex")
    rng = np.random.default_rng(3)
    for _ in range(20):
        assert not trace(s, rng.integers(-3, 4, s.n_edges)).holds_together


def test_piano_hinge_can_hold_together():
    assert trace(lkspace.load("cubes:piano"), 1).holds_together


@pytest.mark.parametrize(
    "name",
    ["tetrahedron", "cube", "octahedron", "dodecahedron", "icosahedron", "truncated-octahedron"]
    + ["truncated-tetrahedron", "cuboctahedron"],
)
def test_built_in_solids_are_their_convex_hulls(name):
    from lkspace.scaffolds.polyhedra import convex_polyhedron

    solid = lkspace.load(name)
    hull = convex_polyhedron(solid.vertices, name)
    assert solid.faces() == hull.faces() and np.array_equal(solid.vertices, hull.vertices)


@pytest.mark.parametrize("name", ["prism:4", "prism:9", "antiprism:4", "antiprism:6"])
def test_prisms_have_the_faces_of_their_convex_hulls(name):
    from lkspace.scaffolds.polyhedra import convex_polyhedron

    s = lkspace.load(name)
    hull = convex_polyhedron(s.vertices, name)
    assert sorted(sorted(f) for f in s.faces()) == sorted(sorted(f) for f in hull.faces())


@pytest.mark.parametrize("name", ["prism:2", "antiprism:2", "prism:x"])
def test_prisms_need_three_sides(name):
    from lkspace.errors import ScaffoldError

    with pytest.raises(ScaffoldError, match=name.split(":")[0]):
        lkspace.load(name)


@pytest.mark.parametrize("name", ["book:1001", "dihedron:999999999999", "book:999999999999", "prism:1001"])
def test_family_parameters_are_bounded(name):
    from lkspace.errors import UsageError
    from lkspace.scaffolds import MAX_FAMILY_PARAMETER

    with pytest.raises(UsageError, match=f"limited to . <= {MAX_FAMILY_PARAMETER}"):
        lkspace.load(name)
    assert lkspace.load(f"book:{MAX_FAMILY_PARAMETER}").edge_degrees.max() == MAX_FAMILY_PARAMETER
