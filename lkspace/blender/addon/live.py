"""Regenerating the strands of a mesh, on demand and live (a depsgraph handler).

:func:`regenerate` reads the mesh, traces and realizes it with lkspace and rebuilds the
curves; the result (components, holding together, or the error) is kept on the object's
``lkspace`` properties for the panel and for scripts.  The handler regenerates the active
mesh after an edit when the scene's ``lkspace.live`` toggle is on and the mesh, its
labels or its null sides changed since the last build (:func:`state_key`).  With the
scene's ``lkspace.relax`` on, the curves are relaxed (:func:`lkspace.relax`).
"""

from __future__ import annotations

import hashlib
from typing import Any

import bpy
import numpy as np

from lkspace.blender.meshdata import MeshDesign
from lkspace.errors import LkspaceError
from lkspace.geometry.params import RealizeOptions
from lkspace.geometry.realization import realize
from lkspace.strands.tracing import trace

from . import meshio, strands

MEASURE_FACES = 150
"""Live rebuilds of meshes with more faces skip the clearance measurement (seconds at 500 faces)."""
BUSY: set[str] = set()
"""Objects being regenerated now (their own updates must not start another round)."""


def state_key(design: MeshDesign, labels: np.ndarray, nulls: np.ndarray, obj: Any, relax: bool = False) -> str:
    """Return a digest of everything the strands depend on: mesh, labels, nulls, placement, relaxed or not."""
    h = hashlib.sha256(design.scaffold.content_hash().encode())
    for arr in (labels, nulls, np.array(obj.matrix_world, np.float64), np.array([relax])):
        h.update(np.ascontiguousarray(arr).tobytes())
    return h.hexdigest()[:16]


def regenerate(
    obj: Any, scene: Any, force: bool = True, measure: bool | None = None, relax: bool | None = None
) -> bool:
    """Rebuild the strand curves of mesh object ``obj``; return whether it worked.

    Errors of lkspace (a mesh it cannot use, strands that would touch, a relaxation it
    refuses) are not raised: they go to ``obj.lkspace.message`` and the old curves stay.
    ``force=False`` skips the work when nothing changed since the last build.  ``measure``
    checks the clearance between strands (``lkspace.realize``'s check; it also thins the
    tubes to fit); by default only meshes of at most :data:`MEASURE_FACES` faces are
    measured.  ``relax`` builds the curves of :func:`lkspace.relax` (default: the scene's
    ``lkspace.relax``).
    """
    result = obj.lkspace
    if relax is None:
        settings = getattr(scene, "lkspace", None)
        relax = bool(settings.relax) if settings is not None else False
    BUSY.add(obj.name)
    try:
        design, labels, nulls = meshio.read_design(obj)
        key = state_key(design, labels, nulls, obj, relax)
        if measure is None:
            measure = design.scaffold.n_faces <= MEASURE_FACES
        if not force and key == result.key and (result.measured or not measure):
            return True
        traced = trace(design.scaffold, labels, nulls)
        options = RealizeOptions(embedding="refuse" if measure else "later", trace=traced)
        real = realize(design.scaffold, labels, nulls, relax=relax, options=options)
        strands.build(obj, real, scene)
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
        result.message = str(exc)
        return False
    finally:
        BUSY.discard(obj.name)


@bpy.app.handlers.persistent
def on_depsgraph_update(scene: Any, depsgraph: Any) -> None:
    """Regenerate the active mesh after an edit, when ``scene.lkspace.live`` is on."""
    settings = getattr(scene, "lkspace", None)
    obj = bpy.context.view_layer.objects.active if bpy.context.view_layer else None
    if settings is None or not settings.live or obj is None or obj.type != "MESH" or obj.name in BUSY:
        return
    if not obj.lkspace.key:  # never regenerated: live updates start with the first Regenerate
        return
    for update in depsgraph.updates:
        if getattr(update.id, "original", None) in (obj, obj.data):
            regenerate(obj, scene, force=False)
            return


def install_handler() -> None:
    """Add :func:`on_depsgraph_update` to Blender's handlers (once)."""
    if on_depsgraph_update not in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.append(on_depsgraph_update)


def remove_handler() -> None:
    """Take :func:`on_depsgraph_update` out of Blender's handlers."""
    if on_depsgraph_update in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.remove(on_depsgraph_update)
