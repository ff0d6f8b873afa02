"""Render a design with Blender headless (``python -m lkspace.blender render``; needs ``bpy``)."""

from __future__ import annotations

import os
import sys

from ..errors import LkspaceError, MissingDependencyError
from .engines import ENGINES


def render_design(
    mesh: str, twist: str, output: str, size: str, engine: str, samples: int, block: str | None = None
) -> None:
    """Load ``mesh`` into an empty Blender scene with the add-on, regenerate, apply the scene preset, render.

    A periodic scaffold is drawn as a ``block`` of cells (default ``4x4`` or ``2x2x2``).
    """
    try:
        import bpy
    except ImportError:
        raise MissingDependencyError("bpy", "blender", "rendering with Blender (Python 3.11)") from None
    from ..io.paths import output_file
    from ..io.sources import load
    from . import addon
    from .addon import builtin, scene

    target = output_file(output, (".png",))
    try:
        width, height = (int(x) for x in size.lower().split("x"))
    except ValueError:
        raise LkspaceError(f"size {size!r}: expected WxH such as 480x480", usage=True, parameter="size") from None
    bpy.ops.wm.read_factory_settings(use_empty=True)
    if not hasattr(bpy.types.Scene, "lkspace"):
        addon.register()
    context = bpy.context
    if load(mesh).periodic:
        dim = load(mesh).dim
        builtin.make_block(context.scene, mesh, twist or "1", block or "x".join(["4", "4", "2"][:dim]))
    else:
        obj = builtin.add_scaffold(context, mesh, twist)
        if obj.lkspace.message:
            raise LkspaceError(obj.lkspace.message)
    note = scene.preset(context.scene, ENGINES[engine], (width, height), samples)
    if note:
        print(note, file=sys.stderr)
    scene.render(context.scene, os.path.abspath(target))
