"""Welding: vertices closer than a tolerance merged, through the library and the CLI."""

from __future__ import annotations

import json
import time

import numpy as np
import pytest

import lkspace
from lkspace.errors import LkspaceWarning, ScaffoldError
from lkspace.io.weld import DEFAULT_WELD, default_tolerance, weld

from .cli_calls import run


def split_obj(scaffold: lkspace.Scaffold, jitter: float = 0.0, seed: int = 0) -> str:
    """OBJ text of ``scaffold`` with one vertex copy per face (as modelling tools export)."""
    rng = np.random.default_rng(seed)
    lines, n = [], 0
    for face in scaffold.faces():
        for v in face:
            x, y, z = (scaffold.vertices[v] + jitter * rng.uniform(-1, 1, 3)).tolist()
            lines.append(f"v {x!r} {y!r} {z!r}")
        lines.append("f " + " ".join(str(n + k + 1) for k in range(len(face))))
        n += len(face)
    return "\n".join(lines) + "\n"


def test_weld_merges_copies_in_first_copy_order():
    cube = lkspace.load("cube")
    vertices = np.concatenate([cube.vertices[f] for f in cube.faces()])
    starts = np.cumsum([0] + [len(f) for f in cube.faces()])
    faces = [list(range(s, s + len(f))) for s, f in zip(starts, cube.faces())]
    points, welded = weld((vertices, faces))
    assert len(points) == 8 and len(welded) == 6
    again = lkspace.Scaffold.from_faces(points, welded)
    assert again.n_edges == 12 and set(again.edge_degrees.tolist()) == {2}
    assert lkspace.trace(again, 1).components == lkspace.trace(cube, 1).components


def test_weld_a_scaffold_and_the_default_tolerance():
    cube = lkspace.load("cube")
    assert default_tolerance(cube.vertices) == pytest.approx(DEFAULT_WELD * np.sqrt(12))
    assert weld(cube).n_vertices == 8  # nothing to merge
    with pytest.raises(ScaffoldError, match="only finite scaffolds"):
        weld(lkspace.load("figure-eight"))  # carries labels


def test_a_face_that_collapses_is_named():
    v = [[0, 0, 0], [1, 0, 0], [1, 1e-9, 0], [0, 1, 0]]
    with pytest.raises(ScaffoldError, match="face 0 collapses"):
        weld((v, [[0, 1, 2, 3]]), 1e-6)


def test_weld_is_fast_on_a_large_mesh():
    from lkspace.scaffolds.spheres import geodesic_sphere

    sphere = geodesic_sphere(5)  # 20480 triangles, 61440 vertex copies
    vertices = np.concatenate([sphere.vertices[f] for f in sphere.faces()])
    faces = np.arange(len(vertices)).reshape(-1, 3).tolist()
    start = time.process_time()  # CPU seconds, whatever the load
    points, welded = weld((vertices, faces))
    assert time.process_time() - start < 5
    assert len(points) == sphere.n_vertices and len(welded) == sphere.n_faces


def test_cli_warns_without_weld_and_joins_with_it(capsys, tmp_path):
    path = tmp_path / "split.obj"
    path.write_text(split_obj(lkspace.load("tetrahedron"), jitter=1e-9))
    code, out, err = run(capsys, "trace", str(path), "--twist", "1", "--json")
    assert code == 0 and json.loads(out)["components"] == 4
    assert err.startswith("lkspace: warning: split.obj: its 4 faces share no edge") and "load it with --weld" in err
    with pytest.warns(LkspaceWarning, match="load it with `weld`$"):  # Python names the parameter of load
        lkspace.load(path)
    code, out, err = run(capsys, "trace", str(path), "--twist", "1", "--weld", "--json")
    data = json.loads(out)
    assert code == 0 and err == "" and data["components"] == 3 and data["welded"]["vertices"] == 4
    code, out, err = run(capsys, "info", str(path), "--weld=1e-3", "--json")
    assert code == 0 and json.loads(out)["n_edges"] == 6
    code, out, err = run(capsys, "info", str(path), "--weld", "1e-12", "--json")  # too small to merge
    assert code == 0 and json.loads(out)["n_edges"] == 12


def test_scaffold_converts_a_welded_obj(capsys, tmp_path):
    path = tmp_path / "split.obj"
    path.write_text(split_obj(lkspace.load("cube")))
    out_json = tmp_path / "cube.json"
    code, out, err = run(capsys, "scaffold", str(path), "--weld", "-o", str(out_json), "--json")
    assert code == 0, err
    assert json.loads(out)["vertices"] == 8
    back = lkspace.load(str(out_json))
    assert back.n_edges == 12 and lkspace.trace(back, 1).components == 4


@pytest.mark.parametrize(
    "args, code, message",
    [
        (["info", "cube", "--weld"], 2, "built-in scaffold, not a file"),
        (["info", "{obj}", "--weld=x"], 2, "TOL must be a number"),
        (["info", "{obj}", "--weld=nan"], 2, "finite number >= 0"),
        (["info", "{obj}", "--weld=0.5"], 1, "face 0 collapses"),
    ],
)
def test_weld_errors(capsys, tmp_path, args, code, message):
    path = tmp_path / "tri.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 0.1 0\nf 1 2 3\n")
    got, out, err = run(capsys, *[a.format(obj=path) for a in args], "--json")
    assert got == code and err.count("\n") == 1 and message in err
    assert json.loads(out)["error"]["exit_code"] == code


def test_weld_on_export_and_identify(tmp_path, capsys):
    """Every command that takes MESH takes --weld, export and identify included."""
    from lkspace.cli import main

    src = tmp_path / "u.obj"
    corners = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    lines = [f"v {' '.join(map(str, corners[i]))}" for f in faces for i in f]
    lines += ["f " + " ".join(str(4 * k + j + 1) for j in range(4)) for k in range(6)]
    src.write_text("\n".join(lines) + "\n")
    out = tmp_path / "w.obj"
    assert main(["export", str(src), "--weld", "--twist", "1", "-o", str(out), "--json"]) == 0
    assert json.loads(capsys.readouterr()[0])["components"] == 4
    assert out.exists()
