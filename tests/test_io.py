"""OBJ and scaffold-file readers/writers: round trips and bad input."""

from __future__ import annotations

import json
import os
import subprocess

import numpy as np
import pytest
from hypothesis import given, settings

import lkspace
from lkspace import io
from lkspace.errors import ScaffoldError
from lkspace.io.obj import parse_obj

from .strategies import scaffolds


def _same(a, b):
    assert np.array_equal(a.vertices, b.vertices)
    assert a.faces() == b.faces()
    assert np.array_equal(a.edge_keys, b.edge_keys)


@pytest.mark.parametrize(
    "name", ["tetrahedron", "cube", "dodecahedron", "truncated-octahedron", "book:3", "dihedron:4"]
)
@pytest.mark.parametrize("ext", [".obj", ".json"])
def test_roundtrip_builtin(tmp_path, name, ext):
    s = lkspace.load(name)
    path = tmp_path / f"s{ext}"
    io.write(s, path)
    _same(s, lkspace.load(str(path)))


@settings(max_examples=60, deadline=None)
@given(scaffolds())
@pytest.mark.filterwarnings("ignore:.*share no edge:lkspace.errors.LkspaceWarning")
def test_roundtrip_random_json_with_labels(tmp_path_factory, s):
    rng = np.random.default_rng(s.n_corners)
    twists = rng.integers(-3, 4, s.n_edges)
    nulls = rng.random(s.n_corners) < 0.2
    path = tmp_path_factory.mktemp("rt") / "s.json"
    io.write(s, path, twists, nulls)
    back = lkspace.load(str(path))
    _same(s, back)
    assert back.labels.tolist() == twists.tolist()
    if nulls.any():
        assert back.nulls.tolist() == nulls.tolist()
    else:
        assert back.nulls is None


def test_json_roundtrip_keeps_radial_orders(tmp_path):
    v = [[0, 0, 0], [0, 0, 1], [1, 0, 0.5], [2, 0, 0.5], [-1, 0, 0.5]]
    s = lkspace.Scaffold.from_faces(v, [[0, 1, 2], [0, 1, 3], [0, 1, 4]], radial_orders={(0, 1, ()): (0, 3, 6)})
    io.write(s, tmp_path / "r.json")
    back = lkspace.load(str(tmp_path / "r.json"))
    assert back.radial_orders == {(0, 1, ()): (0, 3, 6)}
    assert lkspace.trace(back, 1).components == 1


def test_obj_features():
    text = """# a quad and a triangle
o thing
v 0 0 0
v 1 0 0
v 1 1 0 1.0
v 0 1 0
vt 0 0
vn 0 0 1
g group
s off
f 1/1/1 2/1/1 3//1 4
f -4 -2 -1   # negative indices: 1 3 4
"""
    s = parse_obj(text, "t.obj")
    assert s.faces() == [[0, 1, 2, 3], [0, 2, 3]]


@pytest.mark.parametrize(
    "text, match",
    [
        ("v 0 0\n", "line 1: vertex needs 3 coordinates"),
        ("v 0 0 x\n", "line 1: vertex coordinates must be numbers"),
        ("v 0 0 nan\n", "line 1: vertex 1 coordinate is not a finite number"),
        ("v 0 0 inf\n", "not a finite number"),
        ("v 0 0 1e13\n", "within \\+-1e\\+12"),
        ("\ufeffv 0 0 0\nv 1 0 0\nf 1 2 x\n", "line 3: face vertex 'x'"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "line 4: face vertex index 9 out of range 1..3"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "line 4: face 0 has 2 vertices"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\n", "line 4: face 0 repeats a vertex"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 a\n", "line 4: face vertex 'a'"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1 2//2 3/a\n", "line 4: face vertex '3/a'"),  # was read as 3
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/1/1/1\n", "line 4: face vertex '3/1/1/1'"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", "index 0 out of range"),
        ("v 0 0 0\nv 0 0 0\nv 0 1 0\nf 1 2 3\n", "zero-length edge between vertices 0 and 1"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nfoo 1 2 3\n", "line 4: unknown OBJ statement 'foo'"),
        ("v 0 0 0\n", "no faces"),
        ("", "no vertices"),
    ],
)
def test_obj_errors(text, match):
    with pytest.raises(ScaffoldError, match=match):
        parse_obj(text, "bad.obj")


def _write(tmp_path, data):
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(data) if not isinstance(data, str) else data)
    return str(path)


GOOD = {"vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "faces": [[0, 1, 2]]}


@pytest.mark.parametrize(
    "patch, match",
    [
        ({"vertices": [[0, 0], [1, 0, 0], [0, 1, 0]]}, "vertices\\[0\\]: expected 3 entries"),
        ({"faces": [[0, 1, 5]]}, "faces\\[0\\]\\[2\\] \\(vertex\\): 5 out of range 0..2"),
        ({"faces": [[0, 1, "x"]]}, "faces\\[0\\]\\[2\\] \\(vertex\\): expected an integer"),
        ({"twists": [1, 2]}, "twists: expected 3 entries"),
        ({"twists": [1, 2, 1.5]}, "twists\\[2\\]: expected an integer"),
        ({"version": 99}, "version 99 is not supported"),
        ({"colour": 1}, "unknown key"),
        ({"nulls": [[0, 7]]}, "nulls\\[0\\]\\[1\\] \\(side\\): 7 out of range 0..2"),
        ({"offsets": [[[0, 0, 0]] * 3]}, "offsets given without a lattice"),
    ],
)
def test_json_errors(tmp_path, patch, match):
    with pytest.raises(ScaffoldError, match=match):
        lkspace.load(_write(tmp_path, {**GOOD, **patch}))


def test_json_syntax_error_has_line(tmp_path):
    with pytest.raises(ScaffoldError, match="bad.json line 2: invalid JSON"):
        lkspace.load(_write(tmp_path, '{"vertices": [],\n "faces": [,]}'))


def test_unknown_extension_and_name(tmp_path):
    with pytest.raises(ScaffoldError, match="unknown file type"):
        lkspace.load("mesh.stl")
    with pytest.raises(ScaffoldError, match="neither a file nor a built-in"):
        lkspace.load("nosuchthing")
    with pytest.raises(ScaffoldError, match="expected book:N with an integer"):
        lkspace.load("book")
    with pytest.raises(ScaffoldError, match="expected book:N with an integer"):
        lkspace.load("book:x")


def lkspace_in(folder, *args):
    """Run the installed ``lkspace ARGS --json`` in ``folder``; return ``(exit status, JSON printed)``."""
    proc = subprocess.run(["lkspace", *args, "--json"], cwd=folder, capture_output=True, text=True, timeout=120)
    return proc.returncode, json.loads(proc.stdout)


def test_a_builtin_name_means_the_builtin_in_every_folder(tmp_path):
    """A file or folder named like a built-in does not shadow it; ``./NAME`` or an extension reads the file."""
    (tmp_path / "cube").mkdir()
    (tmp_path / "tetrahedron").write_text("not a mesh\n")
    io.write(lkspace.load("tetrahedron"), tmp_path / "cube.obj")
    code, data = lkspace_in(tmp_path, "info", "cube")
    assert (code, data["scaffold"], data["n_edges"]) == (0, "cube", 12)
    code, data = lkspace_in(tmp_path, "trace", "tetrahedron", "--twist", "1")
    assert (code, data["components"]) == (0, 3)
    code, data = lkspace_in(tmp_path, "info", "cube.obj")
    assert (code, data["n_edges"]) == (0, 6)
    code, data = lkspace_in(tmp_path, "info", "./tetrahedron")  # the file, which is no scaffold file
    assert code != 0 and "unknown file type" in data["error"]["message"]
    code, data = lkspace_in(tmp_path, "enumerate", "tetrahedron", "--labels", "-1,1", "--shards", "2", "-o", "book:2")
    assert code == 0 and os.path.isdir(tmp_path / "book:2")
    code, data = lkspace_in(tmp_path, "export", "book:2", "--twist", "1", "-o", "a.obj")  # not the catalog folder
    assert (code, data["scaffold"]) == (0, "book:2")
    code, data = lkspace_in(tmp_path, "export", "./book:2", "--row", "0", "-o", "b.obj")
    assert (code, data["scaffold"], data["row"]) == (0, "tetrahedron", 0)


def test_load_reads_builtin_names_before_files(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "cube").write_text("not a mesh\n")
    assert lkspace.load("cube").n_edges == 12
    with pytest.raises(ScaffoldError, match="unknown file type"):
        lkspace.load("./cube")
    with pytest.raises(ScaffoldError, match="unknown file type"):
        lkspace.load(tmp_path / "cube")  # a pathlib.Path is always a file
    io.write(lkspace.load("tetrahedron"), tmp_path / "mine.obj")
    os.rename(tmp_path / "mine.obj", tmp_path / "mine")
    with pytest.raises(ScaffoldError, match="unknown file type"):
        lkspace.load("mine")  # no built-in name: the file of that name


def test_write_is_atomic_on_failure(tmp_path):
    target = tmp_path / "keep.json"
    target.write_text("old")
    with pytest.raises(ScaffoldError):
        io.write(lkspace.load("cube"), tmp_path / "keep.stl")
    assert target.read_text() == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["keep.json"]


def test_written_files_get_the_usual_permissions(tmp_path):
    import os

    io.write(lkspace.load("cube"), tmp_path / "c.obj")
    umask = os.umask(0)
    os.umask(umask)
    assert (os.stat(tmp_path / "c.obj").st_mode & 0o777) == (0o666 & ~umask)


def test_bom_and_bad_bytes(tmp_path):
    path = tmp_path / "bom.json"
    path.write_bytes(b"\xef\xbb\xbf" + json.dumps(GOOD).encode())
    assert lkspace.load(str(path)).n_faces == 1
    path = tmp_path / "bom.obj"
    path.write_bytes(b"\xef\xbb\xbfv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n")
    assert lkspace.load(str(path)).n_faces == 1
    path = tmp_path / "latin.obj"
    path.write_bytes(b"# caf\xe9\nv 0 0 0\n")
    with pytest.raises(ScaffoldError, match=r"latin.obj line 1: byte 5 \(0xe9\) is not UTF-8"):
        lkspace.load(str(path))


@pytest.mark.parametrize(
    "patch, match",
    [
        ({"version": True}, "version True is not supported"),
        ({"version": 1.0}, "version 1.0 is not supported"),
        ({"name": 5}, "name: expected a string"),
        ({"vertices": [[10**400, 0, 0], [1, 0, 0], [0, 1, 0]]}, "past the bound"),
        ({"vertices": [[True, 0, 0], [1, 0, 0], [0, 1, 0]]}, "expected a number, got True"),
        ({"faces": [[0, 1, 10**30]]}, "out of range 0..2"),
        ({"faces": [[0, 1, True]]}, "expected an integer, got True"),
        ({"labels": [2**63, 0, 0]}, "labels\\[0\\]: 9223372036854775808 out of range"),
        ({"labels": [True, 0, 0]}, "labels\\[0\\]: expected an integer"),
        ({"edges": 5}, "'edges' does not match"),
        ({"edges": [[0, 1, [5]], 3, [1]]}, "'edges' does not match"),
        ({"edges": [[True, 1], [0, 2], [1, 2]]}, "'edges' does not match"),
        ({"radial_orders": [{"edge": [0], "sides": []}]}, "radial_orders\\[0\\].edge: expected \\[a, b\\]"),
        ({"radial_orders": [{"edge": [0, "x"], "sides": 3}]}, "edge\\[1\\]: expected an integer"),
        ({"radial_orders": [{"edge": [0, 1], "sides": 3}]}, "sides: expected a list"),
        ({"radial_orders": [5]}, "expected \\{'edge'"),
        ({"lattice": [[1, 0], "x"]}, "lattice\\[0\\]: expected 3 entries"),
        ({"lattice": 3}, "lattice: expected a list"),
        ({"lattice": [[1, 0, 0], [0, 1, 0]]}, "offsets: expected a list"),
    ],
)
def test_json_fields_are_checked_strictly(tmp_path, patch, match):
    with pytest.raises(ScaffoldError, match=match):
        lkspace.load(_write(tmp_path, {**GOOD, **patch}))


def test_deep_and_huge_json(tmp_path):
    with pytest.raises(ScaffoldError, match="nested deeper than 64"):
        lkspace.load(_write(tmp_path, "[" * 100000 + "]" * 100000))
    with pytest.raises(ScaffoldError, match="invalid JSON"):
        lkspace.load(_write(tmp_path, '{"vertices": [[' + "9" * 5000 + ", 0, 0]]}"))


def test_fifo_is_refused(tmp_path):
    import os

    fifo = tmp_path / "pipe.obj"
    os.mkfifo(fifo)
    with pytest.raises(ScaffoldError, match="not a regular file"):
        lkspace.load(str(fifo))
