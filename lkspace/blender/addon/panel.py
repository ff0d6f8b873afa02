"""The add-on's settings, results and sidebar panel (View3D > Sidebar > lkspace).

``scene.lkspace`` holds what the buttons use (twist to set, label set, seed, N, live
toggle, engine); ``object.lkspace`` holds what lkspace found for a mesh (components,
holding together, the knot name, the last error), so scripts read them too.
"""

from __future__ import annotations

import os
from typing import Any

import bpy

from . import live
from .scene import ENGINES, preset, render, strand_curves


def live_toggled(settings: Any, context: Any) -> None:
    """Regenerate at once when the live toggle is switched on."""
    obj = context.active_object
    if settings.live and obj is not None and obj.type == "MESH":
        live.regenerate(obj, context.scene)


def shape_changed(settings: Any, context: Any) -> None:
    """Rebuild the active mesh's strands when a shape control changes, if it was built and *Live* is on."""
    obj = context.active_object
    if settings.live and obj is not None and obj.type == "MESH" and obj.lkspace.key:
        live.regenerate(obj, context.scene)


SOLVE_LIMIT = "Seconds of wall-clock time for Solve"
"""What the panel's Time limit counts (issue 35: every limit says whether it is CPU or wall-clock time)."""


class LkspaceSettings(bpy.types.PropertyGroup):
    """Scene settings of the lkspace panel."""

    twist: bpy.props.IntProperty(name="Twist", default=1, description="Twist to give the selected edges")  # type: ignore[valid-type]
    symmetry: bpy.props.EnumProperty(  # type: ignore[valid-type]
        name="Symmetry",
        items=[("rotations", "Rotations", "Rotations keep a twist"), ("isometries", "Isometries", "Mirrors negate it")],
    )
    label_set: bpy.props.StringProperty(name="Labels", default="-2..2", description="Labels to draw or solve with")  # type: ignore[valid-type]
    no_zero: bpy.props.BoolProperty(name="No zero", default=True, description="Never use twist 0")  # type: ignore[valid-type]
    seed: bpy.props.IntProperty(name="Seed", default=0, min=0)  # type: ignore[valid-type]
    components: bpy.props.IntProperty(name="Components", default=1, min=1)  # type: ignore[valid-type]
    time_limit: bpy.props.FloatProperty(name="Time limit", default=20.0, min=0.5, description=SOLVE_LIMIT)  # type: ignore[valid-type]
    live: bpy.props.BoolProperty(name="Live", default=True, update=live_toggled, description="Regenerate on edits")  # type: ignore[valid-type]
    relax: bpy.props.BoolProperty(name="Relax", description="Strands drawn tight (lkspace.relax, until it converges)")  # type: ignore[valid-type]
    engine: bpy.props.EnumProperty(name="Engine", items=ENGINES)  # type: ignore[valid-type]
    radius: bpy.props.FloatProperty(  # type: ignore[valid-type]
        name="Inset",
        update=shape_changed,
        min=0.0,
        default=0.0,
        description="Distance of the strands from the edges in their faces (0: automatic)",
    )
    normal_offset: bpy.props.FloatProperty(  # type: ignore[valid-type]
        name="Normal offset",
        update=shape_changed,
        min=0.0,
        default=0.0,
        description="Lift of the strands off the faces (0: automatic)",
    )
    tube_radius: bpy.props.FloatProperty(  # type: ignore[valid-type]
        name="Tube radius",
        update=shape_changed,
        min=0.0,
        default=0.0,
        description="Radius of the strand tubes (0: automatic, clear of each other)",
    )
    resolution: bpy.props.IntProperty(  # type: ignore[valid-type]
        name="Resolution",
        update=shape_changed,
        min=0,
        max=16,
        default=3,
        description="Bevel resolution of the tubes (round segments)",
    )


class LkspaceResult(bpy.types.PropertyGroup):
    """What lkspace found for a mesh object at its last regeneration."""

    components: bpy.props.IntProperty(name="Components")  # type: ignore[valid-type]
    holds_together: bpy.props.BoolProperty(name="Holds together")  # type: ignore[valid-type]
    open_strands: bpy.props.IntProperty(name="Open strands")  # type: ignore[valid-type]
    knot: bpy.props.StringProperty(name="Knot or link")  # type: ignore[valid-type]
    message: bpy.props.StringProperty(name="Message")  # type: ignore[valid-type]
    measured: bpy.props.BoolProperty(name="Clearance measured, strands smoothed")  # type: ignore[valid-type]
    relaxed: bpy.props.BoolProperty(name="Relaxed")  # type: ignore[valid-type]
    key: bpy.props.StringProperty(name="State")  # type: ignore[valid-type]
    strands: bpy.props.StringProperty(name="Strand collection")  # type: ignore[valid-type]


class LKSPACE_OT_scene_preset(bpy.types.Operator):  # noqa: N801
    """Fit a camera to the strands, add lights and a world, and pick the render engine."""

    bl_idname = "lkspace.scene_preset"
    bl_label = "Scene Preset"
    bl_options = {"REGISTER", "UNDO"}
    engine: bpy.props.EnumProperty(name="Engine", items=ENGINES)  # type: ignore[valid-type]

    def execute(self, context: Any) -> set[str]:
        """Set the scene up for a picture (EEVEE without a GPU: Cycles, reported as a warning)."""
        note = preset(context.scene, self.engine)
        if note:
            self.report({"WARNING"}, note)
        return {"FINISHED"}


class LKSPACE_OT_render_preset(bpy.types.Operator):  # noqa: N801
    """Set the scene up for a picture of the strands (as Scene Preset does) and render it to a PNG file."""

    bl_idname = "lkspace.render_preset"
    bl_label = "Render Picture"
    filepath: bpy.props.StringProperty(subtype="FILE_PATH")  # type: ignore[valid-type]
    engine: bpy.props.EnumProperty(name="Engine", items=ENGINES)  # type: ignore[valid-type]
    width: bpy.props.IntProperty(name="Width", default=800, min=16, max=8192)  # type: ignore[valid-type]
    height: bpy.props.IntProperty(name="Height", default=800, min=16, max=8192)  # type: ignore[valid-type]
    samples: bpy.props.IntProperty(name="Samples", default=32, min=1, max=4096, description="Cycles and EEVEE")  # type: ignore[valid-type]

    def invoke(self, context: Any, event: Any) -> set[str]:
        """Ask for the file name (by default the active object's, ``.png``)."""
        if not self.filepath:
            obj = context.active_object
            self.filepath = bpy.path.ensure_ext(obj.name if obj is not None else "lkspace", ".png")
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context: Any) -> set[str]:
        """Apply the preset and render; refuse in one line when there is nothing to draw or nowhere to write."""
        path = bpy.path.abspath(bpy.path.ensure_ext(self.filepath, ".png")) if self.filepath else ""
        folder = os.path.dirname(os.path.abspath(path)) if path else ""
        problem = (
            "give the PNG file to write (filepath)"
            if not path
            else f"folder {folder} does not exist"
            if not os.path.isdir(folder)
            else "no strands to draw: Regenerate a mesh, or Add Scaffold, first"
            if not strand_curves(context.scene)
            else ""
        )
        if problem:
            self.report({"ERROR"}, problem)
            return {"CANCELLED"}
        note = preset(context.scene, self.engine, (self.width, self.height), self.samples)
        if note:
            self.report({"WARNING"}, note)
        render(context.scene, path)
        self.report({"INFO"}, f"wrote {path}")
        return {"FINISHED"}


class LKSPACE_PT_design(bpy.types.Panel):  # noqa: N801
    """The lkspace sidebar panel."""

    bl_label = "lkspace"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "lkspace"

    def draw(self, context: Any) -> None:
        """Edit, read and output sections."""
        layout = self.layout
        settings = context.scene.lkspace
        obj = context.active_object
        if obj is None or obj.type != "MESH":
            layout.label(text="Select a mesh: its edges carry the twists")
            layout.operator("lkspace.add_scaffold")
            layout.operator("lkspace.periodic_block")
            return
        edit = layout.box()
        edit.label(text="Edit twists (lk_twist)")
        row = edit.row(align=True)
        row.prop(settings, "twist")
        row.operator("lkspace.set_twist", text="Set Selected").twist = settings.twist
        row = edit.row(align=True)
        row.prop(settings, "symmetry", text="")
        row.operator("lkspace.fill_orbit").mode = settings.symmetry
        row = edit.row(align=True)
        row.prop(settings, "label_set")
        row.prop(settings, "no_zero")
        row = edit.row(align=True)
        row.prop(settings, "seed")
        row.operator("lkspace.randomize").seed = settings.seed
        row = edit.row(align=True)
        row.prop(settings, "components")
        row.operator("lkspace.solve").components = settings.components
        row = edit.row(align=True)
        row.operator("lkspace.set_null", text="Cut Sides").null = True
        row.operator("lkspace.set_null", text="Uncut Sides").null = False
        read = layout.box()
        row = read.row(align=True)
        row.prop(settings, "live")
        row.prop(settings, "relax")
        row.operator("lkspace.regenerate", text="Regenerate")
        row = read.row(align=True)
        row.prop(settings, "radius")
        row.prop(settings, "normal_offset")
        row = read.row(align=True)
        row.prop(settings, "tube_radius")
        row.prop(settings, "resolution")
        if any(m.show_viewport for m in obj.modifiers):
            read.label(text="Strands follow the mesh with its modifiers", icon="INFO")
        result = obj.lkspace
        if result.message:
            for line in wrap(result.message):
                read.label(text=line, icon="ERROR")
        elif result.key:
            from lkspace.words import plural  # here: lkspace may be missing when the panel is drawn

            together = "holds together" if result.holds_together else "falls apart"
            read.label(
                text=f"{plural(result.components, 'component')}, {together}{', relaxed' if result.relaxed else ''}"
            )
            if result.open_strands:
                read.label(text=plural(result.open_strands, "open strand"))
            if not result.measured:
                read.label(text="Preview (large mesh): not smoothed or measured; Regenerate does both")
        row = read.row(align=True)
        row.operator("lkspace.identify")
        row.label(text=result.knot or "-")
        out = layout.box()
        out.operator("lkspace.export", text="Export STL / 3MF")
        out.operator("lkspace.export_dna", text="Export DNA (oxDNA)")
        row = out.row(align=True)
        row.prop(settings, "engine", text="")
        row.operator("lkspace.scene_preset").engine = settings.engine
        row.operator("lkspace.render_preset").engine = settings.engine
        row = out.row(align=True)
        row.operator("lkspace.add_scaffold")
        row.operator("lkspace.periodic_block")


def wrap(text: str, width: int = 48) -> list[str]:
    """Split ``text`` into lines of at most about ``width`` characters for the panel."""
    lines, line = [], ""
    for word in text.split():
        if line and len(line) + len(word) >= width:
            lines.append(line)
            line = ""
        line = f"{line} {word}".strip()
    return lines + [line] if line else lines


CLASSES = (LkspaceSettings, LkspaceResult, LKSPACE_OT_scene_preset, LKSPACE_OT_render_preset, LKSPACE_PT_design)
