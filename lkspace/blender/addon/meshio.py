"""Reading a Blender mesh into lkspace and writing labels back to its attributes.

The strands are made from the *evaluated* mesh, the one Blender shows: the object's
modifiers applied (those showing in the viewport, and in Edit Mode those showing there)
and its Edit Mode changes included (:func:`evaluated_mesh`).  Modifiers carry
``lk_twist`` and ``lk_null`` along as they carry any attribute: Subdivision, Array,
Mirror, Solidify, Bevel, Triangulate, Edge Split, Weld and the deforming ones keep an
edge's twist on the edges it becomes (edges they add inside a face get 0); Remesh and
Skin drop the attributes and Wireframe and Screw zero them, which :func:`read_design`
refuses in one line rather than draw every strand with twist 0.

The labels are written on the base mesh (``obj.data``), whose edges the user selects, so
the edit operators read that one (``read_design(obj, evaluated=False)``); in Edit Mode it
is flushed first (:func:`readable_mesh`), and operators that write go through
:func:`edit_attributes`, which leaves Edit Mode for the write and comes back.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import bpy
import numpy as np

from lkspace.blender.meshdata import NULL, TWIST, MeshArrays, MeshDesign, check_attribute, mesh_design, whole_twists
from lkspace.errors import LabelError


@contextmanager
def readable_mesh(obj: Any) -> Iterator[Any]:
    """Yield the mesh of ``obj`` with its attributes readable.

    In Edit Mode the changes are flushed to the mesh, and a temporary copy is read: there
    ``mesh.attributes`` shows the edit mesh, whose boolean corner layers Python cannot read.
    """
    if obj.mode != "EDIT":
        yield obj.data
        return
    obj.update_from_editmode()
    copy = obj.data.copy()
    try:
        yield copy
    finally:
        bpy.data.meshes.remove(copy)


@contextmanager
def evaluated_mesh(obj: Any, depsgraph: Any = None) -> Iterator[Any]:
    """Yield the mesh of ``obj`` as Blender evaluates it (modifiers applied), a temporary copy freed afterwards.

    ``depsgraph`` is the evaluated dependency graph to read it from (default: the context's,
    brought up to date).
    """
    evaluated = obj.evaluated_get(depsgraph or bpy.context.evaluated_depsgraph_get())
    mesh = evaluated.to_mesh()
    try:
        yield mesh
    finally:
        evaluated.to_mesh_clear()


def mesh_arrays(mesh: Any) -> MeshArrays:
    """Copy the vertices, edges and polygons of a ``bpy.types.Mesh`` into :class:`MeshArrays`."""

    def get(collection: Any, name: str, count: int, dtype: type, width: int = 1) -> np.ndarray:
        out: np.ndarray = np.zeros(count * width, dtype)
        collection.foreach_get(name, out)
        return out.reshape(-1, width) if width > 1 else out

    return MeshArrays(
        vertices=get(mesh.vertices, "co", len(mesh.vertices), np.float64, 3),
        edges=get(mesh.edges, "vertices", len(mesh.edges), np.int64, 2),
        loop_starts=get(mesh.polygons, "loop_start", len(mesh.polygons), np.int64),
        loop_totals=get(mesh.polygons, "loop_total", len(mesh.polygons), np.int64),
        loop_vertices=get(mesh.loops, "vertex_index", len(mesh.loops), np.int64),
    )


def attribute(mesh: Any, name: str) -> Any:
    """Return attribute ``name`` (:data:`TWIST` or :data:`NULL`) of ``mesh``, ``None`` if absent; refuse one of the wrong domain or type."""
    found = mesh.attributes.get(name)
    if found is not None:
        check_attribute(name, found.domain, found.data_type)
    return found


def twists(mesh: Any) -> np.ndarray:
    """(n_blender_edges,) int64: the ``lk_twist`` of every edge (0 where unset); a float one must hold whole numbers."""
    values = np.zeros(len(mesh.edges), np.int64)
    found = attribute(mesh, TWIST)
    if found is not None and found.data_type == "FLOAT":
        floats = np.zeros(len(mesh.edges), np.float32)
        found.data.foreach_get("value", floats)
        return whole_twists(floats)
    if found is not None:
        ints = np.zeros(len(mesh.edges), np.int32)
        found.data.foreach_get("value", ints)
        values[:] = ints
    return values


def loop_nulls(mesh: Any) -> np.ndarray:
    """(n_loops,) bool: the ``lk_null`` of every face corner (none when the mesh has no ``lk_null``)."""
    out = np.zeros(len(mesh.loops), bool)
    found = attribute(mesh, NULL)
    if found is not None:
        found.data.foreach_get("value", out)
    return out


def read_design(obj: Any, evaluated: bool = True, depsgraph: Any = None) -> tuple[MeshDesign, np.ndarray, np.ndarray]:
    """Return the scaffold of mesh object ``obj`` with its labels and null sides in lkspace's order.

    ``evaluated``: the mesh with its modifiers applied (:func:`evaluated_mesh`, from
    ``depsgraph``), else the base mesh whose edges carry the labels.  Modifiers that leave
    no twist where the base mesh has some are refused (:class:`~lkspace.errors.LabelError`).
    """
    with evaluated_mesh(obj, depsgraph) if evaluated else readable_mesh(obj) as mesh:
        design = mesh_design(mesh_arrays(mesh), obj.name)
        edge_twists = twists(mesh)
        if evaluated and not edge_twists.any():
            check_modifiers_keep_twists(obj)
        return design, design.labels(edge_twists), design.nulls(loop_nulls(mesh))


def check_modifiers_keep_twists(obj: Any) -> None:
    """Refuse modifiers of ``obj`` that turn a base mesh with twists into one without (Remesh, Skin, Wireframe, Screw)."""
    shown = [m.name for m in obj.modifiers if (m.show_in_editmode if obj.mode == "EDIT" else m.show_viewport)]
    if not shown:
        return
    with readable_mesh(obj) as base:
        if not twists(base).any():
            return
    raise LabelError(
        f"{obj.name}: its modifiers ({', '.join(shown)}) leave no lk_twist on the mesh they make, so every "
        "strand would have twist 0; hide the modifier that drops it (Remesh, Skin, Wireframe, Screw do), "
        "or apply the modifiers and label the result"
    )


def write_attribute(mesh: Any, name: str, domain: str, kind: str, values: np.ndarray) -> None:
    """Write ``values`` to attribute ``name``, creating it (``kind`` ``INT`` or ``BOOLEAN``) if needed."""
    attribute = mesh.attributes.get(name)
    if attribute is not None and (attribute.domain != domain or attribute.data_type != kind):
        mesh.attributes.remove(attribute)
        attribute = None
    if attribute is None:
        attribute = mesh.attributes.new(name, kind, domain)
    attribute.data.foreach_set("value", values)
    mesh.update()


def write_labels(obj: Any, design: MeshDesign, labels: np.ndarray) -> None:
    """Set ``lk_twist`` of the face edges of ``obj`` to ``labels`` (lkspace order); loose edges keep theirs."""
    mesh = obj.data
    values = design.edge_twists(labels, twists(mesh)).astype(np.int32)
    write_attribute(mesh, TWIST, "EDGE", "INT", values)


def selected_edges(mesh: Any) -> np.ndarray:
    """Return the indices of the selected Blender edges."""
    selected = np.zeros(len(mesh.edges), bool)
    mesh.edges.foreach_get("select", selected)
    return np.flatnonzero(selected)


def selected_faces(mesh: Any) -> np.ndarray:
    """(n_polygons,) bool: which polygons are selected."""
    selected = np.zeros(len(mesh.polygons), bool)
    mesh.polygons.foreach_get("select", selected)
    return selected


@contextmanager
def edit_attributes(obj: Any) -> Iterator[Any]:
    """Yield the mesh of ``obj`` for writing attributes; from Edit Mode, leave it and come back."""
    editing = obj.mode == "EDIT"
    if editing:
        bpy.ops.object.mode_set(mode="OBJECT")
    try:
        yield obj.data
    finally:
        if editing:
            bpy.ops.object.mode_set(mode="EDIT")
