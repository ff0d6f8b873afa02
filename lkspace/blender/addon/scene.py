"""A scene preset for pictures of a design: camera fitted to the strands, lights, world, engine.

:func:`preset` works for Cycles (CPU), EEVEE (with a GPU; Cycles without) and Workbench;
:func:`render` writes a PNG.
Both are used by the ``lkspace.scene_preset`` operator and by ``python -m lkspace.blender
render`` (headless, for ``experiments/gallery.py --renderer blender``).
"""

from __future__ import annotations

from typing import Any, NamedTuple

import bpy
import numpy as np
from mathutils import Matrix, Vector

from lkspace.blender.engines import engine_to_use
from lkspace.geometry.clearance import check_embedding, tightest_bend

from .strands import SOURCE

ENGINES = (
    ("CYCLES", "Cycles", "Path tracing (CPU), the best pictures"),
    ("BLENDER_EEVEE_NEXT", "EEVEE", "Fast, needs a GPU (without one: Cycles on the CPU)"),
    ("BLENDER_WORKBENCH", "Workbench", "Flat colours, instant, works anywhere"),
)
VIEW = np.array([1.0, -1.4, 0.9])
"""Direction from the centre of a design in 3D to the camera."""
TILT = np.radians(20.0)
"""A flat design is seen from this far off its normal."""
TUBE_SHARE, GAP_SHARE, BEND_SHARE = 0.01, 0.3, 0.9
"""A picture's tubes: radius up to 1% of the design's size, 0.3 of the closest approach, 0.9 of the tightest bend."""


def strand_curves(scene: Any) -> list[Strand]:
    """Every strand curve rendered in ``scene``: its object, world points and tube radius (:class:`Strand`)."""
    found = []
    for obj in scene.objects:
        if obj.type != "CURVE" or obj.get(SOURCE) is None or obj.hide_render:
            continue
        matrix = np.array(obj.matrix_world)
        scale = float(np.cbrt(abs(np.linalg.det(matrix[:3, :3])))) or 1.0
        for spline in obj.data.splines:
            co = np.zeros(4 * len(spline.points))
            spline.points.foreach_get("co", co)
            local = co.reshape(-1, 4)[:, :3]
            points = local @ matrix[:3, :3].T + matrix[:3, 3]
            found.append(Strand(obj, points, bool(spline.use_cyclic_u), obj.data.bevel_depth * scale, scale))
    return found


class Strand(NamedTuple):
    """A strand curve of the scene, in world space."""

    obj: Any
    points: np.ndarray
    """(n, 3) float64"""
    closed: bool
    radius: float
    """Its tube's radius (world units)."""
    scale: float
    """World units per unit of the curve's own space."""


def strand_points(scene: Any) -> np.ndarray:
    """(n, 3) world positions of every strand curve point in ``scene`` (empty if none)."""
    return np.vstack([np.zeros((0, 3))] + [s.points for s in strand_curves(scene)])


def thicken_tubes(strands: list[Strand]) -> float:
    """Thicken the tubes of ``strands`` toward :data:`TUBE_SHARE` of the design's size, as their clearance allows; return the radius.

    A tube keeps lkspace's radius when that is thicker already; otherwise it becomes
    ``min(TUBE_SHARE * size, GAP_SHARE * closest, BEND_SHARE * tightest bend)``: ``size``
    the diagonal of the strands' bounding box, ``closest`` the smallest distance between
    distinct pieces of the strands (:func:`lkspace.geometry.clearance.check_embedding`),
    so thickened tubes still stay apart, and no tube folds where a strand bends most.  A
    block of 4 x 4 chainmail rings (lkspace's tubes, 0.03 of an edge, are 1% of the
    picture) gets tubes 1.8 times as thick; a cube's, 5% of the picture, stay.
    """
    if not strands:
        return 0.0
    points = np.vstack([s.points for s in strands])
    size = float(np.linalg.norm(points.max(axis=0) - points.min(axis=0)))
    curves, closed = [s.points for s in strands], np.array([s.closed for s in strands])
    least = min(s.radius for s in strands)
    want = TUBE_SHARE * size
    if want <= least:
        return least
    closest, _ = check_embedding(curves, closed, 1e-3 * size, size / 5)  # finds distances up to 6% of the size
    radius = max(least, min(want, GAP_SHARE * closest, BEND_SHARE * tightest_bend(curves, closed).radius))
    for strand in strands:
        strand.obj.data.bevel_depth = max(strand.radius, radius) / strand.scale
    return radius


def view_axes(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return unit vectors ``(back, up)``: from the design toward the camera, and the picture's up.

    A design in 3D is seen from :data:`VIEW`, the world's Z up.  A flat one (a sheet of
    chainmail, a tiling's block) is seen from about 20 degrees off its normal, squarely: the
    sides of its smallest bounding rectangle in its plane run along the picture's sides (the
    longer one across), its far side up, as a sheet on a table is seen from in front.
    """
    view = VIEW / np.linalg.norm(VIEW)
    up = np.array([0.0, 0.0, 1.0])
    if len(points) < 3:
        return view, up
    _, spread, axes = np.linalg.svd(points - points.mean(axis=0), full_matrices=False)
    if spread[2] > 0.3 * spread[0]:
        return view, up
    normal = axes[2] if axes[2] @ view >= 0 else -axes[2]
    flat = (points - points.mean(axis=0)) @ axes[:2].T
    angles = np.radians(np.arange(0.0, 90.0, 1.0))
    turns = np.stack([np.cos(angles), np.sin(angles)], axis=1)  # (n_angles, 2): the rectangle's first side
    along, across = flat @ turns.T, flat @ np.stack([-turns[:, 1], turns[:, 0]], axis=1).T
    areas = np.ptp(along, axis=0) * np.ptp(across, axis=0)
    best = int(np.argmin(areas))
    side = turns[best, 0] * axes[0] + turns[best, 1] * axes[1]
    if np.ptp(along[:, best]) < np.ptp(across[:, best]):  # the longer side across the picture
        side = np.cross(normal, side)
    far = np.cross(normal, side)
    back = np.cos(TILT) * normal - np.sin(TILT) * far
    return back / np.linalg.norm(back), far


def fit_camera(scene: Any, strands: list[Strand], margin: float = 1.08) -> Any:
    """Place the scene's camera (created if needed) so that the tubes of ``strands`` fill the frame of the render size.

    The camera stands back along :func:`view_axes` far enough for a 50 mm lens to see every
    tube; then the lens zooms and shifts so that the tubes' picture is centred in the frame
    with ``margin`` (8%) to spare on its tighter side (zooming keeps the perspective).
    """
    cam = scene.camera
    if cam is None:
        cam = bpy.data.objects.new("lkspace camera", bpy.data.cameras.new("lkspace camera"))
        scene.collection.objects.link(cam)
        scene.camera = cam
    points = np.vstack([np.zeros((0, 3))] + [s.points for s in strands])
    radii = np.concatenate([np.zeros(0)] + [np.full(len(s.points), s.radius) for s in strands])
    if len(points) == 0:
        points, radii = np.zeros((1, 3)), np.zeros(1)
    cam.data.sensor_fit = "AUTO"  # the longer side of the picture spans the sensor width
    width, height = scene.render.resolution_x, scene.render.resolution_y
    frame_x, frame_y = (1.0, height / width) if width >= height else (width / height, 1.0)
    wide = cam.data.sensor_width / 2 / 50.0  # a 50 mm lens: half the frame's longer side, per unit of depth
    centre = (points.min(axis=0) + points.max(axis=0)) / 2
    back, up = view_axes(points)
    right = np.cross(up, back)
    right = right / np.linalg.norm(right) if np.linalg.norm(right) > 1e-9 else np.array([1.0, 0.0, 0.0])
    up = np.cross(back, right)
    rel = points - centre
    # every tube in view: its offset across plus its radius <= (distance - its depth) * tan(half angle)
    across = np.maximum((np.abs(rel @ right) + radii) / (wide * frame_x), (np.abs(rel @ up) + radii) / (wide * frame_y))
    distance = max(float((across + rel @ back + radii).max()), 1e-6)
    depth = distance - rel @ back  # from the camera's plane: positive for every point
    x, y, r = rel @ right / depth, rel @ up / depth, radii / depth
    lo, hi = np.array([(x - r).min(), (y - r).min()]), np.array([(x + r).max(), (y + r).max()])
    half = margin * max((hi[0] - lo[0]) / 2 / frame_x, (hi[1] - lo[1]) / 2 / frame_y, 1e-9)
    cam.data.lens = cam.data.sensor_width / 2 / half
    cam.data.shift_x, cam.data.shift_y = ((lo + hi) / 2 / (2 * half)).tolist()  # in frame widths
    cam.location = Vector((centre + distance * back).tolist())
    cam.rotation_mode = "QUATERNION"
    cam.rotation_quaternion = Matrix(np.column_stack([right, up, back]).tolist()).to_quaternion()
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
    strands = strand_curves(scene)
    thicken_tubes(strands)
    strands = strand_curves(scene)
    for obj in scene.objects:  # the meshes the strands come from stay in the viewport, out of the picture
        if obj.type == "MESH" and bpy.data.collections.get(obj.name) is not None:
            obj.hide_render = True
    render = scene.render
    if size is not None:
        render.resolution_x, render.resolution_y = size
        render.resolution_percentage = 100
    fit_camera(scene, strands)
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
