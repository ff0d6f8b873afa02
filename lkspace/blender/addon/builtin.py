"""Built-in scaffolds in Blender: a finite one as a labelled mesh, a periodic one as a block.

``lkspace.add_scaffold`` adds a built-in (or file) scaffold as a mesh object carrying its
twists in ``lk_twist`` and its null sides in ``lk_null``, ready to edit.  A periodic
scaffold cannot be a Blender mesh (its faces wrap around a lattice), so
``lkspace.periodic_block`` adds a block of cells instead: the cells' faces as a wire mesh
and the strands cut at the block's faces, as ``lkspace export --block`` draws them.  Its
labels are edited in the operator (one per edge class), not on the mesh.
"""

from __future__ import annotations

from typing import Any

import bpy
import numpy as np

from lkspace.blender.meshdata import NULL, mesh_design
from lkspace.errors import LkspaceError
from lkspace.model.scaffold import Scaffold

from . import live, meshio, strands


def scaffold_object(scene: Any, scaffold: Scaffold, labels: np.ndarray, nulls: np.ndarray) -> Any:
    """Add ``scaffold`` to ``scene`` as a mesh object with ``labels`` and ``nulls`` as attributes.

    Faces are added without Blender's validation, so the two faces of a two-sided polygon
    (``dihedron:N``) both stay (Blender's own tools would merge them).
    """
    mesh = bpy.data.meshes.new(scaffold.name)
    mesh.from_pydata(scaffold.vertices.tolist(), [], scaffold.faces())
    mesh.update()
    obj = bpy.data.objects.new(scaffold.name, mesh)
    scene.collection.objects.link(obj)
    design = mesh_design(meshio.mesh_arrays(mesh), obj.name)
    meshio.write_labels(obj, design, labels)
    loop_nulls = np.zeros(len(mesh.loops), bool)
    loop_nulls[design.loop_of] = nulls
    meshio.write_attribute(mesh, NULL, "CORNER", "BOOLEAN", loop_nulls)
    return obj


class LKSPACE_OT_add_scaffold(bpy.types.Operator):  # noqa: N801
    """Add a built-in scaffold (or a scaffold file) as a mesh with its twists, and its strands."""

    bl_idname = "lkspace.add_scaffold"
    bl_label = "Add Scaffold"
    bl_options = {"REGISTER", "UNDO"}
    scaffold: bpy.props.StringProperty(name="Scaffold", default="tetrahedron")  # type: ignore[valid-type]
    twist: bpy.props.StringProperty(name="Twist", default="1", description="As --twist; empty: the scaffold's own")  # type: ignore[valid-type]

    def execute(self, context: Any) -> set[str]:
        """Load the scaffold with lkspace, add it, make it active and regenerate."""
        try:
            obj = add_scaffold(context, self.scaffold, self.twist)
        except LkspaceError as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        if obj.lkspace.message:
            self.report({"WARNING"}, obj.lkspace.message)
        return {"FINISHED"}


def add_scaffold(context: Any, name: str, twist: str) -> Any:
    """Add scaffold ``name`` with twists ``twist`` (a finite one as a mesh, a periodic one refused); return it."""
    from lkspace.io.sources import load
    from lkspace.io.twists import parse_twist

    scaffold = load(name)
    if scaffold.periodic:
        raise LkspaceError(f"{name} is periodic: add a block of it with Add Periodic Block", usage=True)
    if twist.strip():
        labels = parse_twist(scaffold, twist)
    elif scaffold.labels is not None:
        labels = scaffold.labels
    else:
        labels = np.zeros(scaffold.n_edges, np.int64)
    nulls = scaffold.nulls if scaffold.nulls is not None else np.zeros(scaffold.n_corners, bool)
    obj = scaffold_object(context.scene, scaffold, labels, nulls)
    context.view_layer.objects.active = obj
    live.regenerate(obj, context.scene)
    return obj


class LKSPACE_OT_periodic_block(bpy.types.Operator):  # noqa: N801
    """Add a block of a built-in periodic scaffold's strands (a tiling or honeycomb, e.g. tiling:square)."""

    bl_idname = "lkspace.periodic_block"
    bl_label = "Add Periodic Block"
    bl_options = {"REGISTER", "UNDO"}
    scaffold: bpy.props.StringProperty(name="Scaffold", default="tiling:square")  # type: ignore[valid-type]
    twist: bpy.props.StringProperty(name="Twist", default="1")  # type: ignore[valid-type]
    block: bpy.props.StringProperty(name="Block", default="4x4")  # type: ignore[valid-type]

    def execute(self, context: Any) -> set[str]:
        """Realize the block with lkspace and add its curves and its faces."""
        try:
            make_block(context.scene, self.scaffold, self.twist, self.block)
        except LkspaceError as exc:
            self.report({"ERROR"}, str(exc))
            return {"CANCELLED"}
        return {"FINISHED"}


def make_block(scene: Any, name: str, twist: str, block: str) -> Any:
    """Add a mesh object of the block's faces named ``name [block]`` with the block's strands; return it."""
    from lkspace.formats.colors import colour_slots
    from lkspace.geometry.block import block_faces, realize_block
    from lkspace.io.sources import load
    from lkspace.io.twists import parse_twist

    scaffold = load(name)
    if not scaffold.periodic:
        raise LkspaceError(f"{name} is not periodic: a block is made of a tiling or honeycomb's cells", usage=True)
    sizes = parse_sizes(block, scaffold.dim)
    real = realize_block(scaffold, parse_twist(scaffold, twist), None, None, sizes)
    assert real.block is not None
    polygons = block_faces(scaffold, real.block)
    points = np.vstack(polygons) if polygons else np.zeros((0, 3))
    starts = np.cumsum([0] + [len(p) for p in polygons])
    mesh = bpy.data.meshes.new(f"{name} [{block}]")
    mesh.from_pydata(points.tolist(), [], [list(range(s, e)) for s, e in zip(starts[:-1], starts[1:])])
    mesh.update()
    obj = bpy.data.objects.new(mesh.name, mesh)
    scene.collection.objects.link(obj)
    strands.build(obj, real, scene, colour_slots(real))
    obj.lkspace.components = real.trace.components
    obj.lkspace.holds_together = real.trace.holds_together
    obj.display_type = "WIRE"
    return obj


def parse_sizes(block: str, dim: int) -> list[int]:
    """``"4x4"`` -> ``[4, 4]`` (``dim`` numbers, each 1..20); :class:`LkspaceError` otherwise."""
    parts = block.lower().split("x")
    if len(parts) != dim or not all(p.strip().isdigit() and 1 <= int(p) <= 20 for p in parts):
        raise LkspaceError(f"block {block!r}: give {dim} sizes 1..20 such as {'x'.join(['3'] * dim)}", usage=True)
    return [int(p) for p in parts]


CLASSES = (LKSPACE_OT_add_scaffold, LKSPACE_OT_periodic_block)
