"""Colours that read in a periodic block, through ``python -m lkspace export``: neighbouring rings of a chainmail
differ, an infinite thread keeps one colour across the cells.

Everything is measured from the written files (PLY polylines, GLB meshes, PNG pixels) with code of its own.
"""

from __future__ import annotations

import colorsys
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from lkspace.formats.colors import PALETTE

from .test_geometry import gauss_linking
from .test_periodic_relax import export, read_ply_edges


def ply_curves(path) -> list[tuple[np.ndarray, bool, tuple[int, ...]]]:
    """The polylines of a PLY of edges: ``(points (n, 3), closed, colour)`` each, read from its bytes."""
    raw = path.read_bytes()
    end = raw.index(b"end_header\n") + len(b"end_header\n")
    nv = int(next(h for h in raw[:end].decode().splitlines() if h.startswith("element vertex")).split()[-1])
    xyz = np.frombuffer(raw, np.dtype([("p", "<f4", 3), ("c", "u1", 3)]), nv, end)["p"].astype(np.float64)
    colours, edges = read_ply_edges(path)
    graph = coo_matrix((np.ones(len(edges)), (edges[:, 0], edges[:, 1])), shape=(nv, nv))
    n, label = connected_components(graph, directed=False)
    out = []
    for k in range(n):
        vertices = np.flatnonzero(label == k)  # a curve's vertices are written in order
        closed = int(np.isin(edges[:, 0], vertices).sum()) == len(vertices)  # an edge from each: the loop closes
        assert len({tuple(c) for c in colours[vertices].tolist()}) == 1  # one colour a curve
        out.append((xyz[vertices], closed, tuple(colours[vertices[0]].tolist())))
    return out


# every ring links its neighbours across the cells' sides: 24 pairs on 4x4 squares, 33 on a 4x4 rhombus of hexagons
@pytest.mark.parametrize("scaffold, pairs", [("tiling:square", 24), ("tiling:hexagonal", 33)])
def test_linked_rings_of_a_chainmail_block_differ_in_the_ply(tmp_path, scaffold, pairs):
    path, data = export(tmp_path, "mail.ply", scaffold, "--twist", "2", "--block", "4x4")
    curves = ply_curves(path)
    assert len(curves) == data["curves"] == 16 and all(closed for _, closed, _ in curves)
    linked = 0
    for a in range(len(curves)):
        for b in range(a):
            if abs(gauss_linking(curves[a][0], curves[b][0])) > 0.5:
                linked += 1
                assert curves[a][2] != curves[b][2]  # rings that link each other differ
    assert linked == pairs
    assert len({c for _, _, c in curves}) == 4  # the one ring class in four tones, not a colour a ring


def test_threads_keep_their_class_colour_and_rings_take_cell_tones_in_the_ply(tmp_path):
    # labels 2,0,0 on the cubic honeycomb: two thread classes run through the block, one ring class sits in its cells
    path, data = export(tmp_path, "mixed.ply", "honeycomb:cP", "--twist", "2,0,0", "--block", "2x2x2")
    curves = ply_curves(path)
    assert data["components"] == 3 and len(curves) == data["curves"]
    threads = {c for _, closed, c in curves if not closed}
    rings = [(p, c) for p, closed, c in curves if closed]
    assert len([1 for _, closed, _ in curves if not closed]) > 2 and len(threads) == 2  # many runs, two colours
    assert len(rings) == 12 and len({c for _, c in rings}) == 8 and not threads & {c for _, c in rings}
    centres = np.array([p.mean(axis=0) for p, _ in rings])
    step = np.sort(np.linalg.norm(centres[:, None] - centres[None], axis=2), axis=1)[:, 1].min()
    for a in range(len(rings)):
        for b in range(a):  # copies one cell apart (a side or across a face's diagonal) differ
            if np.linalg.norm(centres[a] - centres[b]) < 1.5 * step:
                assert rings[a][1] != rings[b][1]


def test_neighbouring_rings_differ_in_the_glb(tmp_path):
    pygltflib = pytest.importorskip("pygltflib")
    path, _ = export(tmp_path, "mail.glb", "tiling:square", "--twist", "2", "--block", "3x3")
    gltf = pygltflib.GLTF2().load(str(path))
    centres, colours = [], []
    for node in gltf.nodes:
        primitive = gltf.meshes[node.mesh].primitives[0]
        box = gltf.accessors[primitive.attributes.POSITION]
        centres.append((np.array(box.min) + np.array(box.max)) / 2)
        colours.append(tuple(gltf.materials[primitive.material].pbrMetallicRoughness.baseColorFactor))
    centres = np.array(centres)
    gaps = np.linalg.norm(centres[:, None] - centres[None], axis=2)
    step = np.sort(gaps, axis=1)[:, 1].min()
    near = [(a, b) for a in range(len(centres)) for b in range(a) if gaps[a, b] < 1.5 * step]
    assert len(centres) == 9 and len(near) == 20  # 12 side neighbours and 8 corner ones
    assert all(colours[a] != colours[b] for a, b in near) and len(set(colours)) == 4


def hue_shares(path, hues: np.ndarray) -> np.ndarray:
    """Share of a PNG's strongly coloured pixels nearest to each of ``hues`` (in ``[0, 1)``)."""
    plt_image = pytest.importorskip("matplotlib.image")
    rgb = plt_image.imread(str(path))[..., :3].reshape(-1, 3)
    vivid = rgb[(rgb.max(axis=1) - rgb.min(axis=1)) > 0.3]
    h = np.array([colorsys.rgb_to_hsv(*p)[0] for p in vivid[::5]])
    gap = np.abs(h[:, None] - hues[None])
    nearest = np.argmin(np.minimum(gap, 1 - gap), axis=1)
    return np.bincount(nearest, minlength=len(hues)) / len(h)


def test_png_of_a_chainmail_shows_its_ring_tones_and_a_weave_its_thread_colours(tmp_path):
    hues = np.array([colorsys.rgb_to_hsv(*c)[0] for c in PALETTE[:4]])  # red, blue, green, orange: apart in hue
    mail, _ = export(tmp_path, "mail.png", "tiling:square", "--twist", "2", "--block", "4x4", "--size", "300")
    weave, _ = export(tmp_path, "weave.png", "tiling:square", "--twist", "1", "--block", "4x4", "--size", "300")
    assert (hue_shares(mail, hues) > 0.1).all()  # four tones, each on a quarter of the rings
    shares = hue_shares(weave, hues)
    assert (shares[:2] > 0.3).all() and shares[2:].sum() < 0.05  # two thread classes: two colours only


def test_two_colours_draw_a_chainmail_as_a_checkerboard_in_the_svg(tmp_path):
    path, _ = export(tmp_path, "mail.svg", "tiling:square", "--twist", "2", "--block", "4x4", "--colors", "red,navy")
    root = ET.parse(path).getroot()
    groups = [g for g in root.iter("{http://www.w3.org/2000/svg}g") if g.get("class") == "strand"]
    stroke = {tuple(int(x) for x in g.get("data-cell").split(",")): g.get("stroke") for g in groups}
    assert len(stroke) == 16 and set(stroke.values()) == {"#ff0000", "#000080"}
    for (i, j), colour in stroke.items():  # the rings a side apart (the linked ones) in the other colour
        assert all(stroke[n] != colour for n in [(i + 1, j), (i, j + 1)] if n in stroke)
