"""``lkspace construct`` and the built-in ``knot:NAME`` / ``link:NAME``: a type's diagram made into a design.

Hand-checked meshes, refusals, the real command line, and the constructions named by an
independent identification (topoly's HOMFLY-PT on the realized curves) across crossing numbers.
"""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from lkspace.errors import ScaffoldError
from lkspace.scaffolds import builtin
from lkspace.scaffolds.constructed import design_scaffold, table
from lkspace.scaffolds.diagram_mesh import check_pd, diagram_mesh, link_components, smooth_nugatory

from .cli_calls import one_line_error, run

TREFOIL = [[1, 5, 2, 4], [3, 1, 4, 6], [5, 3, 6, 2]]  # KnotInfo's 3_1
FIGURE_EIGHT = [[4, 2, 5, 1], [8, 6, 1, 5], [6, 3, 7, 4], [2, 7, 3, 8]]  # KnotInfo's 4_1
HOPF = [[4, 1, 3, 2], [2, 3, 1, 4]]


def test_a_twist_region_becomes_one_edge():
    m = diagram_mesh(TREFOIL)
    # the three crossings are one twist region: every face a triangle, the labels add up to 3 half twists
    assert all(len(f) >= 3 for f in m.faces)
    assert sum(abs(t) for t in m.labels) == 3 and m.crossings == 3
    assert len({tuple(sorted(e)) for e in m.edges}) == len(m.edges)  # no two edges on one vertex pair


def test_the_mesh_is_a_sphere_with_one_edge_per_crossing_or_twist_region():
    for pd in (TREFOIL, FIGURE_EIGHT, HOPF):
        m = diagram_mesh(pd)
        v, e, f = m.n_vertices, len(m.edges), len(m.faces)
        assert v - e + f == 2
        assert sum(abs(t) for t in m.labels) == len(pd)  # alternating diagrams: no crossing cancels


def test_a_kink_is_smoothed_away_and_the_type_kept():
    # the trefoil with a Reidemeister I kink added on edge 6: X[6,7,7,8] and 6 -> 8 where 6 ended
    kinked = [[1, 5, 2, 4], [3, 1, 4, 6], [5, 3, 8, 2], [6, 7, 7, 8]]
    code, freed = smooth_nugatory(check_pd(kinked))
    assert len(code) == 3 and freed == 0
    assert sum(abs(t) for t in diagram_mesh(kinked).labels) == 3


def test_components_of_a_pd_code():
    assert link_components(check_pd(TREFOIL)) == 1
    assert link_components(check_pd(HOPF)) == 2


@pytest.mark.parametrize(
    "pd, words",
    [
        ([[1, 2, 3]], ["crossing 1", "four integer edge labels"]),
        ([[1, 1, 1, 2]], ["edge label 1", "occurs 3"]),
        ([[1, 5, 2, 4], [3, 1, 4, 6], [5, 3, 6, 2], [7, 9, 8, 10], [9, 7, 10, 8]], ["not a connected diagram"]),
    ],
)
def test_what_is_no_link_diagram_is_refused_in_words(pd, words):
    with pytest.raises(ScaffoldError) as info:
        diagram_mesh(pd)
    for w in words:
        assert w in str(info.value)


def test_the_layout_is_deterministic_and_embedded():
    a, b = design_scaffold(FIGURE_EIGHT, "4_1"), design_scaffold(FIGURE_EIGHT, "4_1")
    assert a.vertices.tobytes() == b.vertices.tobytes() and np.array_equal(a.labels, b.labels)
    flat = design_scaffold(FIGURE_EIGHT, "4_1", "flat")
    assert np.all(flat.vertices[:, 2] >= 0)


def _named(scaffold):
    from lkspace import identify

    return identify(scaffold, scaffold.labels).to_json()


@pytest.mark.parametrize(
    "name", ["3_1", "m3_1", "5_2", "8_17", "10_1", "L6a4", "mL7a1", "L10a91", "L11a159", "mL11a159"]
)
def test_builtin_table_designs_are_their_type(name):
    pytest.importorskip("snappy")
    kind = "link" if name.lstrip("m").startswith("L") else "knot"
    s = builtin(f"{kind}:{name}")
    got = _named(s)
    base = name[1:] if name.startswith("m") else name
    assert got["name"] == base
    if got["mirror"] is not None:
        assert got["mirror"] is name.startswith("m")


def test_unknown_and_misfiled_builtin_names_are_refused():
    with pytest.raises(ScaffoldError, match="unknown built-in 'knot:99_1'"):
        builtin("knot:99_1")
    with pytest.raises(ScaffoldError, match="it is a link: write link:L6a4"):
        builtin("knot:L6a4")


def test_the_shipped_table_holds_every_type_up_to_its_range():
    entries = table()
    knots_ = [n for n, e in entries.items() if e.components == 1]
    links = [n for n, e in entries.items() if e.components > 1]
    assert len(knots_) == 2977 and len(links) == 1424  # LinkInfo: 4,188 entries, one per orientation
    assert sum(1 for n in knots_ if entries[n].crossings <= 10) == 249
    assert sum(1 for n in links if entries[n].crossings <= 9) == 130


@pytest.mark.parametrize("name", ["3_1", "4_1", "5_2", "6_2", "7_4", "8_17", "9_35", "10_100", "10_161"])
def test_constructions_are_named_alike_by_topoly(name):
    """Independent: topoly's HOMFLY-PT names the curves lkspace realizes, and tells the mirror image apart."""
    topoly = pytest.importorskip("topoly")
    from lkspace import realize

    marks = []
    for typed in (name, "m" + name):
        curves = realize(builtin(f"knot:{typed}")).curves
        assert len(curves) == 1
        found = topoly.homfly(np.asarray(curves[0]).tolist(), closure=0, max_cross=80, chiral=True)
        assert found.lstrip("+-") == name, (typed, found)
        marks.append(found[0] if found[0] in "+-" else "")
    if name in {"4_1", "8_17"}:  # amphichiral (8_17 equals its mirror image reversed: unoriented, the same)
        assert marks == ["", ""], marks
    else:
        assert "" not in marks and marks[0] != marks[1], marks


def test_construct_on_the_command_line(tmp_path, capsys):
    pytest.importorskip("snappy")
    out = tmp_path / "8_17.json"
    code, text, err = run(capsys, "construct", "8_17", "-o", out, "--json")
    assert code == 0, err
    answer = json.loads(text)
    assert answer["name"] == "8_17" and answer["builtin"] == "knot:8_17" and answer["diagram_crossings"] == 8
    code, text, err = run(capsys, "identify", out, "--json")
    assert code == 0 and json.loads(text)["name"] == "8_17"
    code, text, err = run(capsys, "construct", "m5_2", "-o", tmp_path / "m5_2.json", "--json")
    assert code == 0 and json.loads(text)["mirror"] is True


def test_construct_from_a_pd_code_and_a_sum(tmp_path, capsys):
    pytest.importorskip("snappy")
    code, text, err = run(capsys, "construct", "--pd", json.dumps(FIGURE_EIGHT), "-o", tmp_path / "a.json", "--json")
    assert code == 0 and json.loads(text)["name"] == "4_1"
    code, text, err = run(capsys, "construct", "3_1#4_1", "-o", tmp_path / "b.json", "--json")
    assert code == 0, err
    assert json.loads(text)["name"] == "3_1#4_1"


def test_construct_refusals_are_one_line(tmp_path, capsys):
    pytest.importorskip("snappy")
    target = tmp_path / "x.json"
    code, _, err = run(capsys, "construct", "99_99", "-o", target)
    assert code == 2
    one_line_error(err, "99_99")
    code, _, err = run(capsys, "construct", "--pd", "[[1,2,3,4]]", "-o", target)
    assert code == 1
    one_line_error(err, "edge label")
    code, _, err = run(capsys, "construct", "--pd", "[[1,2", "-o", target)
    assert code == 2
    one_line_error(err, "--pd")
    assert not target.exists()


def test_export_a_builtin_table_design_as_users_type_it(tmp_path):
    out = tmp_path / "8_17.obj"
    done = subprocess.run(
        [sys.executable, "-m", "lkspace", "export", "knot:8_17", "-o", str(out)], capture_output=True, text=True
    )
    assert done.returncode == 0, done.stderr
    assert out.stat().st_size > 1000


def test_lookup_answers_a_type_the_atlas_lacks_with_its_construction(capsys, tmp_path):
    from lkspace.linktypes.lookup import read_index, write_index

    rows, meta = read_index()  # the shipped atlas without 10_1's rows: 10_1 only constructed
    walked = tmp_path / "walked.parquet"
    write_index(str(walked), [r for r in rows if r.type != "10_1"], {k: v for k, v in meta.items() if k != "format"})
    code, text, err = run(capsys, "lookup", "10_1", "--json", "--atlas", walked)
    assert code == 0, err
    designs = json.loads(text)["designs"]
    assert designs and all(d["constructed"] for d in designs)
    assert {d["scaffold"] for d in designs} == {"knot:10_1", "knot:m10_1"}
    code, text, err = run(capsys, "lookup", "3_1", "--json")
    assert code == 0 and not any(d["constructed"] for d in json.loads(text)["designs"])


def test_a_relaxed_table_design_prints_with_no_other_option(tmp_path, capsys):
    """The issue's example: ``lkspace export knot:8_17 --relax -o 8_17.stl`` (a tight rope touches itself)."""
    out = tmp_path / "3_1.stl"
    code, text, err = run(capsys, "export", "knot:3_1", "--relax", "-o", out, "--json")
    assert code == 0, err
    printed = json.loads(text)["fabrication"]
    assert printed["min_gap"] > 0 and printed["pieces"] == 1


@pytest.mark.parametrize("name", ["knot:8_6", "knot:m8_6", "knot:10_3", "knot:m10_3", "link:L10a91", "link:L9a8"])
def test_builtin_table_designs_pass_the_embedding_check(name):
    """These placements were shipped refused by ``export`` (strands within ``min_separation``)."""
    from lkspace import realize

    real = realize(builtin(name))
    assert real.min_distance >= real.min_separation


def test_construct_skips_a_placement_whose_strands_come_too_close():
    pytest.importorskip("snappy")
    from lkspace.linktypes.construct import clear, construct

    pd = [list(x) for x in table()["8_6"].pd]
    assert "come within" in (clear(design_scaffold(pd, "8_6", "sphere")) or "")  # named 8_6, but refused
    made = construct("8_6")
    assert made.clear and made.layout != "sphere" and clear(made.scaffold) is None
    assert made.builtin == "knot:8_6" and made.layout == table()["8_6"].layout


def test_export_relaxed_8_6_with_no_other_option(tmp_path, capsys):
    """``lkspace export knot:8_6 --relax -o 8_6.stl``: refused before its placement was checked for clearance."""
    code, text, err = run(capsys, "export", "knot:8_6", "--relax", "-o", tmp_path / "8_6.stl", "--json")
    assert code == 0, err
    assert json.loads(text)["fabrication"]["pieces"] == 1


def test_unnamed_links_are_compared_for_every_orientation_of_their_components():
    """A link's Jones polynomial depends on its components' orientations: both of the Hopf link's are kept."""
    pytest.importorskip("regina")
    from lkspace.linktypes.construct import reversals

    hopf = reversals(HOPF)
    assert len(hopf) == 2 and len({jones for jones, _ in hopf}) == 2
    assert len(reversals(TREFOIL)) == 1


@pytest.mark.slow
@pytest.mark.parametrize("name", ["L11n432", "mL11n437"])
def test_links_the_tables_names_miss_are_constructed(name):
    """Non-hyperbolic: lkspace names neither the table's diagram nor the design; Jones and HOMFLY-PT must agree."""
    pytest.importorskip("snappy")
    from lkspace.linktypes.construct import clear, construct

    made = construct(name)
    assert made.clear and clear(made.scaffold) is None
    assert made.crossings == 11 and int(abs(made.scaffold.labels).sum()) == 11
