"""Pictures: 3D renders with view, size, background and colours; 2D knot diagrams; no global state."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

import lkspace
from lkspace import PictureOptions, export, realize

from .cli_calls import one_line_error, run

plt_image = pytest.importorskip("matplotlib.image")


def test_rendering_leaves_the_callers_backend_and_pyplot_alone():
    script = (
        "import sys, tempfile, os, matplotlib\n"
        "matplotlib.use('svg')\n"
        "import lkspace\n"
        "d = tempfile.mkdtemp()\n"
        "lkspace.export('tetrahedron', os.path.join(d, 't.png'), 1)\n"
        "print(matplotlib.get_backend(), 'matplotlib.pyplot' in sys.modules)\n"
    )
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True)
    assert proc.stdout.split() == ["svg", "False"]


def test_size_background_and_colours(tmp_path, capsys):
    path = tmp_path / "t.png"
    code, _, err = run(
        capsys, "export", "tetrahedron", "--twist", "1", "-o", str(path), "--size", "320x200",
        "--background", "transparent", "--colors", "red", "--view", "top",
    )  # fmt: skip
    assert code == 0, err
    img = plt_image.imread(path)
    assert img.shape == (200, 320, 4)
    assert img[0, 0, 3] == 0  # transparent corner
    opaque = img[img[..., 3] > 0.9][:, :3]
    strands = opaque[(opaque.max(axis=1) - opaque.min(axis=1)) > 0.3]
    assert len(strands) > 500 and np.all(strands[:, 0] >= strands[:, 1])  # every strand pixel is a shade of red
    code, _, err = run(
        capsys, "export", "tetrahedron", "--twist", "1", "-o", str(path), "--size", "64", "--background", "navy"
    )
    assert code == 0, err
    img = plt_image.imread(path)
    assert img.shape[:2] == (64, 64) and np.allclose(img[0, 0, :3], [0, 0, 128 / 255], atol=0.01)


def test_views_differ(tmp_path):
    real = realize("cube", 2)
    from lkspace.formats.render import look_of

    pictures = []
    for view in ("front", "top", "30,10"):
        export(real, tmp_path / "v.png", options=PictureOptions(look=look_of(view, "96x96", None, None)))
        pictures.append(plt_image.imread(tmp_path / "v.png")[..., :3])
    assert not np.allclose(pictures[0], pictures[1]) and not np.allclose(pictures[0], pictures[2])


@pytest.mark.parametrize(
    "args, words",
    [
        (["--view", "sideways"], ["--view", "iso"]),
        (["--view", "10,95"], ["elevation"]),
        (["--size", "5x5"], ["--size", "16.."]),
        (["--size", "big"], ["--size", "WIDTHxHEIGHT"]),
        (["--background", "notacolour"], ["--background", "not a colour"]),
        (["--colors", "red,nope"], ["--colors", "'nope'"]),
    ],
)
def test_bad_picture_options(tmp_path, capsys, args, words):
    code, _, err = run(capsys, "export", "tetrahedron", "--twist", "1", "-o", str(tmp_path / "t.png"), *args)
    assert code == 2
    one_line_error(err, *words)
    assert list(tmp_path.iterdir()) == []


def test_picture_options_belong_to_pictures(tmp_path, capsys):
    code, _, err = run(capsys, "export", "tetrahedron", "--twist", "1", "-o", str(tmp_path / "t.stl"), "--diagram")
    assert code == 2
    one_line_error(err, "pictures")
    code, _, err = run(capsys, "export", "tiling:square", "--twist", "1", "-o", str(tmp_path / "t.svg"), "--diagram")
    assert code == 2
    one_line_error(err, "knot diagram needs closed strands")


@pytest.mark.parametrize(
    "mesh, twist", [("dihedron:3", "1"), ("dihedron:5", "1"), ("whitehead", None), ("book:4", "3")]
)
def test_diagram_crossings_match_identify(tmp_path, capsys, mesh, twist):
    pytest.importorskip("spherogram")
    from lkspace.formats.diagram import planar_diagram

    real = realize(mesh, None if twist is None else int(twist))
    drawn = planar_diagram(real)
    named = lkspace.identify(mesh, None if twist is None else int(twist))
    assert drawn.n_crossings == named.crossings
    assert drawn.n_components == named.components
    # every crossing cuts the under strand: two NaN breaks... one per crossing in all paths together
    assert sum(int(np.isnan(p[:, 0]).sum()) for p in drawn.paths) == drawn.n_crossings
    svg = tmp_path / "d.svg"
    design = [mesh] + (["--twist", twist] if twist else [])
    code, _, err = run(capsys, "export", *design, "--diagram", "-o", str(svg))
    assert code == 0, err
    text = svg.read_text()
    assert text.lstrip().startswith("<?xml") and text.count("<path") >= named.components


def test_diagram_png_colours_each_component(tmp_path):
    pytest.importorskip("spherogram")
    path = tmp_path / "b.png"
    proc = subprocess.run(
        [
            "lkspace",
            "export",
            "tetrahedron",
            "--twist",
            "1",
            "--diagram",
            "--size",
            "240x240",
            "-o",
            str(path),
            "--json",
        ],
        capture_output=True,
        text=True,
        check=False,
    )
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["format"] == "png"
    rgb = plt_image.imread(path)[..., :3]
    saturated = rgb[(rgb.max(axis=2) - rgb.min(axis=2)) > 0.4]
    hues = {tuple(np.round(p, 1)) for p in saturated}
    assert len(saturated) > 1000 and len(hues) >= 3  # three rings, three colours


def _lab(rgb: np.ndarray) -> np.ndarray:
    """sRGB in [0, 1] -> CIELAB (D65), written out here (no colour library)."""
    lin = np.where(rgb > 0.04045, ((rgb + 0.055) / 1.055) ** 2.4, rgb / 12.92)
    xyz = lin @ np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]]).T
    f = xyz / np.array([0.9505, 1.0, 1.089])
    f = np.where(f > 0.008856, np.cbrt(f), 7.787 * f + 16 / 116)
    return np.column_stack([116 * f[:, 1] - 16, 500 * (f[:, 0] - f[:, 1]), 200 * (f[:, 1] - f[:, 2])])


def test_default_palette_keeps_24_strands_apart_and_follows_the_strand_keys():
    from lkspace.formats.colors import PALETTE, curve_colors, strand_keys

    lab = _lab(PALETTE)
    gaps = np.linalg.norm(lab[:, None] - lab[None], axis=2) + np.eye(len(lab)) * 1e9
    assert len(PALETTE) >= 24 and gaps.min() > 30  # clearly different colours, pairwise
    assert np.all((lab[:, 0] > 20) & (lab[:, 0] < 85))  # none vanishes on white or black
    real = realize("cube", 2)  # six face loops: each strand's key is the face it runs in
    keys = strand_keys(real)
    faces = lkspace.load("cube").corner_face
    tr = real.trace
    for k in range(tr.components):
        steps = tr.steps[tr.strand_starts[k] : tr.strand_starts[k + 1]]
        assert keys[k] == min(int(faces[p // 2]) for p in steps)
    assert sorted(keys.tolist()) == list(range(6))
    # colours go by the keys' order, whatever the strands' numbering
    np.testing.assert_array_equal(curve_colors(real), PALETTE[keys[real.strand_of]])
