"""How long the Blender add-on takes to rebuild the strands of a mesh (the live update).

Blender's own primitives, every edge twisted once; the median of three rebuilds
(``lkspace.blender.addon.live.regenerate``: read the mesh, trace, realize, replace the
curve objects), measured and unmeasured clearance.  Needs the ``bpy`` module
(``pip install -e '.[blender]'``, Python 3.11).  Writes ``results/bench_blender.md``.

Run: ``python experiments/bench_blender.py``.
"""

from __future__ import annotations

import os
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


def main() -> None:
    bpy.ops.wm.read_factory_settings(use_empty=True)
    addon.register()
    bpy.context.scene.lkspace.live = False
    rows = []
    for name, make in MESHES:
        make()
        obj = bpy.context.active_object
        mesh = obj.data
        mesh.attributes.new("lk_twist", "INT", "EDGE").data.foreach_set("value", [1] * len(mesh.edges))
        mesh.update()
        fast = median_rebuild(obj, measure=False)
        checked = median_rebuild(obj, measure=True)
        rows.append(f"| {name} | {len(mesh.polygons)} | {obj.lkspace.components} | {fast:.3f} | {checked:.2f} |")
        print(rows[-1])
    lines = [
        "# Rebuilding strands in Blender",
        "",
        "Made by `python experiments/bench_blender.py` (bpy 4.2, a shared 2-core machine under load): the",
        "median of three rebuilds of a Blender primitive with every edge twisted once.  Live updates skip",
        f"the clearance measurement above {live.MEASURE_FACES} faces; *Regenerate* always measures.",
        "",
        "| mesh | faces | components | rebuild, unmeasured (s) | rebuild, clearance measured (s) |",
        "|---|---|---|---|---|",
        *rows,
    ]
    with open(OUT, "w") as fh:
        fh.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
