"""lkspace for Blender 4.2: twist labels on your mesh's edges, strands as curves, pictures and prints.

A legacy add-on (``bl_info``), installed from the zip that ``python -m lkspace.blender
build`` writes (Edit > Preferences > Add-ons > Install from Disk).  It uses lkspace as a
library from Blender's own Python; when that Python lacks lkspace, the panel says so and
shows the command that installs it.  See ``docs/blender.md``.
"""

from __future__ import annotations

import atexit
import sys
from typing import Any

import bpy

bl_info = {
    "name": "lkspace",
    "author": "lkspace",
    "version": (0, 2, 0),
    "blender": (4, 2, 0),
    "location": "View3D > Sidebar > lkspace",
    "description": "Knots, links and chainmail from integer twist labels on a mesh's edges",
    "category": "Mesh",
}

INSTALL = f'"{sys.executable}" -m pip install "lkspace[knots]"'
"""The command that installs lkspace into the Python running this Blender."""


class LKSPACE_PT_missing(bpy.types.Panel):  # noqa: N801
    """Shown instead of the real panel when Blender's Python cannot import lkspace."""

    bl_label = "lkspace"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "lkspace"

    def draw(self, context: Any) -> None:
        """Say what is missing and how to install it."""
        layout = self.layout
        layout.label(text="lkspace is not installed in Blender's Python", icon="ERROR")
        layout.label(text=f"Missing: {MISSING[0] if MISSING else 'lkspace'}")
        layout.label(text="Install it from a terminal, then restart Blender:")
        for part in (f'"{sys.executable}"', '-m pip install "lkspace[knots]"'):
            layout.label(text=part)
        layout.operator("lkspace.copy_install_command")


class LKSPACE_OT_copy_install_command(bpy.types.Operator):  # noqa: N801
    """Copy the command that installs lkspace into Blender's Python to the clipboard."""

    bl_idname = "lkspace.copy_install_command"
    bl_label = "Copy Install Command"

    def execute(self, context: Any) -> set[str]:
        """Put :data:`INSTALL` on the clipboard."""
        context.window_manager.clipboard = INSTALL
        self.report({"INFO"}, INSTALL)
        return {"FINISHED"}


MISSING: list[str] = []
"""Why lkspace could not be imported (empty when it was)."""
REGISTERED: list[Any] = []
EXIT_HOOK: list[Any] = []


def classes() -> tuple[Any, ...]:
    """Return the add-on's classes in registration order (imports lkspace: may raise ImportError)."""
    from . import builtin, design_ops, edit_ops, panel

    return (*panel.CLASSES, *edit_ops.CLASSES, *design_ops.CLASSES, *builtin.CLASSES)


def register() -> None:
    """Register the panel and operators, or the install hint when lkspace is missing."""
    try:
        found = classes()
    except ImportError as exc:
        MISSING[:] = [str(exc)]
        print(f"lkspace add-on: {exc}; install lkspace with: {INSTALL}", file=sys.stderr)
        found = (LKSPACE_OT_copy_install_command, LKSPACE_PT_missing)
    for cls in found:
        bpy.utils.register_class(cls)
    REGISTERED[:] = found
    if not MISSING:
        from . import live, panel

        bpy.types.Scene.lkspace = bpy.props.PointerProperty(type=panel.LkspaceSettings)
        bpy.types.Object.lkspace = bpy.props.PointerProperty(type=panel.LkspaceResult)
        live.install_handler()
    if not bpy.app.binary_path and not EXIT_HOOK:  # the bpy module crashes on exit with a handler or timer left
        atexit.register(unregister)
        EXIT_HOOK.append(unregister)


def unregister() -> None:
    """Undo :func:`register` (nothing if it is not registered)."""
    if not REGISTERED:
        return
    if not MISSING:
        from . import identifying, live

        live.remove_handler()
        identifying.stop_all()
        del bpy.types.Scene.lkspace
        del bpy.types.Object.lkspace
    for cls in reversed(REGISTERED):
        bpy.utils.unregister_class(cls)
    REGISTERED.clear()
    MISSING.clear()
