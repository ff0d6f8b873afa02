"""Reverse lookup (``lkspace lookup``), common names and the atlas index, through the installed CLI.

Lookup answers are identified again by the geometric path (``lkspace.identify``); common
names are checked against KnotInfo/LinkInfo's own columns; the index is built by the
real script (``experiments/build_atlas.py``) into a temporary folder.
"""

import json
import os
import pathlib
import subprocess
import sys

import pytest
from hypothesis import given
from hypothesis import strategies as st

import lkspace
from lkspace.errors import UsageError
from lkspace.linktypes.answers import LookupAnswer
from lkspace.linktypes.common_names import CHIRAL, COMMON, common_name, resolve_name, resolve_type
from lkspace.linktypes.records import DesignRecord, IndexRow

ROOT = pathlib.Path(__file__).resolve().parents[1]
LKSPACE = str(pathlib.Path(sys.executable).parent / "lkspace")
ENV = {**os.environ, "LKSPACE_PROGRESS": "0"}

ROLFSEN_LINKS = {"L2a1": "2^2_1", "L4a1": "4^2_1", "L5a1": "5^2_1", "L6a3": "6^2_1", "L6a4": "6^3_2"}
"""Rolfsen's names of the links with a common name (Hopf 2^2_1, Whitehead 5^2_1, Borromean 6^3_2, ...)."""


def lookup(*args, check=True):
    proc = subprocess.run([LKSPACE, "lookup", *args], capture_output=True, text=True, env=ENV, timeout=120)
    if check:
        assert proc.returncode == 0, proc.stderr
    return proc


def lookup_json(*args):
    return json.loads(lookup(*args, "--json").stdout)


@pytest.mark.parametrize(
    ("typed", "name"),
    [
        ("Borromean rings", "L6a4"),
        ("borromean", "L6a4"),
        ("  BORROMEAN-rings ", "L6a4"),
        ("trefoil", "3_1"),
        ("left-handed trefoil", "m3_1"),
        ("Left handed Trefoil", "m3_1"),
        ("figure-eight knot", "4_1"),
        ("Figure eight", "4_1"),
        ("Whitehead link", "L5a1"),
        ("Solomon link", "L4a1"),
        ("(2,4) torus link", "L4a1"),
        ("Hopf link", "L2a1"),
        ("cinquefoil", "5_1"),
        ("three-twist knot", "5_2"),
        ("stevedore", "6_1"),
        ("unknot", "0_1"),
        ("unlink of 2 components", "split: 0_1 + 0_1"),
        ("3-component unlink", "split: 0_1 + 0_1 + 0_1"),
        ("L6a4", "L6a4"),
        ("l6a4{0,1}", "L6a4"),
        ("3_1", "3_1"),
        ("m3_1", "m3_1"),
        ("K11a1", "11a_1"),
        ("k14n10910", "K14n10910"),
        ("4_1#3_1", "4_1#3_1"),
    ],
)
def test_resolve_name(typed, name):
    assert resolve_name(typed) == name


def test_common_names_both_ways():
    for name, words in COMMON.items():
        assert common_name(name) == words[0]
        for w in words:
            assert resolve_name(w) == name
            assert resolve_name(w.upper().replace(" ", "-")) == name
    assert resolve_type("right-handed trefoil") == ("3_1", "table")
    assert common_name("3_1", mirror=False) == "right-handed trefoil" == CHIRAL["3_1"][0]
    assert common_name("3_1", mirror=True) == common_name("m3_1") == "left-handed trefoil"
    assert common_name("8_19") is None and common_name("split: 0_1 + 3_1") is None
    assert common_name("split: 0_1 + 0_1") == "unlink of 2 components"


def test_unknown_name_names_the_parameter_and_suggests():
    with pytest.raises(UsageError) as caught:
        resolve_name("borromian rings")
    assert caught.value.parameter == "name"
    assert str(caught.value).startswith("name 'borromian rings': not a knot or link name")
    assert "did you mean 'Borromean rings'?" in str(caught.value)
    with pytest.raises(UsageError):
        resolve_name("")


def test_common_names_match_knotinfo_and_linkinfo():
    """The pairs against the database's own columns: links by Rolfsen name, the trefoil's hand by its writhe."""
    dki = pytest.importorskip("database_knotinfo")
    spherogram = pytest.importorskip("spherogram")
    knots = {r["name"]: r for r in dki.link_list()}
    links = {r["name"].split("{")[0]: r for r in dki.link_list(proper_links=True)}
    for name in COMMON:
        if name.startswith("L"):
            assert links[name]["rolfsen_name"] == ROLFSEN_LINKS[name], name
        else:
            assert name in knots, name
    assert int(links["L6a4"]["components"]) == 3
    pd = json.loads(knots["3_1"]["pd_notation"])
    assert spherogram.Link(pd).writhe() == 3  # all crossings positive: KnotInfo's 3_1 is the right-handed trefoil


def test_parse_type_understands_common_names():
    from lkspace.linktypes.names import parse_type

    pytest.importorskip("database_knotinfo")
    borromean = parse_type("Borromean rings")
    assert (borromean.name, borromean.components, borromean.chirality) == ("L6a4", 3, "any")
    left = parse_type("left-handed trefoil")
    assert (left.name, left.chirality) == ("3_1", "mirror")
    with pytest.raises(UsageError):
        parse_type("left-handed trefoil", "table")


def test_solve_type_takes_a_common_name():
    pytest.importorskip("snappy")
    args = [LKSPACE, "solve", "tetrahedron", "--type", "Borromean rings", "--labels", "-1..1", "--json"]
    proc = subprocess.run(args, capture_output=True, text=True, env=ENV, timeout=300)
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert out["status"] == "found" and out["target"]["name"] == "L6a4"
    assert [s["labels"] for s in out["solutions"]] == [
        [1] * 6
    ]  # amphichiral: built from its diagram with +1 (the mirror, -1, is the same type)


def test_lookup_answers_are_identified_again():
    """The shipped atlas's answers, identified by the geometric path, are what lookup says."""
    pytest.importorskip("snappy")
    borromean = lookup_json("Borromean rings", "--limit", "2")
    assert (borromean["name"], borromean["common_name"]) == ("L6a4", "Borromean rings")
    mirror = lookup_json("m3_1", "--limit", "2")
    assert mirror["chirality"] == "mirror" and all(d["mirror"] is True for d in mirror["designs"])
    for answer, name, want_mirror in ((borromean, "L6a4", None), (mirror, "3_1", True)):
        assert answer["designs"]
        for d in answer["designs"]:
            ident = lkspace.identify(d["scaffold"], d["labels"], geometric=True)
            assert ident.name == name, d
            if want_mirror is not None:
                assert ident.mirror is want_mirror, d
            assert d["command"] == f"lkspace identify {d['scaffold']} --twist {','.join(map(str, d['labels']))}"


def test_lookup_plain_name_shows_both_chiralities_simplest_first():
    both = lookup_json("3_1", "--limit", "1000")
    assert {d["mirror"] for d in both["designs"]} == {True, False}
    assert {d["chiral_name"] for d in both["designs"]} == {"3_1", "m3_1"}
    keys = [(d["sum_abs"], d["nonzero"]) for d in both["designs"]]
    assert keys == sorted(keys)
    assert both["simplest_kept"] == len(both["designs"])
    assert both["designs_total"] == sum(
        json.loads(lookup("3_1", "--scaffold", s.split()[0], "--json").stdout)["designs_total"]
        for s in {space.split()[0] for space in both["found_in"]}  # a scaffold may have several spaces (cube)
    )
    assert len({(d["scaffold"], tuple(d["labels"])) for d in both["designs"]}) == len(both["designs"])
    one = lookup_json("3_1", "--scaffold", "dihedron:3")
    assert one["designs"] and {d["scaffold"] for d in one["designs"]} == {"dihedron:3"}
    assert len(lookup_json("3_1", "--limit", "3")["designs"]) == 3


def test_lookup_json_fields():
    out = lookup_json("trefoil", "--limit", "1")
    assert LookupAnswer.from_json(out).to_json() == out  # the JSON is the record's, field for field
    assert set(out) == {
        "query", "name", "chirality", "common_name", "atlas", "searched", "found_in", "designs_total", "simplest_kept",
        "designs", "ideal_shape",
    }  # fmt: skip
    assert set(out["designs"][0]) == {
        "type", "common_name", "scaffold", "labels", "label_set", "sum_abs", "nonzero", "crossings", "mirror",
        "chiral_name", "designs_of_type", "command", "constructed",
    }  # fmt: skip
    assert out["query"] == "trefoil" and set(out["found_in"]) <= set(out["searched"])
    assert out["designs_total"] >= out["simplest_kept"] >= 2
    assert out["atlas"] == str(ROOT / "lkspace" / "data" / "atlas.parquet")


def test_lookup_human_output():
    out = lookup("Borromean rings", "--limit", "1").stdout
    assert out.startswith("L6a4 (Borromean rings): ")
    assert "lkspace identify tetrahedron --twist " in out


def test_identify_shows_common_names():
    pytest.importorskip("snappy")
    run = [LKSPACE, "identify", "whitehead"]
    human = subprocess.run(run, capture_output=True, text=True, env=ENV, timeout=300)
    assert human.stdout.startswith("whitehead: 2 components: L5a1 (Whitehead link, as in the table) [linkinfo]\n")
    left = subprocess.run([*run[:2], "dihedron:3", "--twist", "-1", "--json"], capture_output=True, text=True, env=ENV)
    assert json.loads(left.stdout)["common_name"] == "left-handed trefoil"


def test_unknown_name_exits_2_with_a_suggestion():
    proc = lookup("borromian", check=False)
    assert proc.returncode == 2
    assert proc.stderr.startswith("lkspace: error: NAME 'borromian': not a knot or link name")
    assert "did you mean 'Borromean rings'?" in proc.stderr and "Traceback" not in proc.stderr


def test_not_an_atlas_exits_1(tmp_path):
    bad = tmp_path / "x.parquet"
    bad.write_text("no parquet")
    proc = lookup("3_1", "--atlas", str(bad), check=False)
    assert proc.returncode == 1
    assert proc.stderr.startswith(f"lkspace: error: --atlas {bad}: not a Parquet atlas index (")
    assert proc.stderr.count("\n") == 1
    proc = lookup("3_1", "--atlas", str(tmp_path / "missing.parquet"), check=False)
    assert (
        proc.returncode == 1
        and proc.stderr == f"lkspace: error: --atlas {tmp_path / 'missing.parquet'}: no such file\n"
    )


@pytest.mark.parametrize("meta", [b"\xff\xfe", b"[" * 100_000, b"{not json"], ids=["not-utf8", "deep", "not-json"])
def test_an_atlas_whose_metadata_is_not_json_exits_1(tmp_path, meta):
    """Its metadata not UTF-8, not JSON or nested past Python's stack: an internal error (ValueError, RecursionError)."""
    import pyarrow.parquet as pq

    from lkspace.linktypes.lookup import META

    table = pq.read_table(ROOT / "lkspace" / "data" / "atlas.parquet")
    bad = tmp_path / "x.parquet"
    pq.write_table(table.replace_schema_metadata({META: meta}), bad)
    proc = lookup("3_1", "--atlas", str(bad), check=False)
    assert proc.returncode == 1
    assert proc.stderr == f"lkspace: error: --atlas {bad}: its {META.decode()} metadata is no JSON object\n"


@pytest.fixture(scope="module")
def small_atlas(tmp_path_factory):
    """An index of dihedron:3 with labels -1..1, built by the real script."""
    folder = tmp_path_factory.mktemp("atlas")
    out = folder / "atlas.parquet"
    args = [sys.executable, str(ROOT / "experiments" / "build_atlas.py"), "--spaces", "dihedron:3=-1..1"]
    args += ["--work", str(folder / "work"), "-o", str(out)]
    first = subprocess.run(args, capture_output=True, text=True, env=ENV, timeout=600)
    assert first.returncode == 0, first.stderr
    again = subprocess.run(args, capture_output=True, text=True, env=ENV, timeout=600)
    assert again.returncode == 0 and "dihedron:3 -1..1: reused" in again.stdout  # a rerun identifies nothing
    return out


def test_build_script_writes_the_documented_index(small_atlas):
    import pyarrow.parquet as pq

    from lkspace.linktypes.lookup import read_index

    rows, meta = read_index(str(small_atlas))
    assert meta["format"] == 1 and meta["lkspace_version"] == lkspace.__version__ and meta["date"]
    assert meta["left_out"] == []
    (space,) = meta["spaces"]
    assert space.pop("wall_time") > 0 and space.pop("identified") == 10
    assert space == {
        "scaffold": "dihedron:3", "labels": "-1..1", "designs": 10, "assignments": 27, "types": 4, "complete": True
    }  # fmt: skip
    # dihedron:3 (two triangles on one 3-cycle), labels -1..1: by hand, the unknot needs one twisted edge
    # (sum 1), the Hopf link two (sum 2), the trefoil all three (sum 3); all labels 0 is the 2-component unlink
    first = {r.type: r.first_sum_abs for r in rows}
    assert first == {"0_1": 1, "L2a1": 2, "3_1": 3, "split: 0_1 + 0_1": 0}
    by_type = {r.type: r for r in rows}
    assert by_type["L2a1"].common_name == "Hopf link" and by_type["L2a1"].crossing_number == 2
    assert by_type["split: 0_1 + 0_1"].crossing_number is None
    trefoil = json.loads(by_type["3_1"].to_row()["examples"])  # the column as written: a JSON list
    assert sorted(e["labels"] for e in trefoil) == [[-1, -1, -1], [1, 1, 1]]
    assert {e["mirror"] for e in trefoil} == {True, False}
    assert by_type["3_1"].chirality_table == by_type["3_1"].chirality_mirror == 1
    raw = pq.read_table(small_atlas).to_pylist()
    assert [IndexRow.from_row(r).to_row() for r in raw] == raw  # one reader, one writer: a round trip
    names = pq.read_schema(small_atlas).names
    assert names[:3] == ["type", "common_name", "components"] and "examples" in names


def test_absent_type_exits_1_naming_the_spaces(small_atlas):
    constructed = lookup_json("figure-eight", "--atlas", str(small_atlas))  # a table type: its construction
    assert [d["scaffold"] for d in constructed["designs"]] == ["knot:4_1"] and constructed["designs"][0]["constructed"]
    proc = lookup("K14n10910", "--atlas", str(small_atlas), check=False)  # beyond the tables: nothing to construct
    assert proc.returncode == 1, proc.stderr
    line = proc.stderr.strip()
    assert line.count("\n") == 0 and line.startswith("lkspace: error: K14n10910: no design in the atlas ")
    assert "searched 1 space: dihedron:3 -1..1" in line and "experiments/build_atlas.py" in line
    assert "--atlas" in line
    found = lookup_json("3_1", "--atlas", str(small_atlas))
    assert found["searched"] == found["found_in"] == ["dihedron:3 -1..1"]
    assert found["designs_total"] == found["simplest_kept"] == 2  # [1, 1, 1] and its mirror [-1, -1, -1]
    mirror = lookup_json("m3_1", "--atlas", str(small_atlas))
    assert mirror["designs_total"] == 1 and [d["labels"] for d in mirror["designs"]] == [[-1, -1, -1]]


def test_lookup_help_and_run_stay_light():
    def modules(*args):
        proc = subprocess.run(
            [sys.executable, "-X", "importtime", "-m", "lkspace", "lookup", *args],
            capture_output=True,
            text=True,
            env=ENV,
        )
        assert proc.returncode == 0, proc.stderr[-2000:]
        return {line.split("|")[2].strip() for line in proc.stderr.splitlines() if line.startswith("import time:")}

    light = modules("--help")
    assert "click" in light and not {m for m in light if m.split(".")[0] in ("numpy", "pandas", "pyarrow")}
    run = modules("5_1")
    assert "pyarrow.parquet" in run
    heavy = ("pandas", "snappy", "spherogram", "regina", "database_knotinfo", "numba", "igraph")
    assert not {m for m in run if m.split(".")[0] in heavy}


def test_studio_answers_lookup_as_the_cli_does():
    pytest.importorskip("starlette")
    pytest.importorskip("uvicorn")
    httpx = pytest.importorskip("httpx")
    from lkspace.studio.app import Studio
    from lkspace.studio.server import start_in_thread

    url, stop = start_in_thread(Studio())
    try:
        with httpx.Client(base_url=url, timeout=60) as client:
            answer = client.get("/api/lookup", params={"name": "Borromean rings", "limit": 3})
            assert answer.status_code == 200
            assert answer.json() == lookup_json("Borromean rings", "--limit", "3")
            on = client.get("/api/lookup", params={"name": "m3_1", "scaffold": "dihedron:4"}).json()
            assert on["designs"] and {(d["scaffold"], d["mirror"]) for d in on["designs"]} == {("dihedron:4", True)}
            for params, status, start in [
                ({"name": "borromian"}, 400, "name 'borromian': not a knot or link name"),
                ({}, 400, "name: a knot or link type"),
                ({"name": "3_1", "limit": "many"}, 400, "limit: an integer in 1..1000"),
                (
                    {"name": "3_1", "scaffold": "nowhere"},
                    404,
                    "3_1: no design in the atlas shipped with lkspace; searched 0 spaces: none (no space of scaffold 'nowhere')",
                ),
            ]:
                bad = client.get("/api/lookup", params=params)
                assert bad.status_code == status, bad.text
                assert bad.json()["error"]["message"].startswith(start), bad.text
    finally:
        stop()


@given(
    st.lists(
        st.tuples(st.lists(st.integers(-2, 2), min_size=3, max_size=3), st.sampled_from([None, True, False])),
        max_size=40,
        unique_by=lambda d: tuple(d[0]),
    ),
    st.integers(1, 4),
)
def test_examples_keep_the_k_simplest_of_each_chirality(designs, k):
    """Against sorting them all: per chirality the k smallest (sum |t|, non-zero, max |t|, labels), merged."""
    import numpy as np

    from lkspace.linktypes.examples import Examples

    kept = Examples(k)
    for labels, mirror in designs:
        a = [abs(x) for x in labels]
        kept.add(
            np.array(labels), (sum(a), sum(x != 0 for x in a), max(a)), DesignRecord("3_1", mirror=mirror, crossings=3)
        )

    def key(d):
        a = [abs(x) for x in d[0]]
        return (sum(a), sum(x != 0 for x in a), max(a), tuple(d[0]))

    want = []
    for side in (None, True, False):
        want += sorted((d for d in designs if d[1] is side), key=key)[:k]
    assert [(list(e.labels), e.mirror) for e in kept.records()] == [(list(d[0]), d[1]) for d in sorted(want, key=key)]


def test_sums_and_split_types_are_looked_up_as_the_atlas_spells_them():
    assert lookup_json("3_1#m3_1", "--limit", "1")["name"] == "3_1#3_1"  # the atlas holds sums without mirror marks
    assert lookup_json("3_1#L2a1", "--limit", "1")["name"] == "L2a1#3_1"
    unlink = lookup_json("unlink of 2 components", "--limit", "1")
    assert unlink["name"] == "split: 0_1 + 0_1" and unlink["designs"][0]["sum_abs"] == 0
    amphichiral = lookup("m4_1", check=False)  # identify does not tell the figure-eight knot's mirror apart
    assert amphichiral.returncode == 1 and "none identified as this chirality: ask for 4_1" in amphichiral.stderr


def test_every_knot_to_ten_crossings_has_an_ideal_shape_within_five_percent():
    import csv

    from lkspace.linktypes.ideal_shapes import shipped_shapes

    with open(ROOT.parent / "shared" / "ideal-ropelength.csv") as f:  # KnotInfo's column
        ideal = {row["type"]: float(row["ropelength"]) for row in csv.DictReader(f)}
    shapes = shipped_shapes()
    assert len(shapes) == 249
    assert set(shapes) == {name for name in ideal if name.split("_")[0].isdigit() and int(name.split("_")[0]) <= 10}
    for name, shape in shapes.items():
        assert shape.chiral_name.removeprefix("m") == name and shape.ideal == ideal[name]
        assert shape.ropelength <= 1.05 * ideal[name], name
    assert lookup_json("5_2")["ideal_shape"]["chiral_name"].removeprefix("m") == "5_2"
    assert lookup_json("L6a4")["ideal_shape"] is None  # links: no table of ideal ropelengths here
    assert "ideal shape" in lookup("7_4").stdout


def test_the_ideal_shape_lookup_gives_is_drawn_within_five_percent(tmp_path):
    """lookup --json -> its command -> the OBJ, measured by the independent tests/ropelength.py; the
    curve is the knot lookup names (topoly), in the chirality it says."""
    import shlex

    import numpy as np

    from tests.ropelength import read_obj_polylines, ropelength

    shape = lookup_json("m3_1")["ideal_shape"]
    cmd = shlex.split(shape["command"])
    assert cmd[:2] == ["lkspace", "export"] and cmd[-2] == "-o"
    out = tmp_path / "trefoil.obj"
    done = subprocess.run([LKSPACE, *cmd[1:-1], str(out)], capture_output=True, text=True, env=ENV, timeout=600)
    assert done.returncode == 0, done.stderr
    curves = read_obj_polylines(str(out))
    measured = ropelength(curves)["ropelength"]
    assert measured <= 1.05 * 32.74 and abs(measured - shape["ropelength"]) < 0.01 * measured
    topoly = pytest.importorskip("topoly")
    points = np.asarray(curves[0][0]).tolist()
    assert topoly.homfly(points, closure=0, chiral=True) == "-3_1"  # topoly's m3_1: the chirality lookup says
