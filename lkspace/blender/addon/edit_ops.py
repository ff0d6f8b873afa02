"""Operators that edit the labels of the active mesh: set, fill an orbit, randomize, solve, null sides.

Each writes the mesh's ``lk_twist`` (or ``lk_null``) attribute and then regenerates the
strands when the scene's live toggle is on.  Errors from lkspace are reported in one line
(the operator is cancelled, the mesh unchanged).
"""

from __future__ import annotations

from typing import Any

import bpy
import numpy as np

from lkspace.blender.editing import fill_orbit, random_labels
from lkspace.blender.meshdata import NULL, mesh_design
from lkspace.errors import LkspaceError
from lkspace.words import plural

from . import live, meshio


class MeshOperator(bpy.types.Operator):
    """Base of the operators working on the active mesh object."""

    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context: Any) -> bool:
        """Only with an active mesh object."""
        obj = context.active_object
        return obj is not None and obj.type == "MESH"

    def execute(self, context: Any) -> set[str]:
        """Run :meth:`apply`; report lkspace's errors as one line."""
        obj = context.active_object
        try:
            with meshio.edit_attributes(obj):
                self.apply(obj, context)
        except LkspaceError as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        if context.scene.lkspace.live:
            live.regenerate(obj, context.scene)
        return {"FINISHED"}

    def apply(self, obj: Any, context: Any) -> None:
        """Change the attributes of ``obj`` (object mode); subclasses override."""
        raise NotImplementedError


class LKSPACE_OT_set_twist(MeshOperator):  # noqa: N801 - Blender's naming convention
    """Set the twist of the selected edges."""

    bl_idname = "lkspace.set_twist"
    bl_label = "Set Twist"
    twist: bpy.props.IntProperty(name="Twist", default=1)  # type: ignore[valid-type]

    def apply(self, obj: Any, context: Any) -> None:
        """Write ``twist`` to the selected edges' ``lk_twist``."""
        mesh = obj.data
        values = meshio.twists(mesh)
        chosen = meshio.selected_edges(mesh)
        if len(chosen) == 0:
            raise LkspaceError("select the edges to set first")
        values[chosen] = self.twist
        meshio.write_attribute(mesh, "lk_twist", "EDGE", "INT", values.astype(np.int32))


class LKSPACE_OT_fill_orbit(MeshOperator):  # noqa: N801
    """Copy the active (or first selected) edge's twist to its orbit under the mesh's symmetry."""

    bl_idname = "lkspace.fill_orbit"
    bl_label = "Fill Orbit"
    mode: bpy.props.EnumProperty(  # type: ignore[valid-type]
        name="Symmetry",
        items=[
            ("rotations", "Rotations", "Rotations keep a twist"),
            ("isometries", "Isometries", "Mirrors too: a mirror image gets the opposite twist"),
        ],
    )

    def apply(self, obj: Any, context: Any) -> None:
        """Fill the orbit of the first selected face edge."""
        design, labels, _ = meshio.read_design(obj, evaluated=False)
        chosen = [int(design.edge_of[b]) for b in meshio.selected_edges(obj.data) if design.edge_of[b] >= 0]
        if not chosen:
            raise LkspaceError("select an edge whose twist to copy first")
        meshio.write_labels(obj, design, fill_orbit(design.scaffold, labels, chosen[0], self.mode))


class LKSPACE_OT_randomize(MeshOperator):  # noqa: N801
    """Give every edge a random twist from the label set (reproducible from the seed)."""

    bl_idname = "lkspace.randomize"
    bl_label = "Randomize"
    seed: bpy.props.IntProperty(name="Seed", default=0, min=0)  # type: ignore[valid-type]

    def apply(self, obj: Any, context: Any) -> None:
        """Draw labels from the scene's label set."""
        settings = context.scene.lkspace
        design, _, _ = meshio.read_design(obj, evaluated=False)
        labels = random_labels(design.scaffold, settings.label_set, self.seed, settings.no_zero)
        meshio.write_labels(obj, design, labels)


class LKSPACE_OT_solve(MeshOperator):  # noqa: N801
    """Find twists with exactly N components (lkspace's solver; labels from the label set)."""

    bl_idname = "lkspace.solve"
    bl_label = "Solve"
    components: bpy.props.IntProperty(name="Components", default=1, min=1)  # type: ignore[valid-type]

    def apply(self, obj: Any, context: Any) -> None:
        """Write the first solution, or report why there is none."""
        from lkspace.inverse.pipeline import SolveOptions, solve

        settings = context.scene.lkspace
        design, _, _ = meshio.read_design(obj, evaluated=False)
        result = solve(
            design.scaffold,
            self.components,
            label_set=settings.label_set,
            no_zero=settings.no_zero,
            options=SolveOptions(time_limit=settings.time_limit, seed=settings.seed),
        )
        if not result.solutions:
            raise LkspaceError(
                f"{obj.name}: no design with {plural(self.components, 'component')} from labels {settings.label_set} "
                f"({result.status}{': ' + result.reason if result.reason else ''})"
            )
        meshio.write_labels(obj, design, result.solutions[0].labels)


class LKSPACE_OT_set_null(MeshOperator):  # noqa: N801
    """Mark the face-sides on the selected edges as null (cut); only those of selected faces if any are."""

    bl_idname = "lkspace.set_null"
    bl_label = "Set Null Sides"
    null: bpy.props.BoolProperty(name="Null", default=True)  # type: ignore[valid-type]

    def apply(self, obj: Any, context: Any) -> None:
        """Write ``null`` to the ``lk_null`` of the chosen face corners."""
        mesh = obj.data
        arrays = meshio.mesh_arrays(mesh)
        design = mesh_design(arrays, obj.name)
        edge_chosen = np.zeros(len(mesh.edges), bool)
        edge_chosen[meshio.selected_edges(mesh)] = True
        side_chosen = edge_chosen[design.blender_edge[design.scaffold.side_edge]]
        faces = meshio.selected_faces(mesh)
        if faces.any():
            side_chosen &= faces[design.scaffold.corner_face]
        if not side_chosen.any():
            raise LkspaceError("select the edges (and faces) whose sides to cut first")
        values = meshio.loop_nulls(mesh)
        values[design.loop_of[side_chosen]] = self.null
        meshio.write_attribute(mesh, NULL, "CORNER", "BOOLEAN", values)


CLASSES = (LKSPACE_OT_set_twist, LKSPACE_OT_fill_orbit, LKSPACE_OT_randomize, LKSPACE_OT_solve, LKSPACE_OT_set_null)
