"""Strand tracing: hand-checked answers, the brute-force reference, properties."""

from __future__ import annotations

import json
import math
from collections import Counter

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import lkspace
from lkspace import Scaffold, trace
from lkspace.errors import LabelError, RadialOrderError

from .reference import reference_trace
from .strategies import traceable_scaffolds


@pytest.mark.parametrize("t, expected", [(0, 4), (1, 3), (2, 4), (-1, 3), (3, 3)])
def test_tetrahedron_uniform(tetra, t, expected):
    assert trace(tetra, t).components == expected


def test_tetrahedron_all_ones_is_three_linked_triangles(tetra):
    result = trace(tetra, 1)
    assert result.components == 3
    assert sorted(result.strand_lengths.tolist()) == [4, 4, 4]
    assert result.holds_together


@pytest.mark.parametrize("k", range(1, 9))
@pytest.mark.parametrize("t", range(-9, 10))
def test_book_gcd(k, t):
    assert trace(lkspace.load(f"book:{k}"), t).components == math.gcd(k, t)  # gcd(k, 0) = k: untwisted, k circles


@pytest.mark.parametrize("n", range(3, 12))
def test_dihedron_twist_one(n):
    assert trace(lkspace.load(f"dihedron:{n}"), 1).components == (1 if n % 2 else 2)


@pytest.mark.parametrize(
    "name",
    [
        "tetrahedron",
        "cube",
        "octahedron",
        "dodecahedron",
        "icosahedron",
        "truncated-octahedron",
        "dihedron:5",
        "book:4",
    ],
)
def test_uniform_zero_is_one_strand_per_face(name):
    s = lkspace.load(name)
    result = trace(s, 0)
    assert result.components == s.n_faces
    for k in range(result.components):
        faces = result.strand_faces(k)
        assert len(set(faces.tolist())) == 1


@pytest.mark.parametrize(
    "name, petrie", [("tetrahedron", 3), ("cube", 4), ("octahedron", 4), ("dodecahedron", 6), ("icosahedron", 6)]
)
def test_uniform_one_gives_petrie_polygons(name, petrie):
    # on a closed 2-manifold twist 1 everywhere swaps the two sides of every edge:
    # the strands are the Petrie polygons of the polyhedron
    assert trace(lkspace.load(name), 1).components == petrie


def test_zero_twist_falls_apart_and_twist_two_holds(cube):
    assert not trace(cube, 0).holds_together
    assert trace(cube, 0).n_pieces == 6
    assert trace(cube, 2).holds_together  # six interlocked rings: chainmail


def test_faces_meeting_at_a_vertex_fall_apart():
    s = Scaffold.from_faces([[0, 0, 0], [1, 0, 0], [0, 1, 0], [-1, 0, 0.5], [0, -1, 0.2]], [[0, 1, 2], [0, 3, 4]])
    result = trace(s, 3)
    assert result.components == 2 and not result.holds_together


def _cyclic_equal(a, b):
    return len(a) == len(b) and any(a[i:] + a[:i] == b for i in range(len(a)))


@pytest.mark.parametrize("t", [-2, -1, 1, 2, 4])
def test_chirality_on_book3(t):
    # edge 0-1 runs 0 -> 1 = +z; pages sit at angles 0, 120, 240 degrees, so the slot
    # order is the page order counter-clockwise about +z
    s = lkspace.load("book:3")
    spine = int(np.flatnonzero(s.edge_degrees == 3)[0])
    sides = s.radial.edge_sides[s.radial.edge_starts[spine] : s.radial.edge_starts[spine + 1]].tolist()
    assert _cyclic_equal(sides, [int(s.face_starts[f]) + 3 for f in range(3)])  # side 3 of page f: 1 -> 0
    twists = np.zeros(s.n_edges, np.int64)
    twists[spine] = t
    result = trace(s, twists)
    for f in range(3):
        side = int(s.face_starts[f]) + 3
        port_at_a = 2 * side + 1  # side 3 ends at vertex 0 = end a
        partner_side = result.edge_partner[port_at_a] // 2
        # the strand of page f at the bottom continues at the top in page f + t (CCW)
        assert s.corner_face[partner_side] == (f + t) % 3


def test_twist_rule_reads_the_same_from_either_end():
    # mirror the book through z -> 1 - z: vertices 0 and 1 swap, the axis flips
    s = lkspace.load("book:5")
    v = s.vertices.copy()
    v[:, 2] = 1 - v[:, 2]
    perm = np.arange(s.n_vertices)
    perm[[0, 1]] = [1, 0]
    flipped = Scaffold.from_faces(v[np.argsort(perm)], [perm[f].tolist() for f in s.faces()])
    # relabelling swaps end a and end b; a rotation by pi about x maps it back onto book:5,
    # so with the same labels the strands must have the same structure
    for t in range(-5, 6):
        a = trace(s, t)
        b = trace(flipped, t)
        assert sorted(a.strand_lengths.tolist()) == sorted(b.strand_lengths.tolist())


def _ref_components(s, twists, nulls=()):
    edges = {tuple(e): int(t) for e, t in zip(s.edge_vertices.tolist(), twists)}
    return reference_trace(s.vertices.tolist(), s.faces(), edges, set(nulls))


def _multiset(strands):
    return Counter((closed, tuple(sorted(Counter(faces).items()))) for closed, faces in strands)


@settings(max_examples=300, deadline=None)
@given(data=st.data(), scaffold=traceable_scaffolds())
def test_matches_reference(data, scaffold):
    twists = data.draw(st.lists(st.integers(-5, 5), min_size=scaffold.n_edges, max_size=scaffold.n_edges))
    n_null = data.draw(st.integers(0, 2))
    null_sides = data.draw(
        st.lists(st.integers(0, scaffold.n_corners - 1), min_size=n_null, max_size=n_null, unique=True)
    )
    result = trace(scaffold, twists, null_sides)
    starts = scaffold.face_starts
    nulls = {
        (
            int(np.searchsorted(starts, c, side="right") - 1),
            int(c - starts[np.searchsorted(starts, c, side="right") - 1]),
        )
        for c in null_sides
    }
    ref = _ref_components(scaffold, twists, nulls)
    assert result.components == len(ref)
    mine = [(bool(result.closed[k]), result.strand_faces(k).tolist()) for k in range(result.components)]
    assert _multiset(mine) == _multiset(ref)
    assert int(np.sum(~result.closed)) == len(null_sides)


@settings(max_examples=200, deadline=None)
@given(data=st.data(), scaffold=traceable_scaffolds())
def test_adding_degree_to_a_label_changes_nothing(data, scaffold):
    twists = np.array(data.draw(st.lists(st.integers(-4, 4), min_size=scaffold.n_edges, max_size=scaffold.n_edges)))
    e = data.draw(st.integers(0, scaffold.n_edges - 1))
    shifted = twists.copy()
    shifted[e] += scaffold.edge_degrees[e] * data.draw(st.integers(-3, 3))
    a, b = trace(scaffold, twists), trace(scaffold, shifted)
    assert a.components == b.components
    assert sorted(a.strand_lengths.tolist()) == sorted(b.strand_lengths.tolist())


@settings(max_examples=200, deadline=None)
@given(data=st.data(), scaffold=traceable_scaffolds())
def test_lengths_add_up_and_steps_are_a_bijection(data, scaffold):
    twists = data.draw(st.lists(st.integers(-4, 4), min_size=scaffold.n_edges, max_size=scaffold.n_edges))
    result = trace(scaffold, twists)
    assert result.strand_lengths.sum() == scaffold.n_corners
    assert sorted(result.step_corners.tolist()) == list(range(scaffold.n_corners))


@settings(max_examples=150, deadline=None)
@given(data=st.data(), scaffold=traceable_scaffolds())
def test_relabelling_vertices_keeps_strand_lengths(data, scaffold):
    twists = np.array(data.draw(st.lists(st.integers(-4, 4), min_size=scaffold.n_edges, max_size=scaffold.n_edges)))
    perm = np.array(data.draw(st.permutations(range(scaffold.n_vertices))))
    # new vertex perm[v] is old vertex v
    vertices = np.empty_like(scaffold.vertices)
    vertices[perm] = scaffold.vertices
    relabelled = Scaffold.from_faces(vertices, [perm[f].tolist() for f in scaffold.faces()])
    # carry each label to the same geometric edge
    new_index = {tuple(sorted(perm[e])): i for i, e in enumerate(scaffold.edge_vertices)}
    new_twists = np.zeros_like(twists)
    for e, (a, b) in enumerate(relabelled.edge_vertices):
        new_twists[e] = twists[new_index[(a, b)]]
    a, b = trace(scaffold, twists), trace(relabelled, new_twists)
    assert sorted(a.strand_lengths.tolist()) == sorted(b.strand_lengths.tolist())


def test_null_side_opens_a_strand(tetra):
    result = trace(tetra, 1, [0])
    assert result.components == 3
    assert int(np.sum(~result.closed)) == 1
    k = int(np.flatnonzero(~result.closed)[0])
    ends = result.strand_ends(k)
    assert len(ends) == 2 and {e["edge"] for e in ends} == {int(tetra.side_edge[0])}
    d = result.to_dict()
    assert d["n_open"] == 1 and d["strands"][k]["closed"] is False


def test_two_nulls_on_one_strand_make_two_open_pieces(tetra):
    result = trace(tetra, 0, [0, 1])
    assert result.components == 5  # face 0 cut twice -> two open arcs
    assert int(np.sum(~result.closed)) == 2


def test_label_errors(tetra):
    with pytest.raises(LabelError, match="expected 6 twist labels"):
        trace(tetra, [1, 2])
    with pytest.raises(LabelError, match="integers"):
        trace(tetra, [1.5] * 6)


def test_ambiguous_radial_order_names_the_edge():
    # three faces on edge 0-1, two of them in the same half-plane
    v = [[0, 0, 0], [0, 0, 1], [1, 0, 0.5], [2, 0, 0.5], [-1, 0, 0.5]]
    s = Scaffold.from_faces(v, [[0, 1, 2], [0, 1, 3], [0, 1, 4]])
    with pytest.raises(RadialOrderError, match="edge 0 \\(0-1\\)"):
        trace(s, 1)


def test_explicit_radial_order_resolves_ambiguity():
    v = [[0, 0, 0], [0, 0, 1], [1, 0, 0.5], [2, 0, 0.5], [-1, 0, 0.5]]
    s = Scaffold.from_faces(v, [[0, 1, 2], [0, 1, 3], [0, 1, 4]], radial_orders={(0, 1, ()): (0, 3, 6)})
    assert trace(s, 1).components == 1
    assert trace(s, 3).components == 3


def test_json_fields(tetra):
    d = trace(tetra, 1).to_dict()
    assert d["components"] == 3 and d["holds_together"] is True
    assert sum(len(s["faces"]) for s in d["strands"]) == tetra.n_corners
    assert all(s["period"] is None for s in d["strands"])


# ---- labels near the int64 limit: the answer of t mod K, or a clean error -------------------


@pytest.mark.parametrize("name", ["book:3", "book:5", "book:6", "book:7", "tetrahedron"])
@pytest.mark.parametrize("t", [2**62, -(2**62), 2**63 - 1, -(2**63 - 1), 2**63 - 3])
def test_huge_labels_trace_as_their_residue(name, t):
    s = lkspace.load(name)
    big = trace(s, t)
    small = trace(s, np.mod(np.full(s.n_edges, t), np.maximum(s.edge_degrees, 1)))
    assert big.components == small.components
    assert big.strand_lengths.tolist() == small.strand_lengths.tolist()
    assert big.labels.tolist() == [t] * s.n_edges  # the labels traced are kept as given


def test_huge_labels_on_the_compiled_walk():
    s = lkspace.load("honeycomb:cP@6x6x6")  # large enough for the compiled kernel
    rng = np.random.default_rng(3)
    residues = rng.integers(0, 4, s.n_edges)
    big = residues + 4 * (2**61 - 1)  # near the int64 limit, congruent mod 4 (every edge has degree 4)
    assert trace(s, big).components == trace(s, residues).components


@pytest.mark.parametrize("labels", [2**63, -(2**63), 10**30])
def test_labels_past_the_bound_are_an_error(labels):
    with pytest.raises(LabelError, match="out of range"):
        trace("book:3", labels)
    with pytest.raises(LabelError, match="out of range"):
        trace("book:3", [labels] + [0] * 9)


@pytest.mark.parametrize("t", ["9223372036854775808", "-9223372036854775808", "1" + "0" * 5000])
def test_cli_twist_past_the_bound(capsys, t):
    from lkspace.cli import main

    code = main(["trace", "book:3", "--twist", t, "--json"])
    out, err = capsys.readouterr()
    assert code == 2 and err.startswith("lkspace: error: --twist") and err.count("\n") == 1
    assert "out of range" in err and "2**63 - 1" in err
    assert json.loads(out)["error"]["type"] == "LabelError"


def test_cli_twist_at_the_int64_limit_is_its_residue(capsys):
    """The issue's crash: book:3 with twist 2**63 - 1 traces as 2**63 - 1 mod K on every edge."""
    from lkspace.cli import main

    assert main(["trace", "book:3", "--twist", str(2**63 - 1), "--json"]) == 0
    big = json.loads(capsys.readouterr()[0])
    s = lkspace.load("book:3")
    small = trace(s, np.mod(np.full(s.n_edges, 2**63 - 1), np.maximum(s.edge_degrees, 1)))
    assert big["components"] == small.components
