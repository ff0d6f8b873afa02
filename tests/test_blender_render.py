"""Pictures from the Blender add-on: EEVEE without a GPU becomes Cycles on the CPU, said in one line (issue 35),
never a software-rasterized render that looks hung."""

import os
import pathlib
import subprocess
import sys

import pytest

from lkspace.blender.engines import EEVEE, engine_to_use, no_gpu

linux_only = pytest.mark.skipif(sys.platform in ("darwin", "win32"), reason="macOS and Windows always have a GPU")


@linux_only
def test_no_gpu_looks_for_device_files_and_mesa_software(tmp_path, monkeypatch):
    monkeypatch.delenv("LIBGL_ALWAYS_SOFTWARE", raising=False)
    devices = (str(tmp_path / "renderD*"),)
    assert no_gpu(devices) == "no /dev/dri or /dev/nvidia device"
    assert engine_to_use(EEVEE, no_gpu(devices)) == (
        "CYCLES",
        "EEVEE needs a GPU and this machine has none (no /dev/dri or /dev/nvidia device): "
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
