"""The Blender add-on under a designer's own meshes (issue 35): every ``lk_twist`` domain and type either read
or refused in one clear line, renames and moves, and advice that names the panel's controls."""

import itertools
import pathlib

import numpy as np
import pytest

from lkspace.blender.meshdata import MAX_TWIST, whole_twists
from lkspace.errors import LabelError

bpy = pytest.importorskip("bpy")

import lkspace  # noqa: E402
import lkspace.blender.addon as addon  # noqa: E402
from lkspace.blender.addon import live  # noqa: E402

DOMAINS = ["POINT", "EDGE", "FACE", "CORNER"]
TYPES = ["INT", "INT8", "FLOAT", "BOOLEAN", "STRING", "FLOAT_VECTOR", "FLOAT_COLOR", "BYTE_COLOR", "FLOAT2", "INT32_2D"]


def cube(context, name="Cube"):
    bpy.ops.mesh.primitive_cube_add()
    obj = context.active_object
    obj.name = obj.data.name = name
    return obj


def regenerate():
    """The operator's answer: ``FINISHED`` or the one line it reported (Blender raises it as RuntimeError)."""
    try:
        return bpy.ops.lkspace.regenerate()
    except RuntimeError as exc:
        return str(exc).strip()


def strand_names():
    return sorted(o.name for o in bpy.data.objects if o.type == "CURVE")


@pytest.mark.parametrize(("kind", "domain"), list(itertools.product(TYPES, DOMAINS)))
def test_every_lk_twist_domain_and_type_is_read_or_refused_by_name(blender, kind, domain):
    obj = cube(blender)
    attr = obj.data.attributes.new("lk_twist", kind, domain)
    if domain == "EDGE" and kind in ("INT", "INT8", "FLOAT"):
        attr.data.foreach_set("value", [2] * 12)
    answer = regenerate()
    if domain == "EDGE" and kind in ("INT", "INT8", "FLOAT"):  # read: the cube with twist 2 everywhere
        assert answer == {"FINISHED"}
        assert obj.lkspace.components == lkspace.trace("cube", [2] * 12).components
        return
    assert answer.startswith("Error: lk_twist is a") and "Integer attribute on the Edge domain" in answer, answer
    assert obj.lkspace.message == answer.removeprefix("Error: ") and strand_names() == []


@pytest.mark.parametrize("kind", ["INT", "FLOAT", "BOOLEAN", "STRING"])
@pytest.mark.parametrize("domain", ["POINT", "EDGE", "FACE"])
def test_an_lk_null_not_on_face_corners_as_boolean_is_refused(blender, kind, domain):
    obj = cube(blender)
    obj.data.attributes.new("lk_null", kind, domain)
    answer = regenerate()
    assert answer.startswith("Error: lk_null is a") and "Boolean attribute on the Face Corner domain" in answer


@pytest.mark.parametrize("value", [1.5, 1.7, -0.5, 2.0**40, -(2.0**31), float("nan"), float("inf")])
def test_a_float_twist_that_is_not_a_whole_number_is_refused(blender, value):
    obj = cube(blender)
    attr = obj.data.attributes.new("lk_twist", "FLOAT", "EDGE")
    attr.data.foreach_set("value", [1.0] * 5 + [value] + [1.0] * 6)
    answer = regenerate()
    assert answer.startswith("Error: lk_twist: edge 5 holds ") and "not a whole twist" in answer, answer
    with pytest.raises(LabelError, match="^lk_twist: edge 0 holds"):
        whole_twists(np.array([value], np.float32))


def test_whole_float_twists_are_read_exactly():
    values = np.array([0, -3, 7, MAX_TWIST - 127, -(MAX_TWIST - 127)], np.float32)  # float32 holds these exactly
    assert whole_twists(values).tolist() == [0, -3, 7, MAX_TWIST - 127, -(MAX_TWIST - 127)]


def test_a_renamed_object_leaves_no_old_strands(blender):
    obj = cube(blender)
    assert regenerate() == {"FINISHED"}
    before = strand_names()
    assert len(before) == 6 and all(n.startswith("Cube.strand.") for n in before)
    obj.name = "Knot"
    assert regenerate() == {"FINISHED"}
    after = strand_names()
    assert len(after) == 6 and all(n.startswith("Knot.strand.") for n in after), after
    assert "Cube" not in bpy.data.collections and len(bpy.data.collections["Knot"].objects) == 6


def test_moving_the_object_moves_the_strands_without_a_rebuild(blender):
    obj = cube(blender)
    assert regenerate() == {"FINISHED"}
    blender.scene.lkspace.live = True
    calls = []
    real = live.regenerate
    live.regenerate = lambda *a, **k: calls.append(a) or real(*a, **k)
    try:
        curve = bpy.data.objects["Cube.strand.00"]
        start = np.array(curve.matrix_world)
        obj.location = (3.0, -1.0, 2.0)
        obj.rotation_euler = (0.3, 0.0, 1.0)
        blender.view_layer.update()
        assert calls == []  # a move: no rebuild
        assert np.allclose(np.array(curve.matrix_world), np.array(obj.matrix_world))  # the curves followed
        assert not np.allclose(np.array(curve.matrix_world), start)
        attr = obj.data.attributes["lk_twist"] if "lk_twist" in obj.data.attributes else None
        assert attr is None
        obj.data.attributes.new("lk_twist", "INT", "EDGE").data.foreach_set("value", [2] * 12)
        obj.data.update()
        blender.view_layer.update()
        assert len(calls) == 1  # an attribute edit: one rebuild
    finally:
        live.regenerate = real


def twins():
    """Two unit cubes in one mesh, the second moved by (0, 0.3, 0.3) into the first: faces that cross."""
    corners = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    mesh = bpy.data.meshes.new("Twins")
    mesh.from_pydata(
        corners + [(x, y + 0.3, z + 0.3) for x, y, z in corners], [], quads + [tuple(i + 8 for i in q) for q in quads]
    )
    obj = bpy.data.objects.new("Twins", mesh)
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)


@pytest.mark.parametrize(
    ("name", "add"),
    [
        ("Twins", twins),  # 12 faces: refused at once
        # Suzanne's 500 faces are realized before the refusal: half a minute, a minute under load
        pytest.param("Suzanne", lambda: bpy.ops.mesh.primitive_monkey_add(), marks=pytest.mark.slow),
    ],
    ids=["twins", "suzanne"],
)
def test_advice_names_controls_the_panel_has(blender, name, add):
    add()
    answer = regenerate()
    assert answer.startswith(f"Error: {name}: strands"), answer
    props = blender.scene.lkspace.bl_rna.properties
    names = {p.name for p in props}
    assert "`" not in answer and "normal_offset" not in answer and "radius" not in answer
    assert "Inset" in answer and "Normal offset" in answer and {"Inset", "Normal offset"} <= names
    # the panel draws those controls
    drawn = [line.strip() for line in pathlib.Path(addon.__file__).with_name("panel.py").read_text().splitlines()]
    assert 'row.prop(settings, "radius")' in drawn and 'row.prop(settings, "normal_offset")' in drawn


def test_the_shape_controls_reach_the_strands(blender):
    obj = cube(blender)
    blender.scene.lkspace.tube_radius = 0.05
    blender.scene.lkspace.resolution = 5
    assert regenerate() == {"FINISHED"}
    curve = bpy.data.objects["Cube.strand.00"]
    assert curve.data.bevel_depth == pytest.approx(0.05) and curve.data.bevel_resolution == 5
    key = obj.lkspace.key
    blender.scene.lkspace.radius = 0.1
    assert regenerate() == {"FINISHED"} and obj.lkspace.key != key  # another shape: another state
    blender.scene.lkspace.live = True
    blender.scene.lkspace.tube_radius = 0.07  # with Live on, a shape change rebuilds at once
    assert bpy.data.objects["Cube.strand.00"].data.bevel_depth == pytest.approx(0.07)


def test_too_many_points_is_advised_in_the_panels_terms():
    from lkspace.errors import TooLargeError
    from lkspace.geometry.limits import check_points

    with pytest.raises(TooLargeError) as refused:  # what a 50,000-face grid gets from realize
        check_points("Grid", 7.29e6, 4_000_000)
    advice = live.panel_advice(str(refused.value))
    assert (
        advice
        == "the curves of Grid would have about 7,290,000 points > 4,000,000; use smaller twists (or a mesh with fewer faces)"
    )


def test_every_time_setting_says_whether_it_counts_cpu_or_wall_clock_time(blender):
    """Issue 35: limits count CPU time or say they are wall-clock time (the panel's Solve limit said 'Seconds')."""
    props = [p for p in blender.scene.lkspace.bl_rna.properties if "time" in p.identifier]
    assert [p.identifier for p in props] == ["time_limit"]
    for prop in props:
        assert ("CPU" in prop.description) != ("wall-clock" in prop.description.lower()), prop.description
