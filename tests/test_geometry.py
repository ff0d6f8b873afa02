"""Strand geometry: clean embeddings of every built-in, handedness, faithfulness to the trace."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import lkspace
from lkspace import GeometryParams, RealizeOptions, realize
from lkspace.errors import GeometryError
from lkspace.geometry.clearance import check_embedding
from lkspace.model.lattice import Lattice
from lkspace.model.scaffold import Scaffold


def builtin_names() -> list[str]:
    """Every named built-in (solids, hinged, periodic cells when present) and some family members."""
    from lkspace import scaffolds

    names = list(scaffolds.SOLIDS) + ["dihedron:3", "dihedron:4", "dihedron:8", "book:1", "book:2", "book:3", "book:6"]
    periodic = getattr(scaffolds, "periodic", None)
    for table in ("LATTICES", "VORONOI_EXAMPLES"):
        names += list(getattr(periodic, table, ()))
    return names


BUILTINS = builtin_names()


def gauss_linking(a: np.ndarray, b: np.ndarray) -> float:
    """Gauss linking integral of two closed polylines (midpoint rule): an independent oracle."""
    da, db = np.roll(a, -1, 0) - a, np.roll(b, -1, 0) - b
    r = (a + da / 2)[:, None] - (b + db / 2)[None]
    num = np.einsum("ijk,ijk->ij", r, np.cross(da[:, None], db[None]))
    return float(np.sum(num / np.linalg.norm(r, axis=2) ** 3) / (4 * np.pi))


@pytest.mark.parametrize("name", BUILTINS)
@pytest.mark.parametrize("twist", [1, -2, 3])
def test_builtins_realize_cleanly(name, twist):
    scaffold = lkspace.load(name)
    real = realize(scaffold, twist)
    tr = lkspace.trace(scaffold, twist)
    assert real.n_curves == tr.components
    assert np.array_equal(real.closed, tr.closed & ~np.any(tr.periods != 0, axis=1))
    assert real.min_distance > real.min_separation
    assert 0 < real.tube_radius < real.min_distance / 2 + 1e-12


def test_curves_stay_near_the_scaffold(cube):
    real = realize(cube, 2)
    reach = np.hypot(real.radius, real.normal_offset) * 1.01
    pts = np.vstack(real.curves)
    # every point lies within the strands' reach of the cube's surface (the box [-1, 1]^3)
    outside = np.linalg.norm(np.maximum(np.abs(pts) - 1, 0), axis=1)
    inside = 1 - np.abs(pts).max(axis=1)
    assert np.all(np.where(inside > 0, inside, outside) <= reach)


@pytest.mark.parametrize("twist", [1, 2, -1, -2])
def test_helix_handedness_on_the_spine(twist):
    """Right-handed about the spine axis 0 -> 1 (+z) for t > 0: the angle grows with z."""
    real = realize(lkspace.load("book:3"), twist)
    turn = []
    for c in real.curves:
        rr = np.hypot(c[:, 0], c[:, 1])
        near = (rr < 1.05 * np.hypot(real.radius, real.normal_offset)) & (c[:, 2] > 0.35) & (c[:, 2] < 0.65)
        ang = np.arctan2(c[:, 1], c[:, 0])
        idx = np.flatnonzero(near[:-1] & near[1:])
        dang = (ang[idx + 1] - ang[idx] + np.pi) % (2 * np.pi) - np.pi
        turn.append(np.sum(dang * np.sign(c[idx + 1, 2] - c[idx, 2])))
    assert np.sign(sum(turn)) == np.sign(twist)


@pytest.mark.parametrize(
    "labels, s", [([1, 1, 1, 1], 4), ([2, 2, -1, 1], 4), ([-1, -1, -1, -1], -4), ([2, 0, 0, 0], 2)]
)
def test_dihedron_linking_number_is_half_the_label_sum(labels, s):
    real = realize(lkspace.load("dihedron:4"), np.array(labels))
    assert real.n_curves == 2
    lk = gauss_linking(real.curves[0], real.curves[1])
    assert abs(abs(lk) - abs(s) / 2) < 0.05


def test_dihedron_parallel_strands_link_with_the_twist_sign():
    # both faces of dihedron:N run in opposite directions, so positive twists give
    # negative linking of the oriented components; a mirror flips it
    a = realize(lkspace.load("dihedron:4"), 1)
    b = realize(lkspace.load("dihedron:4"), -1)
    la = gauss_linking(*a.curves)
    lb = gauss_linking(*b.curves)
    assert round(la) == -round(lb) != 0


def test_collision_is_refused_with_the_place():
    with pytest.raises(GeometryError, match=r"come within .* near (edge|vertex)") as bad:
        realize(lkspace.load("book:6"), 1, params=GeometryParams(radius=0.6))
    assert "(try a smaller `radius` or `normal_offset`)" in str(bad.value)


def test_embedding_check_modes():
    """``"refuse"`` raises where ``"measure"`` reports the same distance; ``"later"`` does not measure."""
    params = GeometryParams(radius=0.6, smooth=False)
    with pytest.raises(GeometryError, match=r"come within ([0-9.e-]+) "):
        realize("book:6", 1, params=params)
    measured = realize("book:6", 1, params=params, options=RealizeOptions(embedding="measure"))
    assert measured.min_distance < measured.min_separation and measured.closest is not None
    later = realize("book:6", 1, params=params, options=RealizeOptions(embedding="later"))
    assert later.min_distance == np.inf and later.closest is None
    assert all(np.array_equal(a, b) for a, b in zip(later.curves, measured.curves, strict=True))
    with pytest.raises(GeometryError, match="^embedding: expected one of refuse, measure, later") as bad:
        realize("book:6", 1, options=RealizeOptions(embedding="never"))  # type: ignore[arg-type]
    assert bad.value.parameter == "embedding" and bad.value.exit_code == 2


def test_options_are_checked_and_name_the_parameter():
    for bad_value in (0, -5, 2.5):
        with pytest.raises(GeometryError, match="^max_points: must be an integer >= 1") as bad:
            realize("cube", 1, options=RealizeOptions(max_points=bad_value))  # type: ignore[arg-type]
        assert bad.value.parameter == "max_points"
    with pytest.raises(GeometryError, match="^translations: copies need a periodic scaffold; cube is finite"):
        realize("cube", 1, options=RealizeOptions(translations=[[0, 0, 0]]))
    with pytest.raises(GeometryError, match="^samples_per_turn: must be an integer in 1..1000, got 0") as bad:
        realize("cube", 1, params=GeometryParams(samples_per_turn=0))
    assert bad.value.parameter == "samples_per_turn" and bad.value.exit_code == 2


def test_a_given_trace_is_reused():
    tr = lkspace.trace("tetrahedron", 1)
    real = realize("tetrahedron", None, options=RealizeOptions(trace=tr))
    assert real.trace is tr and real.n_curves == 3


def test_check_embedding_finds_a_crossing():
    t = np.linspace(0, 2 * np.pi, 100, endpoint=False)
    a = np.column_stack([np.cos(t), np.sin(t), 0 * t])
    b = np.column_stack([np.cos(t), 0 * t, np.sin(t)])  # meets a at (+-1, 0, 0)
    d, where = check_embedding([a, b], [True, True], 0.01, 1.0)
    assert d < 0.01 and where is not None and where.curves == (0, 1)
    d2, _ = check_embedding([a, b + [0, 0.5, 0]], [True, True], 0.01, 1.0)
    assert abs(d2 - (1 - 0.75**0.5)) < 0.02  # nearest: (0.866, .5, 0) to (1, .5, 0)
    d3, where3 = check_embedding([a, b + [5, 0, 0]], [True, True], 0.01, 1.0)
    assert d3 == np.inf and where3 is None


def test_open_strands_end_at_their_cut(tetra):
    real = realize(tetra, 1, nulls=[0])
    assert (~real.closed).sum() == 1
    assert real.n_curves == lkspace.trace(tetra, 1, nulls=[0]).components


def square_torus() -> Scaffold:
    """One square face on the square lattice: a periodic scaffold with two edge classes."""
    return Scaffold.from_faces(
        [[0, 0, 0]],
        [[0, 0, 0, 0]],
        offsets=[[[0, 0], [1, 0], [1, 1], [0, 1]]],
        lattice=Lattice.square(),
        name="square-torus",
    )


@pytest.mark.parametrize("twists, n_open", [([2, 2], 0), ([1, 1], 2), ([0, 0], 0)])
def test_periodic_block_of_translates(twists, n_open):
    sc = square_torus()
    block = [[i, j] for i in range(3) for j in range(3)]
    real = realize(sc, twists, options=RealizeOptions(translations=block))
    assert real.n_curves == 9 * lkspace.trace(sc, twists).components
    assert (~real.closed).sum() == 9 * n_open
    assert real.min_distance > real.min_separation
    # a block copy is the base copy translated by its lattice vector
    k = int(np.flatnonzero(real.copy_of == 4)[0])
    assert np.allclose(real.curves[k], real.curves[real.strand_of[k]] + [1, 1, 0])


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(half=st.lists(st.integers(-2, 2), min_size=12, max_size=12))
def test_cube_chainmail_linking_numbers(cube, half):
    """Even labels keep every face a loop; adjacent loops link by -t/2 (Gauss integral oracle).

    Faces are oriented outward, so two adjacent face loops run along their shared edge in
    opposite directions, as the two faces of a dihedron do; a right-handed twist t = 2m
    gives them linking number -m (mirror labels: +m).
    """
    twists = 2 * np.array(half)
    real = realize(cube, twists)
    tr = real.trace
    face_of = [int(tr.strand_faces(k)[0]) for k in range(tr.components)]
    assert sorted(face_of) == list(range(6))
    expected = np.zeros((6, 6))
    for e in range(cube.n_edges):
        f, g = cube.corner_face[cube.radial.edge_sides[cube.radial.edge_starts[e] : cube.radial.edge_starts[e + 1]]]
        expected[f, g] = expected[g, f] = -twists[e] / 2
    for a in range(6):
        for b in range(a + 1, 6):
            lk = gauss_linking(real.curves[a], real.curves[b])
            assert abs(lk - expected[face_of[a], face_of[b]]) < 0.05


def test_normal_offset_that_reorders_the_strands_is_refused():
    book = lkspace.load("book:3")
    faces = book.faces()
    faces[1] = faces[1][::-1]  # one page turned over: its normal flips
    flipped = Scaffold.from_faces(book.vertices, faces, name="book:3-flipped")
    realize(flipped, 1)  # the default offset keeps the order
    with pytest.raises(GeometryError, match=r"edge 0-1: the normal offset .* reorders"):
        realize(flipped, 1, params=GeometryParams(radius=0.1, normal_offset=0.3))
