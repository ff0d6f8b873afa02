"""A scene preset for pictures of a design: camera fitted to the strands, lights, world, engine.

:func:`preset` works for Cycles (CPU), EEVEE (with a GPU; Cycles without) and Workbench;
:func:`render` writes a PNG.
Both are used by the ``lkspace.scene_preset`` operator and by ``python -m lkspace.blender
render`` (headless, for ``experiments/gallery.py --renderer blender``).
"""

from __future__ import annotations

from typing import Any

import bpy
import numpy as np
from mathutils import Vector

from lkspace.blender.engines import engine_to_use

from .strands import SOURCE

ENGINES = (
    ("CYCLES", "Cycles", "Path tracing (CPU), the best pictures"),
    ("BLENDER_EEVEE_NEXT", "EEVEE", "Fast, needs a GPU (without one: Cycles on the CPU)"),
    ("BLENDER_WORKBENCH", "Workbench", "Flat colours, instant, works anywhere"),
)
VIEW = np.array([1.0, -1.4, 0.9])
"""Direction from the design's centre to the camera."""


def strand_points(scene: Any) -> np.ndarray:
    """(n, 3) world positions of every strand curve point in ``scene`` (empty if none)."""
    parts = [np.zeros((0, 3))]
    for obj in scene.objects:
        if obj.type != "CURVE" or obj.get(SOURCE) is None or obj.hide_render:
            continue
        matrix = np.array(obj.matrix_world)
        for spline in obj.data.splines:
            co = np.zeros(4 * len(spline.points))
            spline.points.foreach_get("co", co)
            local = co.reshape(-1, 4)[:, :3]
            parts.append(local @ matrix[:3, :3].T + matrix[:3, 3])
    return np.vstack(parts)


def view_direction(points: np.ndarray) -> np.ndarray:
    """Return the unit vector from the design toward the camera: :data:`VIEW`, tipped toward a flat design's normal."""
    view = VIEW / np.linalg.norm(VIEW)
    if len(points) < 3:
        return view
    _, spread, axes = np.linalg.svd(points - points.mean(axis=0), full_matrices=False)
    if spread[2] > 0.3 * spread[0]:
        return view
    normal = axes[2] if axes[2] @ view >= 0 else -axes[2]
    tipped = 2 * normal + view
    return np.asarray(tipped / np.linalg.norm(tipped))


def fit_camera(scene: Any, points: np.ndarray, margin: float = 1.08) -> Any:
    """Place the scene's camera (created if needed) so that ``points`` fill the frame of the render size."""
    cam = scene.camera
    if cam is None:
        cam = bpy.data.objects.new("lkspace camera", bpy.data.cameras.new("lkspace camera"))
        scene.collection.objects.link(cam)
        scene.camera = cam
    if len(points) == 0:
        points = np.zeros((1, 3))
    cam.data.lens = 50
    cam.data.sensor_fit = "AUTO"  # the longer side of the picture spans the sensor width
    width, height = scene.render.resolution_x, scene.render.resolution_y
    wide = cam.data.sensor_width / 2 / cam.data.lens / margin
    tan_x, tan_y = (wide, wide * height / width) if width >= height else (wide * width / height, wide)
    centre = (points.min(axis=0) + points.max(axis=0)) / 2
    back = view_direction(points)
    right = np.cross([0.0, 0.0, 1.0], back)
    right = right / np.linalg.norm(right) if np.linalg.norm(right) > 1e-9 else np.array([1.0, 0.0, 0.0])
    up = np.cross(back, right)
    rel = points - centre
    # every point inside the view: its offset across <= (distance - its depth) * tan(half angle)
    reach = np.maximum(np.abs(rel @ right) / tan_x, np.abs(rel @ up) / tan_y) + rel @ back
    distance = max(float(reach.max()), 1e-6)
    cam.location = Vector((centre + distance * back).tolist())
    cam.rotation_mode = "QUATERNION"
    cam.rotation_quaternion = Vector((-back).tolist()).to_track_quat("-Z", "Y")
    cam.data.clip_start = distance / 100
    cam.data.clip_end = distance * 10
    return cam


def add_lights(scene: Any) -> None:
    """Add a key sun and a soft fill (replacing earlier lkspace lights)."""
    for name in ("lkspace key", "lkspace fill"):
        old = bpy.data.objects.get(name)
        if old is not None:
            bpy.data.objects.remove(old, do_unlink=True)
    for name, kind, energy, rotation in (
        ("lkspace key", "SUN", 3.0, (0.7, 0.2, 0.6)),
        ("lkspace fill", "SUN", 1.0, (-0.9, -0.3, -2.4)),
    ):
        light = bpy.data.lights.new(name, kind)
        light.energy = energy
        light.angle = 0.3
        obj = bpy.data.objects.new(name, light)
        obj.rotation_euler = rotation
        scene.collection.objects.link(obj)


def preset(scene: Any, engine: str = "CYCLES", size: tuple[int, int] | None = None, samples: int = 32) -> str:
    """Set up ``scene`` for a picture of its strands: camera, lights, a light grey world, ``engine``.

    ``size`` is the picture's ``(width, height)`` in pixels (default: the scene's).  The
    meshes the strands were made from are hidden from the render (not the viewport).
    Cycles denoises with OpenImageDenoise.  EEVEE on a machine without a GPU becomes Cycles
    on the CPU (:func:`lkspace.blender.engines.engine_to_use`): the one-line note saying so
    is returned (``""`` when the engine is the one asked for).
    """
    engine, note = engine_to_use(engine)
    points = strand_points(scene)
    for obj in scene.objects:  # the meshes the strands come from stay in the viewport, out of the picture
        if obj.type == "MESH" and bpy.data.collections.get(obj.name) is not None:
            obj.hide_render = True
    render = scene.render
    if size is not None:
        render.resolution_x, render.resolution_y = size
        render.resolution_percentage = 100
    fit_camera(scene, points)
    add_lights(scene)
    world = scene.world or bpy.data.worlds.new("lkspace world")
    scene.world = world
    world.color = (0.9, 0.9, 0.92)
    world.use_nodes = True
    background = world.node_tree.nodes.get("Background")
    if background is not None:
        background.inputs["Color"].default_value = (0.9, 0.9, 0.92, 1.0)
        background.inputs["Strength"].default_value = 0.6
    render.engine = engine
    render.film_transparent = False
    scene.view_settings.view_transform = "Standard"
    if engine == "CYCLES":
        scene.cycles.device = "CPU"
        scene.cycles.samples = samples
        scene.cycles.use_denoising = True
        scene.cycles.denoiser = "OPENIMAGEDENOISE"
    elif engine == "BLENDER_WORKBENCH":
        scene.display.shading.light = "STUDIO"
        scene.display.shading.color_type = "MATERIAL"
        scene.display.shading.show_cavity = False
    else:
        scene.eevee.taa_render_samples = samples
    return note


def render(scene: Any, path: str) -> None:
    """Render ``scene`` to the PNG file ``path``."""
    scene.render.image_settings.file_format = "PNG"
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True, scene=scene.name)
