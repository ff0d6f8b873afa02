"""Pictures from the Blender add-on: EEVEE without a GPU becomes Cycles on the CPU, said in one line (issue 35),
never a software-rasterized render that looks hung."""

import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

from lkspace.blender.engines import EEVEE, engine_to_use, no_gpu

linux_only = pytest.mark.skipif(sys.platform in ("darwin", "win32"), reason="macOS and Windows always have a GPU")


@linux_only
def test_no_gpu_looks_for_device_files_and_mesa_software(tmp_path, monkeypatch):
    monkeypatch.delenv("LIBGL_ALWAYS_SOFTWARE", raising=False)
    devices = (str(tmp_path / "renderD*"),)
    assert no_gpu(devices) == "no /dev/dri, /dev/nvidia or /dev/dxg device"
    assert engine_to_use(EEVEE, no_gpu(devices)) == (
        "CYCLES",
        "EEVEE needs a GPU and this machine has none (no /dev/dri, /dev/nvidia or /dev/dxg device): "
        "rendering with Cycles on the CPU instead",
    )
    (tmp_path / "renderD128").touch()
    assert no_gpu(devices) == ""
    assert engine_to_use(EEVEE, no_gpu(devices)) == (EEVEE, "")
    monkeypatch.setenv("LIBGL_ALWAYS_SOFTWARE", "1")
    assert no_gpu(devices) == "LIBGL_ALWAYS_SOFTWARE asks for software rendering"
    for engine in ("CYCLES", "BLENDER_WORKBENCH"):  # they need no GPU
        assert engine_to_use(engine, "no GPU") == (engine, "")


@linux_only
def test_eevee_render_without_a_gpu_says_so_and_renders_with_cycles(tmp_path):
    pytest.importorskip("bpy")
    import lkspace

    root = pathlib.Path(lkspace.__file__).resolve().parents[1]
    env = {**os.environ, "LIBGL_ALWAYS_SOFTWARE": "1", "PYTHONPATH": str(root)}  # Mesa's software GL, GPU or not
    out = tmp_path / "cube.png"
    args = ["cube", "--twist", "1", "-o", str(out), "--engine", "eevee", "--size", "24x24", "--samples", "1"]
    run = subprocess.run(
        [sys.executable, "-m", "lkspace.blender", "render", *args], capture_output=True, text=True, env=env, timeout=600
    )
    assert run.returncode == 0, run.stderr
    assert run.stderr.strip() == (
        "EEVEE needs a GPU and this machine has none (LIBGL_ALWAYS_SOFTWARE asks for software rendering): "
        "rendering with Cycles on the CPU instead"
    )
    assert out.stat().st_size > 0


@linux_only
def test_scene_preset_operator_falls_back_to_cycles(blender, monkeypatch):
    import bpy

    monkeypatch.setenv("LIBGL_ALWAYS_SOFTWARE", "1")
    assert bpy.ops.lkspace.add_scaffold(scaffold="tetrahedron", twist="1") == {"FINISHED"}
    assert bpy.ops.lkspace.scene_preset(engine=EEVEE) == {"FINISHED"}
    assert blender.scene.render.engine == "CYCLES" and blender.scene.cycles.device == "CPU"
    assert bpy.ops.lkspace.scene_preset(engine="BLENDER_WORKBENCH") == {"FINISHED"}
    assert blender.scene.render.engine == "BLENDER_WORKBENCH"


def silhouette(path):
    """Rows and columns of a picture holding anything but its background (the corner pixel's colour)."""
    bpy = pytest.importorskip("bpy")
    image = bpy.data.images.load(str(path))
    width, height = image.size
    pixels = np.array(image.pixels[:]).reshape(height, width, 4)[::-1, :, :3]  # Blender's rows run bottom up
    drawn = np.abs(pixels - pixels[0, 0]).sum(axis=2) > 0.1
    return np.flatnonzero(drawn.any(axis=1)), np.flatnonzero(drawn.any(axis=0)), (width, height)


@pytest.mark.parametrize(("design", "size"), [("cube", (64, 48)), ("tiling:square", (48, 64))])
def test_render_preset_frames_the_strands_centred_and_whole(blender, tmp_path, design, size):
    import bpy

    from lkspace.blender.addon.builtin import make_block

    if design == "cube":
        assert bpy.ops.lkspace.add_scaffold(scaffold="cube", twist="1") == {"FINISHED"}
    else:
        make_block(blender.scene, design, "2", "2x2")
    out = tmp_path / "picture.png"
    width, height = size
    answer = bpy.ops.lkspace.render_preset(
        filepath=str(out), engine="BLENDER_WORKBENCH", width=width, height=height, samples=1
    )
    assert answer == {"FINISHED"} and out.exists()
    rows, cols, got = silhouette(out)
    assert got == size
    margins = np.array([rows[0], height - 1 - rows[-1], cols[0], width - 1 - cols[-1]])
    assert (margins >= 1).all(), margins  # no tube cut by the frame
    tight = margins[2:] if (cols[-1] - cols[0]) / width >= (rows[-1] - rows[0]) / height else margins[:2]
    loose = margins[:2] if tight is margins[2:] else margins[2:]
    assert tight.max() <= 0.08 * max(size) and abs(tight[0] - tight[1]) <= 1, margins  # fills the frame
    assert abs(loose[0] - loose[1]) <= 0.06 * max(size) + 1, margins  # centred the other way too


def tube_radii(obj):
    import bpy

    return sorted({c.data.bevel_depth for c in bpy.data.collections[obj.name].objects if c.type == "CURVE"})


def test_render_preset_thickens_thin_tubes_within_their_clearance(blender):
    import bpy

    import lkspace
    from lkspace.blender.addon import scene
    from lkspace.blender.addon.builtin import make_block
    from lkspace.geometry.block import realize_block
    from lkspace.io.twists import parse_twist

    block = make_block(blender.scene, "tiling:square", "2", "3x3")
    square = lkspace.load("tiling:square")
    real = realize_block(square, parse_twist(square, "2"), None, None, [3, 3])
    assert tube_radii(block) == [pytest.approx(real.tube_radius)]
    scene.preset(blender.scene, "BLENDER_WORKBENCH", (32, 32))
    (radius,) = tube_radii(block)
    assert radius > 1.5 * real.tube_radius  # lkspace's 0.03 of an edge is 1% of a 3x3 block's picture
    assert radius <= 0.3 * real.min_distance * 1.1  # still clear of each other: 0.3 of the closest approach
    block.hide_render = True
    for curve in bpy.data.collections[block.name].objects:
        curve.hide_render = True
    assert bpy.ops.lkspace.add_scaffold(scaffold="cube", twist="1") == {"FINISHED"}
    scene.preset(blender.scene, "BLENDER_WORKBENCH", (32, 32))
    # the cube's tubes, 5% of its picture, are thick enough already: kept
    assert tube_radii(blender.active_object) == [pytest.approx(lkspace.realize("cube", [1] * 12).tube_radius)]


def test_render_preset_refuses_in_one_line(blender, tmp_path):
    import bpy

    with pytest.raises(RuntimeError, match="no strands to draw: Regenerate a mesh, or Add Scaffold, first"):
        bpy.ops.lkspace.render_preset(filepath=str(tmp_path / "empty.png"), engine="BLENDER_WORKBENCH")
    assert bpy.ops.lkspace.add_scaffold(scaffold="tetrahedron", twist="1") == {"FINISHED"}
    missing = tmp_path / "no" / "such"
    with pytest.raises(RuntimeError, match=f"folder {missing} does not exist"):
        bpy.ops.lkspace.render_preset(filepath=str(missing / "x.png"), engine="BLENDER_WORKBENCH")
    assert not (tmp_path / "empty.png").exists()
