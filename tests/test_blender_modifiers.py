"""The Blender add-on draws the strands of the evaluated mesh (issue 35): a Subdivision or Array modifier changes
the scaffold exactly as applying it would, ``lk_twist`` travels through the modifiers that carry edge attributes, one
that drops it is refused in one line, a modifier change rebuilds live and a move does not."""

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

from mathutils import Matrix  # noqa: E402  (only after bpy)

import lkspace  # noqa: E402
from lkspace.blender.addon import live  # noqa: E402


def labelled_cube(context, twist=1):
    bpy.ops.mesh.primitive_cube_add()
    obj = context.active_object
    obj.name = obj.data.name = "Cube"
    obj.data.attributes.new("lk_twist", "INT", "EDGE").data.foreach_set("value", [twist] * 12)
    obj.data.update()
    return obj


def applied_trace(context, obj):
    """The trace of a copy of ``obj`` with its modifiers applied by Blender, read as an lkspace scaffold."""
    copy = obj.copy()
    copy.data = obj.data.copy()
    context.scene.collection.objects.link(copy)
    with context.temp_override(object=copy, active_object=copy):
        for mod in list(copy.modifiers):
            bpy.ops.object.modifier_apply(modifier=mod.name)
    mesh = copy.data
    scaffold = lkspace.Scaffold.from_faces([v.co[:] for v in mesh.vertices], [p.vertices[:] for p in mesh.polygons])
    twist = {tuple(sorted(e.vertices)): d.value for e, d in zip(mesh.edges, mesh.attributes["lk_twist"].data)}
    labels = [twist[tuple(e)] for e in scaffold.edge_vertices.tolist()]
    bpy.data.objects.remove(copy)
    return lkspace.trace(scaffold, labels)


def strand_faces(obj):
    curves = [c for c in bpy.data.collections[obj.name].objects if c.type == "CURVE"]
    return sorted(min(tuple(f[i:] + f[:i]) for i in range(len(f))) for f in (list(c["lk_faces"]) for c in curves))


def want_faces(result):
    keys = []
    for k in range(result.components):
        f = result.strand_faces(k).tolist()
        keys.append(min(tuple(f[i:] + f[:i]) for i in range(len(f))))
    return sorted(keys)


@pytest.mark.parametrize(
    ("kind", "settings"),
    [
        ("SUBSURF", {"levels": 1}),
        ("ARRAY", {"count": 2, "relative_offset_displace": (1.5, 0, 0)}),
        ("MIRROR", {"use_mirror_merge": False}),
    ],
)
def test_modifiers_change_the_scaffold_as_applying_them_would(blender, kind, settings):
    obj = labelled_cube(blender)
    plain = lkspace.trace("cube", [1] * 12).components
    if kind == "MIRROR":  # the cube moved off the object's origin: its mirror image is a second cube
        obj.data.transform(Matrix.Translation((2, 0, 0)))
    mod = obj.modifiers.new(kind, kind)
    for name, value in settings.items():
        setattr(mod, name, value)
    assert bpy.ops.lkspace.regenerate() == {"FINISHED"}, obj.lkspace.message
    result = applied_trace(blender, obj)
    assert obj.lkspace.components == result.components
    assert strand_faces(obj) == want_faces(result)
    if kind == "SUBSURF":  # 24 faces: the edges split from a cube edge keep its twist, the new inner ones get 0
        assert max(max(f) for f in strand_faces(obj)) == 23
    else:  # two separate cubes: twice the strands of one
        assert result.components == 2 * plain


def remesh(obj):
    """A Remesh modifier making a six-face cube of blocks (it keeps no attribute)."""
    mod = obj.modifiers.new("Remesh", "REMESH")
    mod.mode = "BLOCKS"
    mod.octree_depth = 1


def test_a_modifier_that_drops_the_twists_is_refused_in_one_line(blender):
    obj = labelled_cube(blender)
    remesh(obj)
    with pytest.raises(RuntimeError) as refused:
        bpy.ops.lkspace.regenerate()
    message = str(refused.value).strip().removeprefix("Error: ")
    assert message.startswith("Cube: its modifiers (Remesh) leave no lk_twist") and "\n" not in message
    assert obj.lkspace.message == message
    obj.modifiers["Remesh"].show_viewport = False  # hidden: the base mesh again
    assert bpy.ops.lkspace.regenerate() == {"FINISHED"}
    assert obj.lkspace.components == lkspace.trace("cube", [1] * 12).components
    plain = labelled_cube(blender, twist=0)  # no twists to drop: the remeshed cube with twist 0 is drawn
    plain.name = "Plain"
    remesh(plain)
    assert bpy.ops.lkspace.regenerate() == {"FINISHED"} and plain.lkspace.components == 6


def test_a_modifier_change_rebuilds_live_and_a_move_does_not(blender):
    obj = labelled_cube(blender)
    mod = obj.modifiers.new("Subdivision", "SUBSURF")
    mod.levels = 1
    assert bpy.ops.lkspace.regenerate() == {"FINISHED"}
    blender.scene.lkspace.live = True
    calls = []
    real = live.regenerate
    live.regenerate = lambda *a, **k: calls.append(a) or real(*a, **k)
    try:
        obj.location = (1.0, 2.0, 3.0)
        obj.rotation_euler = (0.5, 0.0, 0.2)
        obj.scale = (2.0, 1.0, 1.0)
        blender.view_layer.update()
        assert calls == []
        key = obj.lkspace.key
        mod.levels = 2
        blender.view_layer.update()
        assert len(calls) == 1 and obj.lkspace.key != key
        assert max(max(f) for f in strand_faces(obj)) == 6 * 16 - 1
    finally:
        live.regenerate = real


def test_edit_operators_label_the_base_mesh_under_a_modifier(blender):
    obj = labelled_cube(blender, twist=0)
    obj.modifiers.new("Subdivision", "SUBSURF").levels = 1
    blender.scene.lkspace.label_set = "1,2"
    assert bpy.ops.lkspace.randomize(seed=3) == {"FINISHED"}
    values = np.zeros(len(obj.data.edges), np.int32)
    obj.data.attributes["lk_twist"].data.foreach_get("value", values)
    assert len(values) == 12 and set(values.tolist()) == {1, 2}
    assert bpy.ops.lkspace.regenerate() == {"FINISHED"}
    assert obj.lkspace.components == applied_trace(blender, obj).components
