"""Blender exits cleanly after a background identification (issue 35): the ``bpy`` module, its add-on
registered, a design identified in a child process, then the process ends while the job runs, after it
finished, or by Blender's own Quit.  Each run is a fresh Python (the crash came at interpreter exit)."""

import os
import pathlib
import subprocess
import sys

import pytest

pytest.importorskip("bpy")

import lkspace  # noqa: E402

SCRIPT = """
import sys, time
import bpy
import lkspace.blender.addon as addon
from lkspace.blender.addon import identifying
bpy.ops.wm.read_factory_settings(use_empty=True)
addon.register()
bpy.ops.lkspace.add_scaffold(scaffold=sys.argv[2], twist="1")
obj = bpy.context.active_object
assert bpy.ops.lkspace.identify() == {"FINISHED"}
print("child", identifying.JOBS[obj.name].process.pid, flush=True)
if sys.argv[1] == "finished":  # the bpy module runs no event loop: poll as Blender's timer would
    give_up = time.monotonic() + 120
    while identifying.JOBS and time.monotonic() < give_up:
        time.sleep(0.1)
        identifying.poll_jobs()
    print("knot", obj.lkspace.knot, flush=True)
elif sys.argv[1] == "quit":
    bpy.ops.wm.quit_blender()
"""


def run(mode: str, scaffold: str) -> subprocess.CompletedProcess[str]:
    root = pathlib.Path(lkspace.__file__).resolve().parents[1]  # the lkspace under test, not another install
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(root), os.environ.get("PYTHONPATH", "")])}
    return subprocess.run(
        [sys.executable, "-c", SCRIPT, mode, scaffold], capture_output=True, text=True, env=env, timeout=300
    )


def gone(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    return False


@pytest.mark.parametrize("mode", ["running", "quit", "finished"])
def test_exit_after_a_background_identify_is_clean(mode):
    # the cube with twist 1 takes SnapPy seconds (exit while it runs); the trefoil of dihedron:3 is quick
    done = run(mode, "dihedron:3" if mode == "finished" else "cube")
    assert done.returncode == 0, f"exit status {done.returncode}: {done.stderr[-2000:]}"
    lines = done.stdout.splitlines()
    child = int(next(line for line in lines if line.startswith("child")).split()[1])
    assert gone(child)  # no identification is left running after Blender
    if mode == "finished":
        assert "knot 3_1" in lines
