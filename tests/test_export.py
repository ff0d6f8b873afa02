"""Exports opened by independent readers (trimesh, pygltflib, matplotlib); CLI and catalog rows."""

from __future__ import annotations

import json
import os
import time

import numpy as np
import pytest

import lkspace
from lkspace import GlbOptions, MeshOptions, export, realize
from lkspace.cli import main
from lkspace.errors import ExportError
from lkspace.formats.glb import glb_bytes
from lkspace.formats.tubes import tube

from .cli_calls import one_line_error, run

trimesh = pytest.importorskip("trimesh")


@pytest.fixture(scope="module")
def borromean():
    return realize(lkspace.load("tetrahedron"), 1)


def test_obj_polylines(tmp_path, borromean):
    path = tmp_path / "b.obj"
    export(borromean, path)
    lines = path.read_text().splitlines()
    polylines = [ln for ln in lines if ln.startswith("l ")]
    assert len(polylines) == 3
    n_vertices = sum(ln.startswith("v ") for ln in lines)
    assert n_vertices == sum(len(c) for c in borromean.curves)
    first = polylines[0].split()[1:]
    assert first[0] == first[-1]  # closed polyline returns to its start


def test_obj_tubes_open_in_trimesh(tmp_path, borromean):
    path = tmp_path / "b.obj"
    export(borromean, path, options=MeshOptions(tubes=True))
    mesh = trimesh.load(path, force="mesh")
    bodies = mesh.split(only_watertight=False)
    assert len(bodies) == 3 and all(b.is_watertight for b in bodies)
    assert path.read_text().count("\no strand_") == 3


def test_ply_tubes_and_polylines(tmp_path, borromean):
    path = tmp_path / "b.ply"
    export(borromean, path, options=MeshOptions(tubes=True))
    mesh = trimesh.load(path)
    assert mesh.is_watertight and mesh.volume > 0
    colours = np.unique(mesh.visual.vertex_colors[:, :3], axis=0)
    assert len(colours) == 3
    export(borromean, tmp_path / "p.ply")
    head = (tmp_path / "p.ply").read_bytes()[:400]
    assert b"format binary_little_endian 1.0" in head
    assert f"element edge {sum(len(c) for c in borromean.curves)}".encode() in head


def test_glb_opens_in_trimesh_and_pygltflib(tmp_path, borromean):
    pygltflib = pytest.importorskip("pygltflib")
    path = tmp_path / "b.glb"
    export(borromean, path)
    scene = trimesh.load(path)
    assert len(scene.geometry) == 3
    assert all(g.is_watertight for g in scene.geometry.values())
    gltf = pygltflib.GLTF2().load(str(path))
    assert len(gltf.meshes) == len(gltf.nodes) == len(gltf.materials) == 3
    colours = {tuple(m.pbrMetallicRoughness.baseColorFactor) for m in gltf.materials}
    assert len(colours) == 3
    assert len(gltf.binary_blob()) == gltf.buffers[0].byteLength
    assert glb_bytes(borromean, GlbOptions())[:4] == b"glTF"


def test_png_is_a_clear_picture(tmp_path, borromean):
    plt = pytest.importorskip("matplotlib.pyplot")
    path = tmp_path / "b.png"
    export(borromean, path)
    img = plt.imread(path)
    assert img.shape[0] >= 600 and img.shape[1] >= 600
    rgb = img[..., :3]
    saturated = (rgb.max(axis=2) - rgb.min(axis=2)) > 0.4
    assert saturated.mean() > 0.02  # tubes cover a visible part of the image
    hues = {tuple(np.round(p, 1)) for p in rgb[saturated][::50]}
    assert len(hues) >= 3


def test_tube_of_an_open_polyline_is_capped():
    pts = np.column_stack([np.linspace(0, 1, 20), np.zeros(20), np.zeros(20)])
    v, n, f = tube(pts, False, 0.1, sides=8)
    mesh = trimesh.Trimesh(v, f)
    assert mesh.is_watertight and mesh.volume == pytest.approx(np.pi * 0.01 * 1, rel=0.1)


def test_every_writer_has_its_format_name():
    from typing import get_args

    from lkspace.formats.registry import ENCODERS, OPTIONS, Format

    assert sorted(get_args(Format)) == sorted(ext[1:] for ext in ENCODERS) == sorted(ext[1:] for ext in OPTIONS)


def test_bad_extension_writes_nothing(tmp_path, borromean):
    with pytest.raises(ExportError, match="unknown output format"):
        export(borromean, tmp_path / "x.xyz")
    assert os.listdir(tmp_path) == []


def test_failed_write_leaves_the_old_file(tmp_path, borromean, monkeypatch):
    path = tmp_path / "b.obj"
    path.write_text("old")
    import lkspace.formats.obj as ex

    def boom(*a, **k):
        raise RuntimeError("disk full")

    monkeypatch.setattr(ex, "tube_meshes", boom)
    with pytest.raises(RuntimeError):
        export(borromean, path, options=MeshOptions(tubes=True))
    assert path.read_text() == "old" and os.listdir(tmp_path) == ["b.obj"]


def test_cli_export_json(tmp_path, capsys):
    out_path = tmp_path / "t.glb"
    code, out, err = run(capsys, "export", "dihedron:3", "--twist", "1", "-o", str(out_path), "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data["written"] == str(out_path) and data["format"] == "glb" and data["components"] == 1
    assert data["min_distance"] > data["min_separation"]
    assert out_path.exists()


def test_cli_export_errors_are_one_line(tmp_path, capsys):
    code, _, err = run(capsys, "export", "book:6", "--twist", "1", "--radius", "0.6", "-o", str(tmp_path / "x.obj"))
    assert code == 1 and err.count("\n") == 1 and "self-intersect" in err
    assert not (tmp_path / "x.obj").exists()
    code, _, err = run(capsys, "export", "cube", "--twist", "1,2", "-o", str(tmp_path / "x.obj"))
    assert code == 2 and err.count("\n") == 1


def write_catalog(capsys, path):
    """The real catalog ``enumerate`` writes: dihedron:3 with labels {0, 2}, 4 designs."""
    code, _, err = run(capsys, "enumerate", "dihedron:3", "--labels", "0,2", "-o", str(path), "--json")
    assert code == 0, err
    return lkspace.read_catalog(path)


def test_cli_export_catalog_row(tmp_path, capsys):
    cat = tmp_path / "designs.parquet"
    catalog = write_catalog(capsys, cat)
    row = int(np.flatnonzero((catalog.labels == 2).all(axis=1))[0])
    out_path = tmp_path / "row.obj"
    code, out, err = run(capsys, "export", str(cat), "--row", str(row), "-o", str(out_path), "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data["labels"] == [2, 2, 2] and data["row"] == row and data["scaffold"] == "dihedron:3"
    assert data["components"] == 2  # T(2, 6)
    assert out_path.read_text().count("\nl ") == 2


def test_cli_catalog_with_nested_metadata(tmp_path, capsys):
    import pyarrow as pa
    import pyarrow.parquet as pq

    from lkspace.catalog.schema import design_schema

    cat = tmp_path / "c.parquet"
    row = {"labels": [[1, 1, 1, 1, 0]], "key": [bytes([1, 1, 1, 1, 0])], "components": [1], "orbit_size": [1],
           "holds_together": [True], "n_zero": [1], "n_odd": [4], "n_even": [1], "abs_sum": [4], "abs_max": [1],
           "residue_class": [0], "strand_lengths": [[10]]}  # fmt: skip
    table = pa.table(row, schema=design_schema(5, False))
    scaffold = {"name": "figure-eight", "content_hash": lkspace.load("figure-eight").content_hash(), "edges": 5}
    meta = {"format_version": 1, "scaffold": scaffold, "label_set": [0, 1], "mode": "designs", "rows": 1}
    pq.write_table(table.replace_schema_metadata({"lkspace": json.dumps(meta)}), cat)  # the scaffold by name only
    code, out, err = run(capsys, "export", str(cat), "--row", "0", "-o", str(tmp_path / "f.ply"), "--json")
    assert code == 0, err
    assert json.loads(out)["components"] == 1


@pytest.mark.parametrize(
    "args, message",
    [
        (["--row", "4"], "row 4 out of range 0..3"),
        ([], "give --row"),
        (["--row", "0", "--twist", "1"], "exclusive"),
    ],
)
def test_cli_catalog_errors(tmp_path, capsys, args, message):
    cat = tmp_path / "designs.parquet"
    write_catalog(capsys, cat)
    code, _, err = run(capsys, "export", str(cat), *args, "-o", str(tmp_path / "x.obj"))
    assert code == 2 and message in err and err.count("\n") == 1


def test_cli_catalog_without_metadata(tmp_path, capsys):
    import pyarrow as pa
    import pyarrow.parquet as pq

    cat = tmp_path / "plain.parquet"
    pq.write_table(pa.table({"labels": [[1, 1, 1]]}), cat)
    code, _, err = run(capsys, "export", str(cat), "--row", "0", "-o", str(tmp_path / "x.obj"))
    assert code == 1 and "not an lkspace catalog" in err


def test_cli_export_periodic_block(tmp_path, capsys):
    from lkspace import io
    from tests.test_geometry import square_torus

    mesh = tmp_path / "sq.json"
    io.write(square_torus(), mesh)
    code, out, err = run(
        capsys, "export", str(mesh), "--twist", "1", "--block", "3x3", "-o", str(tmp_path / "w.glb"), "--json"
    )
    assert code == 0, err
    data = json.loads(out)
    assert data["components"] == 2 and data["block"] == [3, 3]
    # two diagonal thread families cut to the 3 x 3 block: runs of length 1..3 cells, 5 per direction at most
    assert 6 <= data["curves"] <= 12
    code, _, err = run(capsys, "export", "cube", "--twist", "1", "--block", "3x3", "-o", str(tmp_path / "c.glb"))
    assert code == 2 and "not periodic" in err
    code, _, err = run(capsys, "export", str(mesh), "--twist", "1", "--block", "3x3x3", "-o", str(tmp_path / "c.glb"))
    assert code == 2 and "2 positive sizes" in err


# --- bounds, numbers and output paths (the budgets issue) ----------------------------------


@pytest.mark.parametrize(
    "args, words",
    [
        (["--tube-radius", "nan", "--tubes"], ["--tube-radius", "finite"]),
        (["--tube-radius", "-1", "--tubes"], ["--tube-radius", "> 0"]),
        (["--normal-offset", "nan"], ["--normal-offset"]),
        (["--normal-offset", "-0.1"], ["--normal-offset", ">= 0"]),
        (["--radius", "inf"], ["--radius"]),
        (["--radius", "abc"], ["--radius", "not a number"]),
        (["--radius", "1e300"], ["--radius: 1e+300 exceeds", "shortest edge"]),
        (["--normal-offset", "1e300"], ["--normal-offset: 1e+300 exceeds", "shortest edge"]),
        (["--tube-radius", "1e300", "--tubes"], ["--tube-radius: 1e+300 exceeds", "shortest edge"]),
    ],
)
def test_export_float_options_are_checked(tmp_path, capsys, args, words):
    out_path = tmp_path / "x.obj"
    code, _, err = run(capsys, "export", "dihedron:3", "--twist", "1", *args, "-o", str(out_path))
    assert code == 2
    one_line_error(err, *words)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    "name, words",
    [
        ("x.stp", ["unknown output format '.stp'", ".obj", ".3mf"]),
        ("noext", ["unknown output format"]),
        ("", ["empty"]),
        ("missing/x.obj", ["does not exist"]),
        ("folder.obj/", ["folder"]),
    ],
)
def test_export_output_paths(tmp_path, capsys, name, words):
    target = f"{tmp_path}/{name}" if name else ""
    code, _, err = run(capsys, "export", "dihedron:3", "--twist", "1", "-o", target)
    assert code == 2
    one_line_error(err, *words)
    assert list(tmp_path.iterdir()) == []


def test_export_refuses_devices_and_fifos(tmp_path, capsys):
    code, _, err = run(capsys, "export", "dihedron:3", "--twist", "1", "-o", "/dev/null")
    assert code == 2
    one_line_error(err, "/dev/null")
    fifo = tmp_path / "pipe.obj"
    os.mkfifo(fifo)
    code, _, err = run(capsys, "export", "dihedron:3", "--twist", "1", "-o", str(fifo))
    assert code == 2
    one_line_error(err, "FIFO")


def test_export_refuses_a_symlink_and_leaves_nothing_on_failure(tmp_path, capsys):
    real = tmp_path / "real.obj"
    link = tmp_path / "link.obj"
    code, _, err = run(capsys, "export", "dihedron:3", "--twist", "1", "-o", str(real))
    assert code == 0, err
    link.symlink_to(real)
    before = real.read_text()
    code, _, err = run(capsys, "export", "dihedron:3", "--twist", "1", "-o", str(link))
    assert code == 2
    one_line_error(err, "symbolic link")
    assert link.is_symlink() and real.read_text() == before
    code, _, err = run(capsys, "export", "dihedron:3", "--twist", "3000", "-o", str(real))
    assert code == 1
    one_line_error(err, "twist 3000", "self-intersect")
    assert real.read_text() == before and sorted(p.name for p in tmp_path.iterdir()) == ["link.obj", "real.obj"]


def test_export_huge_twist_and_block_are_refused_quickly(capsys, tmp_path):
    cpu = time.process_time()  # CPU seconds, whatever the load
    code, _, err = run(capsys, "export", "dihedron:3", "--twist", "100000", "-o", str(tmp_path / "x.obj"))
    assert code == 1
    one_line_error(err, "winds its strands")
    code, _, err = run(
        capsys, "export", "honeycomb:cP", "--twist", "1", "--block", "100x100x100", "-o", str(tmp_path / "x.obj")
    )
    assert code == 2
    one_line_error(err, "1,000,000 copies", "MAX_BLOCK_COPIES")
    assert time.process_time() - cpu < 10


@pytest.mark.parametrize("command", ["export", "identify"])
def test_extreme_int64_twists_are_refused(tmp_path, capsys, command):
    if command == "identify":
        pytest.importorskip("spherogram")
    output = ["-o", str(tmp_path / "x.obj")] if command == "export" else []
    for twist in (str(-(2**63)), str(2**62), str(2**63 - 1)):
        code, _, err = run(capsys, command, "dihedron:3", f"--twist={twist}", *output)
        assert code in (1, 2)  # export: the geometry cannot embed (1); identify: too large (2)
        one_line_error(err, "twist")
    assert list(tmp_path.iterdir()) == []


def test_realize_and_export_library_bounds(tmp_path):
    from lkspace import GeometryParams, RealizeOptions
    from lkspace.errors import ExportError, GeometryError, LabelError, TooLargeError

    with pytest.raises(TooLargeError, match="^max_points: the curves of cube would have about ") as bound:
        realize("cube", 1, options=RealizeOptions(max_points=100))
    assert bound.value.parameter == "max_points"
    unchecked = RealizeOptions(embedding="measure")
    with pytest.raises(TooLargeError, match="^max_points: "):
        realize("dihedron:3", -(2**62), options=unchecked)
    with pytest.raises(LabelError, match="2\\*\\*63 - 1"):
        realize("dihedron:3", -(2**63), options=unchecked)
    with pytest.raises(GeometryError, match="radius") as info:
        realize("cube", 1, params=GeometryParams(radius=float("nan")))
    assert info.value.exit_code == 2
    with pytest.raises(GeometryError, match="samples_per_turn"):
        realize("cube", 1, params=GeometryParams(samples_per_turn=0))
    with pytest.raises(ExportError, match="tube radius"):
        export("cube", tmp_path / "c.obj", 1, options=MeshOptions(tubes=True, radius=float("nan")))
    with pytest.raises(ExportError, match="shortest edge"):
        export("cube", tmp_path / "c.obj", 1, options=MeshOptions(tubes=True, radius=1e300))
    assert list(tmp_path.iterdir()) == []


@pytest.fixture(scope="module")
def catalogs(tmp_path_factory):
    """The same catalog written by the real ``enumerate``: one Parquet file and a sharded folder."""
    root = tmp_path_factory.mktemp("catalogs")
    paths = {}
    for kind, extra in (("single", ["--shards", "1"]), ("sharded", ["--shards", "3", "--jobs", "2"])):
        path = root / ("cube.parquet" if kind == "single" else "cube-parts")
        code = main(["enumerate", "cube", "--labels", "-1..1", "-o", str(path), *extra, "--json"])
        assert code == 0
        paths[kind] = path
    return paths


@pytest.mark.parametrize("kind", ["single", "sharded"])
def test_export_row_reads_one_row_group(catalogs, kind, capsys, tmp_path, monkeypatch):
    from lkspace.catalog import reader

    path = catalogs[kind]
    catalog = lkspace.read_catalog(path)
    if kind == "sharded":
        assert path.is_dir() and len(list(path.glob("*.parquet"))) == 3
    capsys.readouterr()

    def whole_catalog(*args, **kwargs):
        raise AssertionError("export --row must not read the whole catalog")

    monkeypatch.setattr(reader, "read_catalog", whole_catalog)
    for row in (0, len(catalog) // 2, len(catalog) - 1):
        code, out, err = run(capsys, "export", str(path), "--row", str(row), "-o", str(tmp_path / "r.obj"), "--json")
        assert code == 0, err
        data = json.loads(out)
        assert data["labels"] == catalog.labels[row].tolist() and data["row"] == row
    code, _, err = run(capsys, "export", str(path), "--row", str(len(catalog)), "-o", str(tmp_path / "r.obj"))
    assert code == 2
    one_line_error(err, f"out of range 0..{len(catalog) - 1}")


def test_identify_catalog_row(catalogs, capsys):
    pytest.importorskip("spherogram")
    catalog = lkspace.read_catalog(catalogs["sharded"])
    row = len(catalog) - 1
    code, out, err = run(capsys, "identify", str(catalogs["sharded"]), "--row", str(row), "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data["labels"] == catalog.labels[row].tolist() and data["status"].startswith(("identified", "unknown: "))
    assert data["components"] == catalog.frame["components"][row]


def test_export_row_of_an_empty_catalog(tmp_path, capsys):
    path = tmp_path / "empty.parquet"
    code, _, err = run(capsys, "enumerate", "cube", "--labels", "0,1", "--components", "7", "-o", str(path), "--json")
    assert code == 0, err
    code, _, err = run(capsys, "export", str(path), "--row", "0", "-o", str(tmp_path / "x.obj"))
    assert code == 2
    one_line_error(err, "no rows")
    assert not (tmp_path / "x.obj").exists()


def test_a_record_of_another_format_is_refused_in_one_line(tmp_path, borromean):
    from lkspace import PictureOptions, PrintOptions

    with pytest.raises(ExportError, match=r"^options: \.obj takes MeshOptions \(radius, .*\), not PrintOptions$"):
        export(borromean, tmp_path / "b.obj", options=PrintOptions(thickness=0.1))
    with pytest.raises(ExportError, match=r"^options: \.stl takes PrintOptions .*, not PictureOptions$") as info:
        export(borromean, tmp_path / "b.stl", options=PictureOptions(title="x"))
    assert info.value.parameter == "options" and info.value.exit_code == 2
    with pytest.raises(ExportError, match="^clearance: polylines have no tubes"):
        MeshOptions(clearance=0.1)
    with pytest.raises(ExportError, match="^sides: must be an integer in 3..256, got 2"):
        GlbOptions(sides=2)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("ext", [".obj", ".ply", ".glb", ".stl", ".png"])
def test_the_file_holds_the_encoders_bytes(tmp_path, borromean, ext):
    if ext == ".png":
        pytest.importorskip("matplotlib")
    from lkspace.formats.registry import OPTIONS, encoder

    options = OPTIONS[ext]()
    export(borromean, tmp_path / f"b{ext}", options=options)
    assert (tmp_path / f"b{ext}").read_bytes() == encoder(ext)(borromean, options)
    assert os.listdir(tmp_path) == [f"b{ext}"]  # no temporary file left
