"""Printable exports read back by independent libraries: trimesh (watertight, volume per strand),
manifold3d (the gap between pieces, measured exactly on the final mesh), and binary PLY."""

from __future__ import annotations

import itertools
import json
import subprocess
import zipfile

import numpy as np
import pytest

from lkspace import MeshOptions, PrintOptions, export, realize
from lkspace.errors import GeometryError
from lkspace.geometry.fabrication import printable

from .cli_calls import one_line_error, run

trimesh = pytest.importorskip("trimesh")
manifold3d = pytest.importorskip("manifold3d")


def bodies_of(path) -> list:
    mesh = trimesh.load(path, force="mesh")
    return mesh.split(only_watertight=False)


def manifolds(bodies) -> list:
    out = []
    for b in bodies:
        m = manifold3d.Manifold(
            manifold3d.Mesh(
                vert_properties=np.asarray(b.vertices, np.float32), tri_verts=np.asarray(b.faces, np.uint32)
            )
        )
        assert m.status() == manifold3d.Error.NoError  # a valid 2-manifold
        out.append(m)
    return out


def smallest_gap(bodies, search: float) -> float:
    """Exact smallest distance between distinct bodies (manifold3d), capped at ``search``."""
    return min(a.min_gap(b, search) for a, b in itertools.combinations(manifolds(bodies), 2))


def test_stl_chainmail_is_watertight_and_keeps_its_clearance(tmp_path, capsys):
    path = tmp_path / "chainmail.stl"
    code, out, err = run(
        capsys, "export", "cube", "--twist", "2", "-o", str(path), "--thickness", "0.1", "--clearance", "0.1", "--json"
    )
    assert code == 0, err
    data = json.loads(out)
    assert data["fabrication"]["pieces"] == 6 and data["fabrication"]["thickness"] == 0.1
    assert path.read_bytes()[:80].startswith(b"lkspace cube units=mm")
    bodies = bodies_of(path)
    assert len(bodies) == 6
    real = realize("cube", 2)
    for body in bodies:
        assert body.is_watertight and body.is_winding_consistent and body.volume > 0
    lengths = sorted(float(np.linalg.norm(np.diff(np.vstack([c, c[:1]]), axis=0), axis=1).sum()) for c in real.curves)
    volumes = sorted(b.volume for b in bodies)
    # a tube of radius r and length L has volume about pi r^2 L (a 16-gon: 0.974 of the circle)
    assert np.allclose(volumes, np.pi * 0.05**2 * np.array(lengths), rtol=0.05)
    assert smallest_gap(bodies, 0.12) >= 0.1 * (1 - 1e-5)


def test_clearance_that_cannot_be_met_is_refused_with_the_place(tmp_path, capsys):
    path = tmp_path / "x.stl"
    code, out, err = run(
        capsys, "export", "cube", "--twist", "2", "-o", str(path), "--thickness", "0.1", "--clearance", "0.5"
    )
    assert code == 1
    one_line_error(err, "clearance 0.5", "near ", "edge")
    assert not path.exists() and list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    "args, words",
    [
        (["--thickness", "-1"], ["--thickness", "> 0"]),
        (["--thickness", "nan"], ["--thickness"]),
        (["--clearance", "-0.1"], ["--clearance", ">= 0"]),
        (["--scale", "0"], ["--scale"]),
        (["--scale", "1e300"], ["--scale", "1e+09"]),
        (["--units", "furlong"], ["--units"]),
        (["--thickness", "1.5"], ["--thickness 1.5", "bend radius", "near "]),
        (["--thickness", "0.1", "--tube-radius", "0.1"], ["exclusive"]),
    ],
)
def test_bad_fabrication_options(tmp_path, capsys, args, words):
    code, _, err = run(capsys, "export", "tetrahedron", "--twist", "1", "-o", str(tmp_path / "t.stl"), *args)
    assert code in (1, 2)
    assert code == (1 if "bend radius" in words else 2)
    one_line_error(err, *words)
    assert list(tmp_path.iterdir()) == []


def test_python_export_refuses_the_same_way(tmp_path):
    with pytest.raises(GeometryError, match="^thickness: must be") as bad:
        export("cube", tmp_path / "c.stl", 2, options=PrintOptions(thickness=-1.0))
    assert bad.value.exit_code == 2 and bad.value.parameter == "thickness"
    with pytest.raises(GeometryError, match=r"clearance 0\.5 .* near (edge|vertex)") as far:
        export("cube", tmp_path / "c.3mf", 2, options=PrintOptions(thickness=0.1, clearance=0.5))
    assert far.value.exit_code == 1 and list(tmp_path.iterdir()) == []


def test_reported_gap_is_never_more_than_the_true_gap(tmp_path):
    real = realize("tetrahedron", 1)
    pieces = printable(real, thickness=0.1, clearance=0.0)
    assert pieces.min_gap is not None
    export(real, tmp_path / "t.stl", options=PrintOptions(pieces=pieces))
    true_gap = smallest_gap(bodies_of(tmp_path / "t.stl"), 3 * pieces.min_gap)
    assert 0 < pieces.min_gap <= true_gap + 1e-6
    with pytest.raises(GeometryError, match="leave a gap"):
        printable(real, thickness=0.1, clearance=1.05 * true_gap)  # more than there is: refused
    finer = printable(real, thickness=0.1, clearance=0.5 * pieces.min_gap).min_gap  # finer sampling: a tighter bound
    assert finer is not None and pieces.min_gap <= finer <= true_gap + 1e-6


def test_3mf_has_units_colours_and_one_object_per_strand(tmp_path):
    path = tmp_path / "b.3mf"
    proc = subprocess.run(
        [
            "lkspace",
            "export",
            "tetrahedron",
            "--twist",
            "1",
            "-o",
            str(path),
            "--units",
            "in",
            "--scale",
            "2",
            "--json",
        ],
        capture_output=True,
        text=True,
        check=False,
    )
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["fabrication"]["units"] == "in"
    model = zipfile.ZipFile(path).read("3D/3dmodel.model").decode()
    assert 'unit="inch"' in model and model.count("<object ") == 3 and model.count("displaycolor=") == 3
    pytest.importorskip("lxml")
    scene = trimesh.load(path)
    assert scene.units == "inch" and len(scene.geometry) == 3
    for body in scene.geometry.values():
        assert body.is_watertight and body.volume > 0
    # --scale 2: twice the tetrahedron's size
    extent = np.ptp(np.vstack([g.vertices for g in scene.geometry.values()]), axis=0).max()
    assert extent > 2 * np.ptp(np.vstack(realize("tetrahedron", 1).curves), axis=0).max()


def test_open_strands_get_capped_ends(tmp_path, capsys):
    path = tmp_path / "open.stl"
    code, out, err = run(capsys, "export", "tetrahedron", "--twist", "1", "--null", "0.0", "-o", str(path), "--json")
    assert code == 0, err
    fab = json.loads(out)["fabrication"]
    assert fab["open_pieces"] >= 1
    bodies = bodies_of(path)
    assert len(bodies) == fab["pieces"] and all(b.is_watertight and b.volume > 0 for b in bodies)


def test_periodic_block_prints_one_piece_per_thread_run(tmp_path, capsys):
    path = tmp_path / "weave.stl"
    code, out, err = run(
        capsys,
        "export",
        "tiling:square",
        "--twist",
        "1",
        "--block",
        "3x3",
        "-o",
        str(path),
        "--clearance",
        "0.05",
        "--json",
    )
    assert code == 0, err
    data = json.loads(out)
    bodies = bodies_of(path)
    assert len(bodies) == data["fabrication"]["pieces"] == data["curves"] >= 6
    assert all(b.is_watertight and b.volume > 0 for b in bodies)
    # the thread runs stay within the 3 x 3 cells widened by the cutting margin (and the tube)
    reach = data["normal_offset"] + 2 * data["tube_radius"] + data["fabrication"]["thickness"] / 2
    lo, hi = np.vstack([b.vertices for b in bodies]).min(0), np.vstack([b.vertices for b in bodies]).max(0)
    assert np.all(lo[:2] >= -0.5 - reach - 1e-9) and np.all(hi[:2] <= 2.5 + reach + 1e-9)
    assert np.all(hi[:2] - lo[:2] > 3)  # threads are cut at the block's faces, not short of them
    assert smallest_gap(bodies, 0.06) >= 0.05 * (1 - 1e-5)


def test_binary_ply_reads_back(tmp_path):
    real = realize("tetrahedron", 1)
    export(real, tmp_path / "t.ply", options=MeshOptions(tubes=True))
    mesh = trimesh.load(tmp_path / "t.ply")
    assert mesh.is_watertight and len(mesh.split()) == 3
    export(real, tmp_path / "p.ply")
    lines = trimesh.load(tmp_path / "p.ply")
    assert len(lines.vertices) == sum(len(c) for c in real.curves)
    head = (tmp_path / "p.ply").read_bytes()[:300]
    assert b"binary_little_endian" in head and b"element edge" in head


def test_obj_polylines_are_line_elements(tmp_path):
    real = realize("dihedron:3", 1)
    export(real, tmp_path / "t.obj")
    verts, polylines = [], []
    for line in (tmp_path / "t.obj").read_text().splitlines():
        if line.startswith("v "):
            verts.append([float(x) for x in line.split()[1:]])
        elif line.startswith("l "):
            polylines.append([int(x) - 1 for x in line.split()[1:]])
    assert len(polylines) == 1
    pts = np.array(verts)[polylines[0]]
    assert polylines[0][0] == polylines[0][-1]  # closed: back to the start
    np.testing.assert_allclose(pts[:-1], real.curves[0], atol=1e-6)
