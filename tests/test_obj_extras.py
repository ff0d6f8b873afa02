"""OBJ files as Blender, MeshLab and other tools write them: extras are read past, malformed lines named.

Vertex colours (``v x y z r g b``) had been refused; a line continued with ``\\`` was an
error at its backslash.  The property test writes any small mesh with any mix of the
extras tools add and reads back the same faces.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import lkspace
from lkspace.errors import ScaffoldError
from lkspace.io.obj import parse_obj
from tests.cli_calls import one_line_error, run

from .strategies import scaffolds

BLENDER = """# Blender 4.2.0
# www.blender.org
mtllib cube.mtl
o Cube
v 1.000000 1.000000 -1.000000 0.8000 0.1000 0.1000
v 1.000000 -1.000000 -1.000000 0.8000 0.1000 0.1000
v 1.000000 1.000000 1.000000 0.1000 0.8000 0.1000
v 1.000000 -1.000000 1.000000 0.1000 0.8000 0.1000
v -1.000000 1.000000 -1.000000 0.1 0.1 0.8
v -1.000000 -1.000000 -1.000000 0.1 0.1 0.8
v -1.000000 1.000000 1.000000 1 1 1
v -1.000000 -1.000000 1.000000 1 1 1
vn -0.0000 1.0000 -0.0000
vn -0.0000 -0.0000 1.0000
vt 0.625000 0.500000
s 0
usemtl Material
f 1/1/1 5/1/1 7/1/1 3/1/1
f 4/1/2 3/1/2 7/1/2 8/1/2
f 8//2 7//2 5//2 6//2
f 6 2 4 8
f 2 1 3 4
f 6 5 1 2
l 1 2
"""


def test_blender_obj_with_vertex_colours_normals_and_materials():
    """A Blender export with vertex colours: read as the cube (colours, normals and materials ignored)."""
    cube = parse_obj(BLENDER.replace("\n", "\r\n"), "cube.obj")
    assert (cube.n_vertices, cube.n_edges, cube.n_faces) == (8, 12, 6)
    assert cube.vertices[6].tolist() == [-1.0, 1.0, 1.0]


def test_meshlab_rgba_colours_and_weights():
    text = "v 0 0 0 255 0 0 255\nv 1 0 0 1.0\nv 0 1 0 0 0 0\nf 1 2 3\n"
    assert parse_obj(text, "m.obj").faces() == [[0, 1, 2]]


def test_a_line_continued_with_a_backslash():
    text = "v 0 0 0\nv 1 0 \\\n  0\nv 0 1 0\nv 1 1 1\nf 1 2 \\\n3 \\\n4\n"
    assert parse_obj(text, "c.obj").faces() == [[0, 1, 2, 3]]
    with pytest.raises(ScaffoldError, match="c.obj line 2: vertex coordinates must be numbers"):
        parse_obj("v 0 0 0\nv 1 0 \\\nx\n", "c.obj")  # the statement's first line
    with pytest.raises(ScaffoldError, match="c.obj line 4: face 0 has 2 vertices"):
        parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \\\n", "c.obj")  # continued on no line


@pytest.mark.parametrize(
    "text, words",
    [
        ("v 0 0 0 1 0\n", ["line 1", "vertex needs 3 coordinates (then a weight or an r g b colour), got 5"]),
        ("v 0 0 0 1 0 0 1 0\n", ["line 1", "got 8 values"]),
        ("v 0 0 0 red 0 0\n", ["line 1", "vertex coordinates must be numbers"]),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", ["line 4", "index -4 out of range 1..3 (or -3..-1)"]),
        ("v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nvx 1\r\n", ["line 4", "unknown OBJ statement 'vx'"]),
        ("v 0 0 0\x0c\nv 1 0 0\nv 0 1 0\nfoo\n", ["line 4", "'foo'"]),  # a form feed had counted as a line end
    ],
)
def test_malformed_extras_are_one_line_naming_the_line(tmp_path, capsys, text, words):
    (tmp_path / "bad.obj").write_text(text, newline="")
    code, out, err = run(capsys, "info", tmp_path / "bad.obj")
    assert code != 0, out
    one_line_error(err, "bad.obj", *words)


EXTRAS = st.sampled_from(["", " 0.5 0.25 1", " 1", " 1 0 0 1"])
"""What a tool may write after a vertex's coordinates: nothing, a colour, a weight, a colour with alpha."""


@settings(max_examples=60, deadline=None, derandomize=True, database=None)
@given(scaffold=scaffolds(), data=st.data())
def test_any_mesh_with_any_extras_reads_back_the_same(scaffold, data):
    """Property: colours, weights, texture and normal indices, relative indices, comments, groups, CRLF and
    continued lines change nothing read."""
    lines = ["# written by a tool", "mtllib x.mtl", "o thing"]
    for x, y, z in scaffold.vertices.tolist():
        lines.append(f"v {x!r} {y!r} {z!r}" + data.draw(EXTRAS))
    lines += ["vt 0 0", "vn 0 0 1", "g group", "s 1", "usemtl m"]
    n = scaffold.n_vertices
    for face in scaffold.faces():
        entries = []
        for v in face:
            index = str(v + 1) if data.draw(st.booleans()) else str(v - n)  # 1-based or relative
            entries.append(index + data.draw(st.sampled_from(["", "/1", "//1", "/1/1"])))
        if len(entries) > 3 and data.draw(st.booleans()):
            entries.insert(2, "\\\n ")  # continued on the next line
        lines.append("f " + " ".join(entries) + data.draw(st.sampled_from(["", "  # a comment"])))
    lines.append("l 1 2")
    text = data.draw(st.sampled_from(["\n", "\r\n"])).join(lines) + "\n"
    back = parse_obj(text, "tool.obj")
    assert back.faces() == scaffold.faces()
    assert np.array_equal(back.vertices, scaffold.vertices)


@pytest.mark.parametrize("name", ["big.obj", "big.json"])
def test_an_input_past_the_size_bound_is_refused_before_it_is_read(tmp_path, capsys, name):
    """A sparse 10 GB mesh file was read whole (``lkspace info`` ran until the machine ran out of memory)."""
    with open(tmp_path / name, "wb") as fh:
        fh.truncate(10 * 2**30)
    code, _out, err = run(capsys, "info", tmp_path / name)
    assert code == 1
    one_line_error(err, name, "10,240 MiB is past the 64 MiB lkspace reads", "decimate it")


def test_a_twist_file_past_the_size_bound_is_refused(tmp_path, monkeypatch):
    from lkspace.errors import LabelError
    from lkspace.io import text
    from lkspace.io.twists import read_twist_file

    monkeypatch.setattr(text, "MAX_INPUT_BYTES", 1000)
    (tmp_path / "t.txt").write_text("1\n" * 600)
    with pytest.raises(LabelError, match="t.txt: .* MiB is past the .* MiB lkspace reads as twist input"):
        read_twist_file(lkspace.load("cube"), str(tmp_path / "t.txt"))
