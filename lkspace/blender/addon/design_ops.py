"""Operators that read a design: regenerate, identify, export a printable file.

``bpy.ops.lkspace.regenerate()`` rebuilds the active mesh's strands.  Identification
(SnapPy, seconds) runs in a child process by default and lands on the object's
``lkspace.knot`` when done (:mod:`.identifying`); ``background=False`` waits for it.
"""

from __future__ import annotations

from typing import Any

import bpy

from lkspace.errors import LkspaceError

from . import identifying, live, meshio


class DesignOperator(bpy.types.Operator):
    """Base of the operators reading the active mesh's design (not registered: Blender wants leaf classes)."""

    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context: Any) -> bool:
        """Only with an active mesh object."""
        obj = context.active_object
        return obj is not None and obj.type == "MESH"


class FileOperator(DesignOperator):
    """Base of the operators writing the design to a file named in a file browser (``extension``: its default)."""

    filepath: bpy.props.StringProperty(subtype="FILE_PATH")  # type: ignore[valid-type]
    extension = ".stl"

    def invoke(self, context: Any, event: Any) -> set[str]:
        """Ask for the file name (by default the object's, with ``extension``)."""
        if not self.filepath:
            self.filepath = bpy.path.ensure_ext(context.active_object.name, self.extension)
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}


class LKSPACE_OT_regenerate(DesignOperator):  # noqa: N801
    """Build the active mesh's strands: one curve object per component, in a collection named after the mesh."""

    bl_idname = "lkspace.regenerate"
    bl_label = "Regenerate Strands"
    measure: bpy.props.BoolProperty(name="Measure clearance", default=True)  # type: ignore[valid-type]

    def execute(self, context: Any) -> set[str]:
        """Regenerate; report lkspace's error as one line."""
        obj = context.active_object
        if not live.regenerate(obj, context.scene, measure=self.measure):
            self.report({"ERROR"}, obj.lkspace.message)
            return {"CANCELLED"}
        return {"FINISHED"}


class LKSPACE_OT_identify(DesignOperator):  # noqa: N801
    """Name the knot or link of the active mesh's design (SnapPy; can take seconds)."""

    bl_idname = "lkspace.identify"
    bl_label = "Identify"
    background: bpy.props.BoolProperty(name="In the background", default=True)  # type: ignore[valid-type]

    def execute(self, context: Any) -> set[str]:
        """Start (or, with ``background=False``, run) the identification of the current design."""
        obj = context.active_object
        if not live.regenerate(obj, context.scene, force=False):
            self.report({"ERROR"}, obj.lkspace.message)
            return {"CANCELLED"}
        design, labels, nulls = meshio.read_design(obj)
        if not self.background:
            obj.lkspace.knot = identifying.identify_now(design.scaffold, labels, nulls)
            return {"FINISHED"}
        obj.lkspace.knot = "identifying..."
        identifying.start(obj.name, obj.lkspace.key, design.scaffold, labels, nulls)
        return {"FINISHED"}


class LKSPACE_OT_export(FileOperator):  # noqa: N801
    """Write printable pieces (.stl or .3mf) through lkspace's checked fabrication path."""

    bl_idname = "lkspace.export"
    bl_label = "Export Printable"
    thickness: bpy.props.FloatProperty(name="Thickness", default=2.0, min=0.0)  # type: ignore[valid-type]
    clearance: bpy.props.FloatProperty(name="Clearance", default=0.4, min=0.0)  # type: ignore[valid-type]
    scale: bpy.props.FloatProperty(name="Scale", default=10.0, min=0.0, description="Millimetres per mesh unit")  # type: ignore[valid-type]

    def execute(self, context: Any) -> set[str]:
        """Export with ``lkspace.export`` (the path of ``lkspace export -o X --thickness --clearance``)."""
        from lkspace.formats.options import PrintOptions
        from lkspace.formats.registry import export

        obj = context.active_object
        try:
            design, labels, nulls = meshio.read_design(obj)
            export(
                design.scaffold,
                bpy.path.abspath(self.filepath),
                labels,
                nulls,
                params=live.shape(context.scene.lkspace),  # the strands' shape as the panel sets it
                options=PrintOptions(thickness=self.thickness, clearance=self.clearance, scale=self.scale),
            )
        except LkspaceError as exc:
            self.report({"ERROR"}, live.panel_advice(str(exc)))
            return {"CANCELLED"}
        self.report({"INFO"}, f"wrote {self.filepath}")
        return {"FINISHED"}


class LKSPACE_OT_export_dna(FileOperator):  # noqa: N801
    """Write the design as DNA for oxDNA and oxView: NAME.top, NAME.dat and NAME.oxview (docs/dna.md)."""

    bl_idname = "lkspace.export_dna"
    bl_label = "Export DNA (oxDNA)"
    seed: bpy.props.IntProperty(name="Seed", default=0, min=0, description="Seed of the random bases")  # type: ignore[valid-type]

    extension = ".oxdna"  # NAME.oxdna: the three files are written beside it

    def execute(self, context: Any) -> set[str]:
        """Build the DNA with :func:`lkspace.dna.build.build` and write it (the path of ``lkspace export -o NAME.oxdna``)."""
        from lkspace.dna.build import build
        from lkspace.dna.oxdna import write

        obj = context.active_object
        try:
            design, labels, nulls = meshio.read_design(obj)
            if nulls is not None and nulls.any():
                raise LkspaceError("DNA export: null edge-sides are not supported (every strand is closed)")
            written = write(build(design.scaffold, labels, seed=self.seed), bpy.path.abspath(self.filepath))
        except LkspaceError as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        self.report({"INFO"}, f"wrote {', '.join(written)}")
        return {"FINISHED"}


CLASSES = (LKSPACE_OT_regenerate, LKSPACE_OT_identify, LKSPACE_OT_export, LKSPACE_OT_export_dna)
