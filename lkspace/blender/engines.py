"""Blender's render engines, and which of them can run here (no ``bpy``).

EEVEE rasterizes on a GPU.  Headless on a Linux machine without one (a server, a
container, CI), Blender 4.2 still starts it on Mesa's software rasterizer, which compiles
EEVEE's shaders on the CPU and then draws a sample at a time: a 64 x 64 picture of a
cube took 43 s on a 2-core machine, an 800 x 800 one would take hours, and nothing says
why.  So the add-on checks for a GPU before it picks EEVEE (:func:`no_gpu`) and renders
with Cycles on the CPU instead, saying so in one line (:func:`engine_to_use`).  Cycles
(path tracing on the CPU) and Workbench (flat shading; Blender 4.2 draws it with OpenGL,
on the software rasterizer too, in about a second) need no GPU.

Examples
--------
>>> engine_to_use("CYCLES")
('CYCLES', '')
>>> engine_to_use("BLENDER_EEVEE_NEXT", "no /dev/dri, /dev/nvidia or /dev/dxg device")[1]
'EEVEE needs a GPU and this machine has none (no /dev/dri, /dev/nvidia or /dev/dxg device): rendering with Cycles on the CPU instead'
"""

from __future__ import annotations

import glob
import os
import sys

ENGINES = {"cycles": "CYCLES", "eevee": "BLENDER_EEVEE_NEXT", "workbench": "BLENDER_WORKBENCH"}
"""``--engine`` of ``python -m lkspace.blender render`` -> Blender's render engine."""
EEVEE = ENGINES["eevee"]
GPU_DEVICES = ("/dev/dri/renderD*", "/dev/dri/card*", "/dev/nvidia[0-9]*", "/dev/dxg")
"""Device files of a GPU on Linux: Mesa's drivers (Intel, AMD, virtio, ...), NVIDIA's, WSL2's (Direct3D 12)."""


def no_gpu(devices: tuple[str, ...] = GPU_DEVICES) -> str:
    """Return why this machine cannot run EEVEE on a GPU, or ``""`` when it can.

    On Linux: ``LIBGL_ALWAYS_SOFTWARE`` set (Mesa's switch to its software rasterizer), or
    none of the ``devices`` patterns matching a file.  macOS always has Metal, and Blender
    on Windows does not start without OpenGL 4.3, so there the answer is ``""``.
    """
    if sys.platform in ("darwin", "win32"):
        return ""
    if os.environ.get("LIBGL_ALWAYS_SOFTWARE", "0").strip().lower() not in ("", "0", "false"):
        return "LIBGL_ALWAYS_SOFTWARE asks for software rendering"
    if not any(glob.glob(pattern) for pattern in devices):
        return "no /dev/dri, /dev/nvidia or /dev/dxg device"
    return ""


def engine_to_use(engine: str, missing: str | None = None) -> tuple[str, str]:
    """Return the engine to render with for ``engine`` and a one-line note when it is another one.

    EEVEE without a GPU (``missing``: the reason, by default :func:`no_gpu`'s) becomes
    Cycles on the CPU; every other engine stays.
    """
    if engine != EEVEE:
        return engine, ""
    reason = no_gpu() if missing is None else missing
    if not reason:
        return engine, ""
    return "CYCLES", f"EEVEE needs a GPU and this machine has none ({reason}): rendering with Cycles on the CPU instead"
