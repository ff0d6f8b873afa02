"""Pictures that read: SVG line art with over/under gaps, a colour per strand, framing on the strands."""

from __future__ import annotations

import colorsys
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from .cli_calls import run

plt_image = pytest.importorskip("matplotlib.image")

SVG = "{http://www.w3.org/2000/svg}"
MAX_SVG_BYTES = 300_000
"""Line art of the cube, dodecahedron and a 3x3 chainmail stays under this (the tube triangles took 3-16 MB)."""


def polyline(d: str) -> np.ndarray:
    """Points of a path ``M x y l dx dy ...`` (an optional ``z``), read back independently of the writer."""
    head, _, rest = d.rstrip("z").partition("l")
    numbers = [float(x) for x in re.findall(r"-?[0-9.]+(?:e-?[0-9]+)?", head)]
    start = np.array(numbers[:2])
    steps = np.array([float(x) for x in rest.split()]).reshape(-1, 2) if rest.strip() else np.zeros((0, 2))
    return np.vstack([start, start + np.cumsum(steps, axis=0)])


def strands(path) -> tuple[ET.Element, list[ET.Element]]:
    """The parsed SVG and its ``<g class="strand">`` groups."""
    root = ET.parse(path).getroot()
    return root, [g for g in root.iter(f"{SVG}g") if g.get("class") == "strand"]


def export_svg(capsys, tmp_path, *design: str) -> tuple[ET.Element, list[ET.Element], int]:
    path = tmp_path / "x.svg"
    code, _, err = run(capsys, "export", *design, "-o", str(path))
    assert code == 0, err
    root, groups = strands(path)
    return root, groups, path.stat().st_size


@pytest.mark.parametrize(
    "design, components",
    [(["cube", "--twist", "1"], 4), (["dodecahedron", "--twist", "1"], 6), (["tetrahedron", "--twist", "1"], 3)],
)
def test_svg_is_line_art_a_group_and_colour_per_component(capsys, tmp_path, design, components):
    root, groups, size = export_svg(capsys, tmp_path, *design)
    assert size < MAX_SVG_BYTES
    assert not list(root.iter(f"{SVG}polygon")) and not list(root.iter(f"{SVG}image"))  # no triangle soup
    assert len(groups) == components
    assert len({g.get("stroke") for g in groups}) == components  # distinct colours
    assert all(len(g.findall(f"{SVG}path")) >= 1 for g in groups)


def test_trefoil_passes_under_itself_at_gaps_beside_the_over_strand(capsys, tmp_path):
    root, groups, _ = export_svg(capsys, tmp_path, "dihedron:3", "--twist", "1", "--no-mesh")
    assert len(groups) == 1
    pieces = [polyline(p.get("d")) for p in groups[0].findall(f"{SVG}path")]
    assert len(pieces) >= 3  # a knotted diagram passes under at least three times
    stroke = float(groups[0].get("stroke-width"))
    for k, piece in enumerate(pieces):  # each cut lies beside another stretch that passes over it
        others = np.vstack([p for m, p in enumerate(pieces) if m != k] + [piece[len(piece) // 4 : -len(piece) // 4]])
        for end in (piece[0], piece[-1]):
            assert np.linalg.norm(others - end, axis=1).min() < 3 * stroke
    width, height = float(root.get("width")), float(root.get("height"))
    every = np.vstack(pieces)
    assert every.min() > 0 and every[:, 0].max() < width and every[:, 1].max() < height


def test_chainmail_block_is_small_line_art_neighbouring_rings_apart(capsys, tmp_path):
    root, groups, size = export_svg(capsys, tmp_path, "tiling:square", "--twist", "2", "--block", "3x3")
    assert size < MAX_SVG_BYTES and len(groups) == 9 and len({g.get("data-strand") for g in groups}) == 1
    cells = [np.array(g.get("data-cell").split(","), int) for g in groups]
    assert len({tuple(c) for c in cells}) == 9  # one ring a cell, each its own component
    for a in range(9):
        for b in range(a):  # rings in neighbouring cells (a side or a corner apart) differ
            if np.abs(cells[a] - cells[b]).max() == 1:
                assert groups[a].get("stroke") != groups[b].get("stroke")
    assert len({g.get("stroke") for g in groups}) == 4  # four tones of the one ring class, repeating
    scaffold = [g for g in root.iter(f"{SVG}g") if g.get("class") == "scaffold"]
    assert len(scaffold) == 1 and float(scaffold[0].get("fill-opacity")) < 0.2  # drawn faintly


def test_weave_block_is_line_art_one_colour_per_thread_class(capsys, tmp_path):
    _, groups, _ = export_svg(capsys, tmp_path, "tiling:square", "--twist", "1", "--block", "3x3")
    colour: dict[str | None, str | None] = {}
    for g in groups:  # every run of a thread, in whichever cell, has its class's colour
        assert colour.setdefault(g.get("data-strand"), g.get("stroke")) == g.get("stroke")
    assert len(groups) > len(colour) == len(set(colour.values())) == 2  # two thread classes, two colours


def test_gradient_is_an_option(capsys, tmp_path):
    path = tmp_path / "g.svg"
    code, _, err = run(capsys, "export", "dihedron:3", "--twist", "1", "--colors", "gradient", "-o", str(path))
    assert code == 0, err
    _, groups = strands(path)
    assert len(groups) == 1 and len({p.get("stroke") for p in groups[0].findall(f"{SVG}path")}) > 20


def test_png_one_hue_per_knot_framed_on_the_strands(capsys, tmp_path):
    path = tmp_path / "t.png"
    design = ["dihedron:3", "--twist", "1", "--no-mesh"]
    code, _, err = run(capsys, "export", *design, "--size", "240x200", "-o", str(path))
    assert code == 0, err
    rgb = plt_image.imread(path)[..., :3]
    strand = rgb.min(axis=2) < 0.85  # on white, with no scaffold: the tubes, rims included
    saturated = rgb[(rgb.max(axis=2) - rgb.min(axis=2)) > 0.3]
    hues = np.array([colorsys.rgb_to_hsv(*p)[0] for p in saturated[::7]])
    spread = np.minimum(np.abs(hues - np.median(hues)), 1 - np.abs(hues - np.median(hues)))
    assert np.quantile(spread, 0.95) < 0.05  # one colour, not a rainbow
    rows, cols = np.flatnonzero(strand.any(axis=1)), np.flatnonzero(strand.any(axis=0))
    margins = np.array([[rows[0], 199 - rows[-1]], [cols[0], 239 - cols[-1]]])
    assert margins.min(axis=1).min() <= 0.06 * 200  # the strands reach near the border on one axis
    assert np.all(np.abs(margins[:, 0] - margins[:, 1]) <= 4)  # and sit in the middle


@pytest.mark.parametrize("near", [0, 1])
def test_the_strand_farther_from_the_eye_is_cut(near):
    from lkspace.formats.lineart import crossings

    across = np.column_stack([np.arange(11.0), np.full(11, 5.0)])  # y = 5, x = 0..10
    down = np.column_stack([np.full(11, 5.5), np.arange(11.0)])  # x = 5.5, y = 0..10
    depth = [np.full(11, 1.0 if near == k else 0.0) for k in range(2)]
    found = crossings([across, down], depth, np.array([False, False]), 3.0)
    far = 1 - near
    assert [(k, round(at, 6), round(sine, 6)) for k, at, sine in found] == [(far, 5.5 if far == 0 else 5.0, 1.0)]


@pytest.mark.parametrize("mesh", ["tetrahedron", "octahedron"])
def test_default_view_looks_down_a_rotation_axis_of_the_scaffold(mesh):
    import lkspace
    from lkspace.formats.render import Look
    from lkspace.formats.view import direction, view_angles

    real = lkspace.realize(mesh, 1)
    view = direction(*view_angles(real, Look(), real.tube_radius))
    # the tetrahedron's 3-fold and the octahedron's 4-fold axes run through their vertices
    axes = real.scaffold.vertices - real.scaffold.vertices.mean(axis=0)
    cosines = np.abs(axes @ view) / np.linalg.norm(axes, axis=1)
    assert cosines.max() > 0.999


def test_title_is_drawn_above_the_strands(capsys, tmp_path):
    path = tmp_path / "t.png"
    code, _, err = run(capsys, "export", "dihedron:3", "--twist", "1", "--no-mesh", "--title", "Trefoil", "--size", "240x200", "-o", str(path))  # fmt: skip
    assert code == 0, err
    rgb = plt_image.imread(path)[..., :3]
    coloured = np.flatnonzero(((rgb.max(axis=2) - rgb.min(axis=2)) > 0.3).any(axis=1))
    text = np.flatnonzero(((rgb.max(axis=2) < 0.5) & (rgb.max(axis=2) - rgb.min(axis=2) < 0.1)).any(axis=1))
    assert len(text) and text.max() < coloured.min()  # grey text rows, all above the strands
    svg = tmp_path / "t.svg"
    code, _, err = run(capsys, "export", "dihedron:3", "--twist", "1", "--title", "a < b", "-o", str(svg))
    assert code == 0, err
    titles = [t for t in ET.parse(svg).getroot().iter(f"{SVG}text") if t.get("class") == "title"]
    assert [t.text for t in titles] == ["a < b"]
