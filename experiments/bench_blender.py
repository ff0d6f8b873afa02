"""How long the Blender add-on takes to rebuild the strands of a mesh (the live update).

Blender's own primitives, every edge twisted once; the median of three of each:

* *live edit*: what a user waits for with *Live* on: the twists of every edge flipped
  (1 <-> -1) through ``lk_twist``, the depsgraph update whose handler rebuilds the strands,
  and Blender evaluating the new curves (their tubes) for the viewport;
* *preview* and *measured* rebuilds (``lkspace.blender.addon.live.regenerate``: read the
  evaluated mesh, trace, realize, replace the curve objects): a preview draws the
  construction unsmoothed, coarser and unmeasured (live rebuilds above
  ``live.MEASURE_FACES`` faces), *Regenerate* measures the clearance and smooths.

Needs the ``bpy`` module (``pip install -e '.[blender]'``, Python 3.11).  Writes
``results/bench_blender.md`` with the commit and the machine's load.

Run: ``python experiments/bench_blender.py``.
"""

from __future__ import annotations

import os
import platform
import subprocess
import time

import bpy

import lkspace.blender.addon as addon
from lkspace.blender.addon import live

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "results", "bench_blender.md")
MESHES = [
    ("cube", lambda: bpy.ops.mesh.primitive_cube_add()),
    ("ico sphere, 2 subdivisions", lambda: bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=2)),
    ("UV sphere 32 x 16", lambda: bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16)),
    ("ico sphere, 4 subdivisions", lambda: bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=4)),
]


def median_rebuild(obj, measure: bool) -> float:
    times = []
    for _ in range(3):
        t0 = time.perf_counter()
        assert live.regenerate(obj, bpy.context.scene, measure=measure), obj.lkspace.message
        times.append(time.perf_counter() - t0)
    return sorted(times)[1]


def set_twists(mesh, twist: int) -> None:
    mesh.attributes["lk_twist"].data.foreach_set("value", [twist] * len(mesh.edges))
    mesh.update()


def median_live_edit(obj) -> float:
    """Flip every twist with *Live* on; the time until the new curves are evaluated for the viewport."""
    scene = bpy.context.scene
    assert live.regenerate(obj, scene, measure=False)
    scene.lkspace.live = True
    times = []
    for twist in (-1, 1, -1):
        key = obj.lkspace.key
        t0 = time.perf_counter()
        set_twists(obj.data, twist)
        bpy.context.view_layer.update()  # the depsgraph handler rebuilds the strands
        bpy.context.evaluated_depsgraph_get()  # Blender evaluates the new curves, as before drawing them
        times.append(time.perf_counter() - t0)
        assert obj.lkspace.key != key and not obj.lkspace.message, obj.lkspace.message
    scene.lkspace.live = False
    set_twists(obj.data, 1)
    return sorted(times)[1]


def commit() -> str:
    here = os.path.dirname(os.path.abspath(__file__))
    run = subprocess.run(["git", "-C", here, "describe", "--always", "--dirty"], capture_output=True, text=True)
    return run.stdout.strip() or "unknown"


def main() -> None:
    bpy.ops.wm.read_factory_settings(use_empty=True)
    addon.register()
    bpy.context.scene.lkspace.live = False
    loads = [os.getloadavg()[0]]
    rows = []
    for name, make in MESHES:
        make()
        obj = bpy.context.active_object
        mesh = obj.data
        mesh.attributes.new("lk_twist", "INT", "EDGE")
        set_twists(mesh, 1)
        edit = median_live_edit(obj)
        fast = median_rebuild(obj, measure=False)
        checked = median_rebuild(obj, measure=True)
        loads.append(os.getloadavg()[0])
        rows.append(
            f"| {name} | {len(mesh.polygons)} | {obj.lkspace.components} | {edit:.3f} | {fast:.3f} | {checked:.2f} |"
        )
        print(rows[-1])
    lines = [
        "# Rebuilding strands in Blender",
        "",
        f"Made by `python experiments/bench_blender.py` at commit `{commit()}` (bpy {bpy.app.version_string},",
        f"{platform.machine()}, {os.cpu_count()} cores, shared; load average {min(loads):.1f} to {max(loads):.1f}",
        "while it ran): the median of three, on a Blender primitive with every edge twisted once.",
        "*Live edit*: every twist flipped with *Live* on, until Blender has evaluated the new curves",
        f"(above {live.MEASURE_FACES} faces a live rebuild is a preview: the construction unsmoothed, sampled",
        f"{live.PREVIEW_COARSER} times more coarsely, tubes of bevel resolution {live.PREVIEW_RESOLUTION}, its clearance",
        "not measured); *preview* and *measured*: `live.regenerate` alone, as *Regenerate* builds with",
        "`measure=False` and with the clearance measured and the strands smoothed.",
        "",
        "| mesh | faces | components | live edit (s) | rebuild, preview (s) | rebuild, measured and smoothed (s) |",
        "|---|---|---|---|---|---|",
        *rows,
    ]
    with open(OUT, "w") as fh:
        fh.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
