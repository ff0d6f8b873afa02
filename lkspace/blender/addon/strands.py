"""Strands as Blender curve objects: one per component, in a collection named after the mesh.

The collection made for a mesh object is remembered on it (``object.lkspace.strands``), so
after a rename the next build renames that collection and replaces its curves rather than
leaving them beside a new one.  Each curve is a child of the mesh object: it follows the
object's moves without a rebuild.

Each curve is a poly spline through the realized points (``lkspace.realize``) with a
round bevel (the tube) and the material of its colour slot: slot ``k`` is the ``k``-th
strand in :func:`lkspace.blender.editing.component_order`, coloured by lkspace's palette
(:func:`lkspace.formats.colors.colors`), and the materials ``lkspace strand 00``, ... are
shared by every design, so a strand keeps its colour across edits.  A periodic block takes
the slots of ``lkspace export`` (:func:`lkspace.formats.colors.colour_slots`): a thread's
class colour in every cell, and a ring's copies coloured by their cells' tones.
"""

from __future__ import annotations

from typing import Any

import bpy
import numpy as np

from lkspace.blender.editing import component_order
from lkspace.formats.colors import colors
from lkspace.geometry.realization import Realization

SOURCE = "lkspace_source"
"""Custom property of a strand collection and its curves: the name of the mesh object they show."""


def material(slot: int) -> Any:
    """Return the shared material of colour slot ``slot`` (created on first use)."""
    name = f"lkspace strand {slot:02d}"
    mat = bpy.data.materials.get(name)
    rgb = [float(x) for x in colors(slot + 1)[slot]]
    if mat is None:
        mat = bpy.data.materials.new(name)
        mat.use_nodes = True
        bsdf = mat.node_tree.nodes.get("Principled BSDF")
        if bsdf is not None:
            bsdf.inputs["Base Color"].default_value = (*rgb, 1.0)
            bsdf.inputs["Roughness"].default_value = 0.35
    mat.diffuse_color = (*rgb, 1.0)  # the viewport's and Workbench's colour
    return mat


def strand_collection(obj: Any, scene: Any) -> Any:
    """Return the strand collection of mesh object ``obj`` named after it, linked into ``scene`` (created if needed)."""
    made = bpy.data.collections.get(obj.lkspace.strands) if obj.lkspace.strands else None
    coll = made if made is not None and made.get(SOURCE) is not None else bpy.data.collections.get(obj.name)
    if coll is None:
        coll = bpy.data.collections.new(obj.name)
    if coll.name != obj.name and bpy.data.collections.get(obj.name) is None:
        coll.name = obj.name  # the object was renamed: its collection follows
    coll[SOURCE] = obj.name
    obj.lkspace.strands = coll.name
    if coll.name not in scene.collection.children and not any(
        c.name == coll.name for c in scene.collection.children_recursive
    ):
        scene.collection.children.link(coll)
    return coll


def clear(coll: Any) -> None:
    """Remove the strand curves (objects and their curve data) from ``coll``."""
    for old in list(coll.objects):
        if old.get(SOURCE) is None:
            continue
        data = old.data
        bpy.data.objects.remove(old, do_unlink=True)
        if data is not None and data.users == 0:
            bpy.data.curves.remove(data)


def curve_object(name: str, points: np.ndarray, closed: bool, radius: float, slot: int, resolution: int = 3) -> Any:
    """Make a curve object through ``points (n, 3)`` with a round bevel of ``radius`` (``resolution``: Blender's bevel resolution)."""
    data = bpy.data.curves.new(name, type="CURVE")
    data.dimensions = "3D"
    data.bevel_mode = "ROUND"
    data.bevel_depth = radius
    data.bevel_resolution = resolution
    data.fill_mode = "FULL"
    data.use_fill_caps = not closed
    spline = data.splines.new("POLY")
    spline.points.add(len(points) - 1)
    spline.points.foreach_set("co", np.column_stack([points, np.ones(len(points))]).reshape(-1))
    spline.use_cyclic_u = closed
    data.materials.append(material(slot))
    return bpy.data.objects.new(name, data)


def build(
    obj: Any, real: Realization, scene: Any, curve_slots: np.ndarray | None = None, resolution: int = 3
) -> list[Any]:
    """Replace the strand curves of mesh object ``obj`` with those of ``real``; return them.

    Curves are children of the mesh object (they follow its moves); ``curve_slots[k]`` is the
    colour slot of curve ``k`` (default: its strand's place in :func:`component_order`).  Each curve carries the
    custom properties ``lk_strand`` (its strand in lkspace's trace) and ``lk_faces`` (the
    polygon of each corner it turns around, in order: ``faces`` of ``lkspace trace --json``).
    """
    coll = strand_collection(obj, scene)
    clear(coll)
    if curve_slots is None:
        order = np.empty(real.trace.components, np.int64)
        order[component_order(real.trace)] = np.arange(real.trace.components)
        curve_slots = order[real.strand_of]
    made = []
    for k, points in enumerate(real.curves):
        slot = int(curve_slots[k])
        name = f"{obj.name}.strand.{k:02d}"
        points = np.asarray(points, np.float64)
        curve = curve_object(name, points, bool(real.closed[k]), real.tube_radius, slot, resolution)
        curve[SOURCE] = obj.name
        curve["lk_strand"] = int(real.strand_of[k])
        curve["lk_faces"] = real.trace.strand_faces(int(real.strand_of[k])).tolist()
        curve.parent = obj  # object-space points: the curve follows the mesh object wherever it goes
        coll.objects.link(curve)
        made.append(curve)
    return made
