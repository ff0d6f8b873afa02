"""Periodic scaffolds: Wigner–Seitz cells, supercells, threads — numbers from the paper."""

from __future__ import annotations

import itertools
import math
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import lkspace
from lkspace import trace
from lkspace.errors import ScaffoldError
from lkspace.model.lattice import Lattice
from lkspace.model.specs import parse_label_set
from lkspace.scaffolds.periodic import LATTICES, voronoi_scaffold, wigner_seitz, wigner_seitz_from_voronoi
from lkspace.strands.holding_together import lattice_index


def test_cubic_honeycomb_threads_per_module():
    # the paper: uniform twists on the cubic honeycomb give 3, 4, 6, 4, 3 threads per module
    s = lkspace.load("honeycomb:cP")
    assert [trace(s, t).components for t in range(5)] == [3, 4, 6, 4, 3]


@pytest.mark.parametrize("t", range(-3, 7))
def test_truncated_octahedral_honeycomb_seven_threads(t):
    assert trace(lkspace.load("honeycomb:cI"), t).components == 7


def test_cubic_edge_classes_are_x_y_z():
    s = lkspace.load("honeycomb:cP")
    assert s.edge_deltas.tolist() == [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    assert s.edge_degrees.tolist() == [4, 4, 4]


@pytest.mark.parametrize(
    "name, faces, edges, degrees",
    [
        ("tiling:square", 1, 2, {2}),
        ("tiling:hexagonal", 1, 3, {2}),
        ("honeycomb:cP", 3, 3, {4}),
        ("honeycomb:hP", 4, 5, {3, 4}),
        ("honeycomb:cF", 6, 8, {3}),
        ("honeycomb:cI", 7, 12, {3}),
        ("honeycomb:oF", 7, 12, {3}),
    ],
)
def test_wigner_seitz_cells(name, faces, edges, degrees):
    s = lkspace.load(name)
    assert (s.n_faces, s.n_edges, set(s.edge_degrees.tolist())) == (faces, edges, degrees)
    # a face class of a 3D honeycomb is a wall between two cells: the cell has 2 * n_faces faces
    assert s.periodic


@pytest.mark.parametrize("name", list(LATTICES))
def test_shipped_cells_are_the_qhull_construction(name):
    # the built-ins are read from data, which must be what Qhull builds (positions to 1e-12: another
    # Qhull may round differently; the shipped positions are the ones catalogs' content hashes saw)
    shipped, built = wigner_seitz(name), wigner_seitz_from_voronoi(name)
    assert shipped.faces() == built.faces() and shipped.name == built.name == name
    assert np.array_equal(shipped.corner_offsets, built.corner_offsets)
    assert np.array_equal(shipped.lattice.basis, built.lattice.basis)
    np.testing.assert_allclose(shipped.vertices, built.vertices, rtol=0, atol=1e-12)


def test_loading_a_honeycomb_needs_no_scipy():
    code = "import sys, lkspace; lkspace.load('honeycomb:oF@2x1x1').n_faces; print('scipy' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"


def test_square_tiling_loops_weave_chainmail():
    s = lkspace.load("tiling:square")
    loops, weave, mail = (trace(s, t).to_dict() for t in (0, 1, 2))
    assert loops["closed_loops"] == 1 and not loops["holds_together"]  # separate rings fall apart
    assert weave["infinite_threads"] == 2 and weave["holds_together"]  # biaxial weave
    directions = {tuple(np.round(x["direction"], 6)) for x in weave["strands"]}
    assert len(directions) == 2
    assert mail["closed_loops"] == 1 and mail["infinite_threads"] == 0 and mail["holds_together"]  # chainmail


def test_hexagonal_tiling_triaxial_weave():
    d = trace(lkspace.load("tiling:hexagonal"), 1).to_dict()
    assert d["infinite_threads"] == 3 and d["holds_together"]
    angles = sorted(round(math.degrees(math.atan2(x["direction"][1], x["direction"][0])) % 180) for x in d["strands"])
    assert angles == [0, 60, 120]


def _period_order(period, sizes):
    # smallest k > 0 with k * period = 0 modulo sizes
    return math.lcm(*[s // math.gcd(s, int(p)) for p, s in zip(period, sizes)])


@pytest.mark.parametrize(
    "name, sizes",
    [
        ("honeycomb:cP", (2, 2, 2)),
        ("honeycomb:cP", (1, 2, 3)),
        ("tiling:square", (3, 2)),
        ("tiling:hexagonal", (2, 2)),
        ("honeycomb:cI", (2, 1, 1)),
        ("honeycomb:hP", (1, 1, 2)),
    ],
)
@pytest.mark.parametrize("t", [0, 1, 2, 3])
def test_supercell_consistency(name, sizes, t):
    base = lkspace.load(name)
    cell = lkspace.load(f"{name}@{'x'.join(map(str, sizes))}")
    n_cells = math.prod(sizes)
    assert cell.n_faces == n_cells * base.n_faces and cell.n_edges == n_cells * base.n_edges
    a, b = trace(base, t), trace(cell, t)
    # each base thread of period p splits into n_cells / order(p mod sizes) threads of the supercell
    expected = sum(n_cells // _period_order(p, sizes) for p in a.periods)
    assert b.components == expected
    lengths = sorted(
        int(a.strand_lengths[k]) * _period_order(a.periods[k], sizes)
        for k in range(a.components)
        for _ in range(n_cells // _period_order(a.periods[k], sizes))
    )
    assert sorted(b.strand_lengths.tolist()) == lengths
    assert a.holds_together == b.holds_together


def test_supercell_labels_per_cell_differ():
    s = lkspace.load("tiling:square@2x1")
    assert s.n_edges == 4
    mixed = trace(s, [1, 1, 0, 0]).components
    assert mixed != trace(s, 1).components or mixed != trace(s, 0).components


def test_voronoi_cube_face_centres():
    s = lkspace.load("voronoi:cube-faces")
    assert s.n_faces == 12 and set(s.face_sizes.tolist()) == {3}
    assert sorted(set(s.edge_degrees.tolist())) == [3, 4]


def test_voronoi_two_points_is_bcc():
    # cubic lattice with points at (0,0,0) and the body centre: the truncated-octahedral
    # honeycomb again, as a 2-cell supercell
    s = voronoi_scaffold(Lattice.cubic(), [[0, 0, 0], [0.5, 0.5, 0.5]])
    assert s.n_faces == 14 and set(s.edge_degrees.tolist()) == {3}
    assert trace(s, 0).components == 14


def test_voronoi_file(tmp_path, capsys):
    import json

    from lkspace.cli import main

    p = tmp_path / "v.json"
    p.write_text(
        json.dumps(
            {
                "format": "lkspace-voronoi",
                "version": 1,
                "lattice": np.eye(3).tolist(),
                "points": [[0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]],
            }
        )
    )
    assert main(["info", str(p), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["faces"] == 12


@pytest.mark.parametrize(
    "name, match",
    [
        ("tiling:square@2x2x2", "expected AxB"),
        ("honeycomb:cP@2x2", "expected AxBxC"),
        ("cube@2x2x2", "supercells need a periodic"),
        ("honeycomb:xx", "unknown"),
    ],
)
def test_bad_periodic_names(name, match):
    with pytest.raises(ScaffoldError, match=match):
        lkspace.load(name)


def test_voronoi_rejects_coincident_points():
    with pytest.raises(ScaffoldError, match="coincide"):
        voronoi_scaffold(Lattice.cubic(), [[0, 0, 0], [1, 0, 0]])


def test_periodic_scaffold_file_roundtrip(tmp_path):
    s = lkspace.load("honeycomb:cF")
    lkspace.io.write(s, tmp_path / "cf.json", labels=np.arange(s.n_edges) % 3)
    back = lkspace.load(str(tmp_path / "cf.json"))
    assert np.array_equal(back.edge_keys, s.edge_keys)
    assert trace(back).components == trace(s, np.arange(s.n_edges) % 3).components


def _minors_gcd(vectors, dim):
    g = 0
    for rows in itertools.combinations(vectors, dim):
        g = math.gcd(g, int(round(abs(np.linalg.det(np.array(rows, dtype=float))))))
    return g


@settings(max_examples=200, deadline=None)
@given(
    st.integers(2, 3).flatmap(
        lambda d: st.tuples(
            st.just(d), st.lists(st.lists(st.integers(-4, 4), min_size=d, max_size=d), min_size=0, max_size=5)
        )
    )
)
def test_lattice_index_is_gcd_of_minors(case):
    dim, vectors = case
    assert lattice_index(np.array(vectors, dtype=np.int64).reshape(-1, dim), dim) == _minors_gcd(vectors, dim)


@pytest.mark.parametrize(
    "name, labels", [("tiling:square@2x1", "-1..1"), ("honeycomb:cP", "-2..2"), ("tiling:hexagonal", "-2..2")]
)
def test_periodic_catalog_rows_match_the_tracer(name, labels):
    # the enumerator's holds_together must be the lift-aware one of the tracer
    import pandas as pd

    s = lkspace.load(name)
    df = pd.concat(list(lkspace.designs(name, labels)))
    assert df.orbit_size.sum() == len(parse_label_set(labels)) ** s.n_edges
    for row in df.itertuples():
        t = trace(s, np.array(row.labels))
        assert (t.components, t.holds_together) == (row.components, row.holds_together)
    assert not df.holds_together.all()


def test_periodic_symmetry_orders():
    from lkspace.symmetry.group import symmetry_group

    orders = {
        name: (symmetry_group(lkspace.load(name)).order, symmetry_group(lkspace.load(name)).n_rotations)
        for name in ("tiling:square", "tiling:hexagonal", "honeycomb:cP", "honeycomb:cI", "honeycomb:cP@2x2x2")
    }
    # 2D tilings live in 3D: turning the plane over is a rotation too
    assert orders == {
        "tiling:square": (16, 8),
        "tiling:hexagonal": (24, 12),
        "honeycomb:cP": (48, 24),
        "honeycomb:cI": (48, 24),
        "honeycomb:cP@2x2x2": (384, 192),
    }


def test_infinite_threads_are_not_closed(capsys):
    from lkspace.cli import main

    d = trace(lkspace.load("honeycomb:cP"), 1).to_dict()
    assert {s["kind"] for s in d["strands"]} == {"thread"}
    assert all(s["closed"] is False and s["infinite"] and s["period"] != [0, 0, 0] for s in d["strands"])
    loops = trace(lkspace.load("honeycomb:cP"), 4).to_dict()
    assert all(s["kind"] == "loop" and s["closed"] and s["period"] == [0, 0, 0] for s in loops["strands"])
    assert main(["trace", "tiling:square", "--twist", "1"]) == 0
    out = capsys.readouterr().out
    assert "0 closed loops, 2 infinite threads" in out
    assert out.count("infinite thread ") == 2 and "closed loop " not in out and " yes " not in out
    assert main(["trace", "tiling:square", "--twist", "2"]) == 0
    assert capsys.readouterr().out.count("closed loop ") == 1


def test_radial_order_of_a_reversed_periodic_edge(tmp_path):
    import json

    from lkspace.io.scaffold_json import scaffold_to_dict

    cp = lkspace.load("honeycomb:cP")
    data = scaffold_to_dict(cp)
    e = 0
    (a, b, *delta) = cp.edge_keys[e].tolist()
    sides = cp.radial.edge_sides[cp.radial.edge_starts[e] : cp.radial.edge_starts[e + 1]].tolist()
    starts = cp.face_starts
    named = [
        [
            int(np.searchsorted(starts, s, side="right") - 1),
            int(s - starts[np.searchsorted(starts, s, side="right") - 1]),
        ]
        for s in sides
    ]
    for edge in ([a, b, delta], [b, a, [-x for x in delta]]):  # the same edge, named from either end
        data["radial_orders"] = [{"edge": edge, "sides": named[::-1]}]
        path = tmp_path / "r.json"
        path.write_text(json.dumps(data))
        back = lkspace.load(str(path))
        assert back.radial_orders == {(a, b, tuple(delta)): tuple(sides[::-1])}
        assert back.radial.edge_sides[:4].tolist() == sides[::-1]


def test_supercell_bound():
    from lkspace.errors import UsageError
    from lkspace.scaffolds.periodic import MAX_SUPERCELL_FACES

    with pytest.raises(UsageError, match=f"at most {MAX_SUPERCELL_FACES} faces"):
        lkspace.load("honeycomb:cP@1000x1000x1000")
    with pytest.raises(ScaffoldError, match="expected AxBxC"):
        lkspace.load("honeycomb:cP@" + "9" * 400 + "x1x1")
