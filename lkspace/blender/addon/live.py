"""Regenerating the strands of a mesh, on demand and live (a depsgraph handler).

:func:`regenerate` reads the mesh, traces and realizes it with lkspace and rebuilds the
curves; the result (components, holding together, or the error) is kept on the object's
``lkspace`` properties for the panel and for scripts.  The handler regenerates the active
mesh after an edit when the scene's ``lkspace.live`` toggle is on and the mesh, its
labels or its null sides changed since the last build (:func:`state_key`): moving, turning
or scaling the object rebuilds nothing (the curves are its children and follow it).  With the
scene's ``lkspace.relax`` on, the curves are relaxed (:func:`lkspace.relax`).  The shape
controls of the panel (inset, normal offset, tube radius) go to :class:`GeometryParams`, and
lkspace's advice is reworded to name those controls (:func:`panel_advice`).  The mesh read is
the evaluated one, modifiers applied (:func:`.meshio.evaluated_mesh`): changing a
modifier rebuilds the strands like an edit of the mesh, a move does not.
"""

from __future__ import annotations

import hashlib
from dataclasses import replace
from typing import Any

import bpy
import numpy as np

from lkspace.blender.meshdata import MeshDesign
from lkspace.errors import LkspaceError
from lkspace.geometry.params import GeometryParams, RealizeOptions
from lkspace.geometry.realization import realize
from lkspace.strands.tracing import trace

from . import meshio, strands

MEASURE_FACES = 150
"""Live rebuilds of meshes with more faces are previews: not smoothed, clearance not measured (seconds at 500 faces)."""
PREVIEW_COARSER = 2
"""A preview samples its curves this many times more coarsely (points per helix turn, edge, corner)."""
PREVIEW_RESOLUTION = 1
"""A preview's tubes have at most this bevel resolution (the panel's *Resolution*, 3 by default, otherwise)."""
BUSY: set[str] = set()
"""Objects being regenerated now (their own updates must not start another round)."""


CONTROLS = {
    "(try a smaller `radius` or `normal_offset`)": (
        "(try a smaller Inset or Normal offset in the panel; faces of the mesh that cross or nearly touch need mending first)"
    ),
    "`radius`": "Inset",
    "`normal_offset`": "Normal offset",
    "`tube_radius`": "Tube radius",
    "(or a smaller block)": "(or a mesh with fewer faces)",
    "max_points: ": "",
}
"""lkspace's advice -> the panel's words for it: the controls the panel has (Shape row)."""


def panel_advice(message: str) -> str:
    """Return lkspace's error ``message`` with the parameters it advises named as the panel's controls."""
    for said, control in CONTROLS.items():
        message = message.replace(said, control)
    return message


def shape(settings: Any) -> GeometryParams:
    """Return the shape the panel asks for: ``0`` on a control means lkspace's default for the mesh."""
    if settings is None:
        return GeometryParams()
    radius, offset, tube = (float(getattr(settings, k)) for k in ("radius", "normal_offset", "tube_radius"))
    return GeometryParams(radius=radius or None, normal_offset=offset or None, tube_radius=tube or None)


def preview(params: GeometryParams) -> GeometryParams:
    """Return the shape of a preview of ``params``: unsmoothed (nothing to prove first), :data:`PREVIEW_COARSER` times coarser.

    Half the points, and tubes of bevel resolution :data:`PREVIEW_RESOLUTION`, cut what
    Blender then spends evaluating the tubes: a live edit of a 512-face sphere takes about
    0.2 s instead of 0.5 s (``results/bench_blender.md``).
    """
    return replace(
        params,
        smooth=False,
        samples_per_turn=max(1, params.samples_per_turn // PREVIEW_COARSER),
        edge_samples=max(1, params.edge_samples // PREVIEW_COARSER),
        corner_samples=max(2, params.corner_samples // PREVIEW_COARSER),
    )


def state_key(
    design: MeshDesign, labels: np.ndarray, nulls: np.ndarray, relax: bool = False, params: GeometryParams | None = None
) -> str:
    """Return a digest of everything the strands depend on: mesh, labels, nulls, relaxed or not, the shape asked for.

    Not the object's placement: the curves are its children, so a move needs no rebuild.
    """
    h = hashlib.sha256(design.scaffold.content_hash().encode())
    for arr in (labels, nulls, np.array([relax])):
        h.update(np.ascontiguousarray(arr).tobytes())
    h.update(repr(params).encode())
    return h.hexdigest()[:16]


def regenerate(
    obj: Any,
    scene: Any,
    force: bool = True,
    measure: bool | None = None,
    relax: bool | None = None,
    depsgraph: Any = None,
) -> bool:
    """Rebuild the strand curves of mesh object ``obj``; return whether it worked.

    Errors of lkspace (a mesh it cannot use, strands that would touch, a relaxation it
    refuses) are not raised: they go to ``obj.lkspace.message`` and the old curves stay.
    ``force=False`` skips the work when nothing changed since the last build.  ``measure``
    checks the clearance between strands (``lkspace.realize``'s check; it also thins the
    tubes to fit) and smooths them, the smoothing being proved safe by that check; without
    it the curves are a :func:`preview`, the construction's polylines sampled more coarsely
    (a 512-face sphere realized in 0.03 s instead of 1.5 to 4 s).  By default only meshes of at most
    :data:`MEASURE_FACES` faces are measured.  ``relax`` builds the curves of :func:`lkspace.relax` (default: the scene's
    ``lkspace.relax``).  ``depsgraph``: the evaluated dependency graph the mesh is read
    from (default: the context's).
    """
    result = obj.lkspace
    settings = getattr(scene, "lkspace", None)
    if relax is None:
        relax = bool(settings.relax) if settings is not None else False
    BUSY.add(obj.name)
    try:
        design, labels, nulls = meshio.read_design(obj, depsgraph=depsgraph)
        params = shape(settings)
        key = state_key(design, labels, nulls, relax, params)
        if measure is None:
            measure = design.scaffold.n_faces <= MEASURE_FACES
        if not force and key == result.key and (result.measured or not measure):
            return True
        traced = trace(design.scaffold, labels, nulls)
        options = RealizeOptions(embedding="refuse" if measure else "later", trace=traced)
        drawn = params if measure else preview(params)
        real = realize(design.scaffold, labels, nulls, drawn, relax=relax, options=options)
        resolution = settings.resolution if settings is not None else 3
        strands.build(obj, real, scene, resolution=resolution if measure else min(resolution, PREVIEW_RESOLUTION))
        result.relaxed = relax
        result.components = traced.components
        result.holds_together = traced.holds_together
        result.open_strands = int(np.sum(~traced.closed))
        result.message = ""
        result.measured = measure
        if result.key != key:
            result.knot = ""
        result.key = key
        return True
    except LkspaceError as exc:
        result.message = panel_advice(str(exc))
        return False
    finally:
        BUSY.discard(obj.name)


@bpy.app.handlers.persistent
def on_depsgraph_update(scene: Any, depsgraph: Any) -> None:
    """Regenerate the active mesh after an edit of its mesh data or modifiers (not a move), when ``scene.lkspace.live`` is on."""
    settings = getattr(scene, "lkspace", None)
    obj = bpy.context.view_layer.objects.active if bpy.context.view_layer else None
    if settings is None or not settings.live or obj is None or obj.type != "MESH" or obj.name in BUSY:
        return
    if not obj.lkspace.key:  # never regenerated: live updates start with the first Regenerate
        return
    for update in depsgraph.updates:
        original = getattr(update.id, "original", None)
        if original is obj.data or (original is obj and update.is_updated_geometry):
            regenerate(obj, scene, force=False, depsgraph=depsgraph)
            return


def install_handler() -> None:
    """Add :func:`on_depsgraph_update` to Blender's handlers (once)."""
    if on_depsgraph_update not in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.append(on_depsgraph_update)


def remove_handler() -> None:
    """Take :func:`on_depsgraph_update` out of Blender's handlers."""
    if on_depsgraph_update in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.remove(on_depsgraph_update)
