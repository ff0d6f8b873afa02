"""Every symmetry of periodic scaffolds and supercells, against an independent brute force.

The reference (:mod:`tests.brute_periodic`) shares no code with :mod:`lkspace.symmetry`:
it tries every integer matrix ``N`` with entries up to twice the largest supercell factor
(a supercell ``D`` of a cell whose point group has entries in ``{-1, 0, 1}`` needs entries
up to ``max(D)``), every translation taking vertex 0 to a vertex, and counts designs by
Burnside's lemma.  Orders and counts go through the command line.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

import lkspace
from lkspace.model.lattice import Lattice
from lkspace.scaffolds.periodic import voronoi_scaffold
from tests.brute_periodic import brute_group, burnside
from tests.cli_calls import one_line_error, run
from tests.strategies import PLANE_LATTICES, voronoi_tilings

LATTICES = ["tiling:square", "tiling:hexagonal", "honeycomb:cP", "honeycomb:hP", "honeycomb:oF", "honeycomb:cF"]
LATTICES += ["honeycomb:cI", "voronoi:cube-faces", "laves"]
SUPERCELLS_2D = ["2x1", "1x2", "2x2", "3x1", "1x3", "3x2"]
SUPERCELLS_3D = ["2x1x1", "1x2x1", "1x1x2", "2x2x1"]
CASES = LATTICES + [f"{n}@{s}" for n in LATTICES[:2] for s in SUPERCELLS_2D]
CASES += [f"{n}@{s}" for n in LATTICES[2:] for s in SUPERCELLS_3D if n != "laves" or s == "2x1x1"]
FEW_EDGES = 12
"""Design counts through ``enumerate`` for scaffolds with at most this many edges (the walk is exponential)."""


def bound(name: str) -> int:
    """Largest entry of ``N`` the brute force tries: twice the largest supercell factor."""
    sizes = [int(x) for x in name.split("@")[1].split("x")] if "@" in name else [1]
    return 2 * max(sizes)


def cli_json(capsys, *args: str) -> dict:
    code, out, err = run(capsys, *args, "--json")
    assert code == 0, err
    return json.loads(out)


@pytest.mark.parametrize("name", CASES)
def test_orders_match_the_brute_force(name, capsys):
    group = brute_group(lkspace.load(name), bound(name))
    order = cli_json(capsys, "info", name)["symmetry_group_order"]
    assert order == {"isometries": len(group), "rotations": sum(sign == 1 for sign, _ in group)}


@pytest.mark.parametrize("name", [n for n in CASES if lkspace.load(n).n_edges <= FEW_EDGES])
def test_design_counts_match_burnside(name, capsys):
    group = brute_group(lkspace.load(name), bound(name))
    rotations = cli_json(capsys, "enumerate", name, "--labels", "0,1", "--count-only")
    assert rotations["designs"] == burnside(group, [0, 1], "rotations")
    isometries = cli_json(capsys, "enumerate", name, "--labels=-1..1", "--symmetry", "isometries", "--count-only")
    assert isometries["designs"] == burnside(group, [-1, 0, 1], "isometries")


def test_hexagonal_two_by_one_by_hand(capsys):
    """The torus of ``2 a1, a2``: its lattice holds ``a2`` and ``2 a1 - a2``, orthogonal (lengths 1 and sqrt 3).

    So 4 in-plane point maps of the tiling's 12 keep it (the half-turn about the normal
    and the mirrors along and across ``a2``), each twice (the plane turned over or not),
    times 2 translations (0 and ``a1``): 16 isometries, 8 of them rotations; main found 4.
    With labels {0, 1} on 6 edges Burnside gives 21 designs (main: 30).
    """
    assert cli_json(capsys, "info", "tiling:hexagonal@2x1")["symmetry_group_order"] == {
        "rotations": 8,
        "isometries": 16,
    }
    assert cli_json(capsys, "enumerate", "tiling:hexagonal@2x1", "--labels", "0,1", "--count-only")["designs"] == 21
    group = brute_group(lkspace.load("tiling:hexagonal@2x1"), 2)
    assert burnside(group, [0, 1], "rotations") == 21


def test_non_lattice_translation():
    """Voronoi cells of cubic points plus body centres are the bcc cells: the half-diagonal is a symmetry."""
    from lkspace.symmetry.group import symmetry_group

    scaffold = voronoi_scaffold(Lattice.cubic(), [[0, 0, 0], [0.5, 0.5, 0.5]])
    group = symmetry_group(scaffold)
    brute = brute_group(scaffold, 2)
    assert (group.order, group.n_rotations) == (len(brute), sum(s == 1 for s, _ in brute)) == (96, 48)


def test_skewed_basis_finds_the_whole_point_group():
    """``tiling:square@2x1`` with lattice basis ``(2, 0), (10, 1)``: its point group needs entries up to 10."""
    from lkspace.model.scaffold import Scaffold
    from lkspace.symmetry.group import symmetry_group

    square = lkspace.load("tiling:square@2x1")
    skew = np.array([[1, 0], [5, 1]])  # new basis = skew @ old basis; offsets o -> o @ skew^-1
    scaffold = Scaffold(
        square.vertices,
        square.face_starts,
        square.corners,
        lattice=Lattice(skew @ square.lattice.basis),
        corner_offsets=square.corner_offsets @ np.array([[1, 0], [-5, 1]]),
        name="skewed",
    )
    group = symmetry_group(scaffold)
    brute = brute_group(scaffold, 12)
    assert (group.order, group.n_rotations) == (len(brute), sum(s == 1 for s, _ in brute)) == (16, 8)


def test_voronoi_of_a_skewed_basis():
    """Voronoi cells of ``Z^3`` given by a skewed basis are still cubes, with the cube's 48 motions."""
    from lkspace.symmetry.group import symmetry_group

    scaffold = voronoi_scaffold(Lattice(np.array([[1.0, 0, 0], [5, 1, 0], [3, -2, 1]])), [[0, 0, 0]])
    assert (scaffold.n_faces, scaffold.n_vertices, scaffold.n_edges) == (3, 1, 3)
    assert (symmetry_group(scaffold).order, symmetry_group(scaffold).n_rotations) == (48, 24)


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(voronoi_tilings())
@example(("oblique", np.zeros((1, 3))))  # a corner at lattice coordinate 0.371875 once split a vertex class
def test_voronoi_tilings_match_the_brute_force(case):
    """Voronoi tilings of 1-3 points at quarter coordinates: glides, half-cell translations, mirrors."""
    from lkspace.errors import ScaffoldError
    from lkspace.symmetry.group import symmetry_group

    name, generators = case
    try:
        scaffold = voronoi_scaffold(Lattice(np.array(PLANE_LATTICES[name])), generators)
    except ScaffoldError:  # e.g. two generators on one lattice point
        return
    group = symmetry_group(scaffold)
    brute = brute_group(scaffold, 2)
    assert (group.order, group.n_rotations) == (len(brute), sum(s == 1 for s, _ in brute))


def test_large_supercell_orders_without_tables(capsys):
    """``info`` counts the 65,536 motions of a 64 x 64 torus; ``enumerate`` refuses their tables in one line."""
    assert cli_json(capsys, "info", "tiling:square@64x64")["symmetry_group_order"] == {
        "rotations": 8 * 64 * 64,
        "isometries": 16 * 64 * 64,
    }
    code, _, err = run(capsys, "enumerate", "tiling:square@64x64", "--labels", "0,1", "--count-only")
    assert code == 2
    one_line_error(err, "65536 motions", "--symmetry none")


@pytest.mark.slow
@pytest.mark.parametrize(
    "name", ["tiling:square@4x4", "tiling:hexagonal@4x2", "honeycomb:cP@2x2x2", "honeycomb:cI@2x2x1"]
)
def test_larger_supercells_match_the_brute_force(name, capsys):
    group = brute_group(lkspace.load(name), bound(name))
    order = cli_json(capsys, "info", name)["symmetry_group_order"]
    assert order == {"isometries": len(group), "rotations": sum(sign == 1 for sign, _ in group)}


@settings(max_examples=60, deadline=None)
@given(st.data())
def test_face_keys_are_cycles_up_to_translation(data):
    """Rotating, reversing or translating a face keeps its key; the key is the smallest sequence (Python)."""
    from lkspace.symmetry.periodic_search import face_keys

    m = data.draw(st.integers(3, 6))
    corners = np.array(data.draw(st.lists(st.tuples(*[st.integers(0, 2)] * 3), min_size=m, max_size=m)), np.int64)
    shift = np.r_[0, data.draw(st.tuples(st.integers(-3, 3), st.integers(-3, 3)))]
    moved = np.roll(corners[:: data.draw(st.sampled_from([1, -1]))], data.draw(st.integers(0, m - 1)), axis=0) + shift
    keys = face_keys(np.concatenate([corners, moved]), np.array([0, m, 2 * m]))
    assert np.array_equal(keys[0], keys[1])
    smallest = min(
        tuple(np.concatenate([[row[0], *(row[1:] - seq[0, 1:])] for row in seq]).tolist())
        for seq in (np.roll(corners[::d], -i, axis=0) for d in (1, -1) for i in range(m))
    )
    assert tuple(keys[0].tolist()) == smallest


@pytest.mark.parametrize("name", ["honeycomb:oF", "honeycomb:cI@2x2x1", "tiling:hexagonal@3x2", "laves@2x1x1"])
def test_kd_tree_and_pairwise_matching_find_one_group(name, monkeypatch):
    # small scaffolds match vertices pair by pair (checked above against the brute force), large
    # ones with scipy's KD-tree: forced both ways, every motion must come out the same
    from lkspace.symmetry import periodic_search

    scaffold = lkspace.load(name)
    groups = []
    for few in (scaffold.n_vertices, 0):
        monkeypatch.setattr(periodic_search, "FEW_VERTICES", few)
        group = periodic_search.periodic_symmetry(scaffold, 1e-6)
        groups.append([(m.sigma.tolist(), m.offsets.tolist(), m.edge_perm.tolist()) for m in group.elements()])
    assert len(groups[0]) > 1 and groups[0] == groups[1]
