"""The Blender add-on, headless with the ``bpy`` wheel (extra ``[blender]``, Python 3.11).

Meshes are made in Blender (its own cube primitive, from_pydata, bmesh), labelled through
the ``lk_twist`` / ``lk_null`` attributes as a user or a script would, and the add-on's
strands are checked against ``lkspace.trace`` of the same mesh read independently: an OBJ
file written here from Blender's vertices and polygons, labels named by vertex pair.
"""

import json
import os
import struct
import subprocess
import sys
import time

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

import bmesh  # noqa: E402  (only after bpy)

import lkspace  # noqa: E402
from lkspace.blender.addon import identifying, scene  # noqa: E402

TETRAHEDRON = [(1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)]


def add_object(context, name, vertices, faces):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(vertices, [], faces)
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    context.scene.collection.objects.link(obj)
    context.view_layer.objects.active = obj
    return obj


def book(context, k):
    """K quads sharing the edge (0, 0, -1)-(0, 0, 1), made with bmesh: a non-manifold hinge."""
    bm = bmesh.new()
    a, b = bm.verts.new((0, 0, -1)), bm.verts.new((0, 0, 1))
    for i in range(k):
        angle = 2 * np.pi * i / k + 0.3
        x, y = np.cos(angle), np.sin(angle)
        c, d = bm.verts.new((x, y, 1)), bm.verts.new((x, y, -1))
        bm.faces.new((a, b, c, d))
    mesh = bpy.data.meshes.new(f"book{k}")
    bm.to_mesh(mesh)
    bm.free()
    obj = bpy.data.objects.new(mesh.name, mesh)
    context.scene.collection.objects.link(obj)
    context.view_layer.objects.active = obj
    return obj


def set_twists(obj, twist_of_pair):
    """Write ``lk_twist`` from ``{(u, v): t}`` (Blender vertex pairs), 0 for other edges, as a script would."""
    mesh = obj.data
    values = [twist_of_pair.get(tuple(sorted(e.vertices)), 0) for e in mesh.edges]
    attr = mesh.attributes.get("lk_twist") or mesh.attributes.new("lk_twist", "INT", "EDGE")
    attr.data.foreach_set("value", values)
    mesh.update()


def edge_pairs(obj):
    return [tuple(sorted(e.vertices)) for e in obj.data.edges]


def twists_by_pair(obj):
    values = [d.value for d in obj.data.attributes["lk_twist"].data]
    return dict(zip(edge_pairs(obj), values))


def independent(obj, tmp_path, twist_of_pair, nulls_of=()):
    """The same mesh read by lkspace from an OBJ file, its labels in lkspace's edge order, and the trace."""
    mesh = obj.data
    lines = [f"v {v.co.x!r} {v.co.y!r} {v.co.z!r}" for v in mesh.vertices]
    lines += ["f " + " ".join(str(i + 1) for i in p.vertices) for p in mesh.polygons]
    path = tmp_path / f"{obj.name}.obj"
    path.write_text("\n".join(lines) + "\n")
    scaffold = lkspace.load(str(path))
    labels = [twist_of_pair.get(tuple(e), 0) for e in scaffold.edge_vertices.tolist()]
    nulls = np.zeros(scaffold.n_corners, bool)
    nulls[list(nulls_of)] = True
    return path, scaffold, labels, lkspace.trace(scaffold, labels, nulls)


def cyclic_key(faces, closed):
    """A strand's face sequence up to where it starts (closed strands); open strands as they are."""
    if not closed or not faces:
        return tuple(faces)
    return min(tuple(faces[i:] + faces[:i]) for i in range(len(faces)))


def strand_curves(obj):
    return [c for c in bpy.data.collections[obj.name].objects if c.type == "CURVE"]


def assert_same_strands(obj, result):
    curves = strand_curves(obj)
    assert len(curves) == result.components == obj.lkspace.components
    got = sorted(cyclic_key(list(c["lk_faces"]), c.data.splines[0].use_cyclic_u) for c in curves)
    want = sorted(cyclic_key(result.strand_faces(k).tolist(), bool(result.closed[k])) for k in range(result.components))
    assert got == want
    assert obj.lkspace.holds_together == result.holds_together


@pytest.mark.parametrize("twist", [1, 2, -1])
def test_tetrahedron_strands_match_trace(blender, tmp_path, twist):
    obj = add_object(blender, "tet", TETRAHEDRON, [(0, 1, 2), (0, 3, 1), (0, 2, 3), (1, 3, 2)])
    pairs = {p: twist for p in edge_pairs(obj)}
    set_twists(obj, pairs)
    assert bpy.ops.lkspace.regenerate() == {"FINISHED"}
    _, _, _, result = independent(obj, tmp_path, pairs)
    assert_same_strands(obj, result)
    curve = strand_curves(obj)[0]
    assert curve.data.bevel_depth > 0 and curve.data.fill_mode == "FULL" and len(curve.data.materials) == 1


def test_blender_cube_with_mixed_twists_matches_the_cli(blender, tmp_path):
    bpy.ops.mesh.primitive_cube_add(size=2)
    obj = blender.active_object
    obj.name = "Cube"
    pairs = {p: [1, 2, -1][i % 3] for i, p in enumerate(sorted(edge_pairs(obj)))}
    set_twists(obj, pairs)
    assert bpy.ops.lkspace.regenerate() == {"FINISHED"}
    path, scaffold, labels, result = independent(obj, tmp_path, pairs)
    assert_same_strands(obj, result)
    cli = subprocess.run(
        ["lkspace", "trace", str(path), "--twist", ",".join(map(str, labels)), "--json"],
        capture_output=True,
        text=True,
        check=True,
    )
    traced = json.loads(cli.stdout)
    assert traced["components"] == obj.lkspace.components
    closed = {c["lk_strand"]: c.data.splines[0].use_cyclic_u for c in strand_curves(obj)}
    assert sorted(cyclic_key(s["faces"], s["closed"]) for s in traced["strands"]) == sorted(
        cyclic_key(list(c["lk_faces"]), closed[c["lk_strand"]]) for c in strand_curves(obj)
    )


def test_book_hinge_and_null_side(blender, tmp_path):
    obj = book(blender, 3)
    pairs = {p: 1 for p in edge_pairs(obj)}
    set_twists(obj, pairs)
    assert bpy.ops.lkspace.regenerate() == {"FINISHED"}
    _, scaffold, _, result = independent(obj, tmp_path, pairs)
    assert scaffold.edge_degrees.max() == 3
    assert_same_strands(obj, result)
    # cut the first side of polygon 0 (loop 0): one strand opens
    mesh = obj.data
    null = mesh.attributes.new("lk_null", "BOOLEAN", "CORNER")
    null.data[mesh.polygons[0].loop_start].value = True
    mesh.update()
    assert bpy.ops.lkspace.regenerate() == {"FINISHED"}
    _, _, _, cut = independent(obj, tmp_path, pairs, nulls_of=[0])
    assert int(np.sum(~cut.closed)) == 1 == obj.lkspace.open_strands
    assert_same_strands(obj, cut)
    assert sum(not c.data.splines[0].use_cyclic_u for c in strand_curves(obj)) == 1


def test_dihedron_needs_both_faces_which_validate_merges(blender, tmp_path):
    triangle = [(1, 0, 0), (-0.5, 0.8, 0), (-0.5, -0.8, 0)]
    obj = add_object(blender, "dihedron", triangle, [(0, 1, 2), (0, 2, 1)])
    set_twists(obj, {p: 1 for p in edge_pairs(obj)})
    assert bpy.ops.lkspace.regenerate() == {"FINISHED"}
    assert obj.lkspace.components == 1
    assert bpy.ops.lkspace.identify(background=False) == {"FINISHED"}
    assert obj.lkspace.knot.startswith("3_1")
    obj.data.validate()  # Blender's clean-up drops the second face of the same vertex cycle
    assert len(obj.data.polygons) == 1


def test_set_fill_orbit_randomize_solve_on_blender_cube(blender):
    bpy.ops.mesh.primitive_cube_add(size=2)
    obj = blender.active_object
    mesh = obj.data
    for e in mesh.edges:
        e.select = e.index == 3
    assert bpy.ops.lkspace.set_twist(twist=2) == {"FINISHED"}
    assert sorted(twists_by_pair(obj).values()) == [0] * 11 + [2]
    assert bpy.ops.lkspace.fill_orbit(mode="rotations") == {"FINISHED"}
    assert set(twists_by_pair(obj).values()) == {2}  # the cube's rotations move any edge to any other
    blender.scene.lkspace.label_set = "-2..2"
    blender.scene.lkspace.no_zero = True
    assert bpy.ops.lkspace.randomize(seed=7) == {"FINISHED"}
    first = twists_by_pair(obj)
    assert bpy.ops.lkspace.randomize(seed=7) == {"FINISHED"}
    assert twists_by_pair(obj) == first and 0 not in first.values() and len(set(first.values())) > 1
    assert bpy.ops.lkspace.solve(components=1) == {"FINISHED"}
    solved = twists_by_pair(obj)
    assert 0 not in solved.values()
    scaffold = lkspace.Scaffold.from_faces([v.co[:] for v in mesh.vertices], [p.vertices[:] for p in mesh.polygons])
    assert lkspace.trace(scaffold, [solved[tuple(e)] for e in scaffold.edge_vertices.tolist()]).components == 1


def test_live_regeneration_follows_attribute_edits(blender):
    obj = add_object(blender, "tet", TETRAHEDRON, [(0, 1, 2), (0, 3, 1), (0, 2, 3), (1, 3, 2)])
    set_twists(obj, {p: 1 for p in edge_pairs(obj)})
    assert bpy.ops.lkspace.regenerate() == {"FINISHED"}
    assert obj.lkspace.components == 3
    blender.scene.lkspace.live = True
    set_twists(obj, {p: 2 for p in edge_pairs(obj)})
    blender.view_layer.update()
    assert obj.lkspace.components == 4 == len(strand_curves(obj))
    blender.scene.lkspace.live = False
    set_twists(obj, {p: 1 for p in edge_pairs(obj)})
    blender.view_layer.update()
    assert obj.lkspace.components == 4


def test_colours_follow_lowest_corner_and_materials_are_shared(blender):
    obj = add_object(blender, "tet", TETRAHEDRON, [(0, 1, 2), (0, 3, 1), (0, 2, 3), (1, 3, 2)])
    set_twists(obj, {p: 0 for p in edge_pairs(obj)})
    assert bpy.ops.lkspace.regenerate() == {"FINISHED"}
    # twist 0: each face is its own strand; face f's strand has slot f
    slots = {c["lk_faces"][0]: c.data.materials[0].name for c in strand_curves(obj)}
    assert slots == {f: f"lkspace strand {f:02d}" for f in range(4)}
    colours = [tuple(bpy.data.materials[f"lkspace strand {f:02d}"].diffuse_color)[:3] for f in range(4)]
    assert len(set(colours)) == 4
    assert bpy.ops.lkspace.regenerate() == {"FINISHED"}
    assert len([m for m in bpy.data.materials if m.name.startswith("lkspace strand")]) == 4


def test_identify_in_the_background_says_what_identify_says(blender, tmp_path):
    obj = add_object(blender, "tet", TETRAHEDRON, [(0, 1, 2), (0, 3, 1), (0, 2, 3), (1, 3, 2)])
    pairs = {p: 1 for p in edge_pairs(obj)}
    set_twists(obj, pairs)
    assert bpy.ops.lkspace.identify() == {"FINISHED"}
    assert obj.lkspace.knot == "identifying..."
    give_up = time.monotonic() + 300
    while identifying.JOBS and time.monotonic() < give_up:
        time.sleep(0.2)
        identifying.poll_jobs()
    _, scaffold, labels, _ = independent(obj, tmp_path, pairs)
    found = lkspace.identify(scaffold, labels)
    assert "L6a4" in (found.name or found.status)  # the Borromean rings (named, or among the table's variants)
    assert obj.lkspace.knot == (found.name + (" (mirror)" if found.mirror else "") if found.name else found.status)


def stl_triangles(path):
    data = path.read_bytes()
    (n,) = struct.unpack("<I", data[80:84])
    assert len(data) == 84 + 50 * n
    return n


def test_export_goes_through_the_checked_fabrication_path(blender, tmp_path):
    obj = add_object(blender, "tet", TETRAHEDRON, [(0, 1, 2), (0, 3, 1), (0, 2, 3), (1, 3, 2)])
    pairs = {p: 1 for p in edge_pairs(obj)}
    set_twists(obj, pairs)
    out = tmp_path / "tet.stl"
    assert bpy.ops.lkspace.export(filepath=str(out), thickness=1.0, clearance=0.3, scale=10.0) == {"FINISHED"}
    _, scaffold, labels, _ = independent(obj, tmp_path, pairs)
    ref = tmp_path / "ref.stl"
    lkspace.export(scaffold, ref, labels, options=lkspace.PrintOptions(thickness=1.0, clearance=0.3, scale=10.0))
    assert stl_triangles(out) == stl_triangles(ref) > 0
    # a clearance the design cannot keep is refused, and nothing is written
    bad = tmp_path / "bad.stl"
    with pytest.raises(RuntimeError, match="clearance"):
        bpy.ops.lkspace.export(filepath=str(bad), thickness=1.0, clearance=50.0, scale=10.0)
    assert not bad.exists()


def test_export_dna_writes_what_the_cli_writes(blender, tmp_path):
    obj = add_object(blender, "tet", TETRAHEDRON, [(0, 1, 2), (0, 3, 1), (0, 2, 3), (1, 3, 2)])
    pairs = {p: 4 for p in edge_pairs(obj)}
    set_twists(obj, pairs)
    assert bpy.ops.lkspace.export_dna(filepath=str(tmp_path / "tet.oxdna")) == {"FINISHED"}
    _, scaffold, labels, _ = independent(obj, tmp_path, pairs)
    from lkspace.dna.build import build
    from lkspace.dna.oxdna import write

    write(build(scaffold, labels), str(tmp_path / "ref.oxdna"))
    for ext in (".top", ".dat", ".oxview"):
        assert (tmp_path / f"tet{ext}").read_text() == (tmp_path / f"ref{ext}").read_text()
    set_twists(obj, {p: 0 for p in pairs})  # zero twist: not B-DNA, refused, nothing written
    with pytest.raises(RuntimeError, match="positive twist"):
        bpy.ops.lkspace.export_dna(filepath=str(tmp_path / "bad.oxdna"))
    assert not (tmp_path / "bad.top").exists()


def test_periodic_block_and_scene_preset_render(blender, tmp_path):
    from lkspace.blender.addon.builtin import make_block

    block = make_block(blender.scene, "tiling:square", "2", "2x2")
    rings = strand_curves(block)
    assert len(rings) == 4 and block.lkspace.components == 1  # one ring class, a ring a cell
    # as lkspace export colours them: the four rings of the 2x2 block in four tones, four materials
    assert len({c.data.materials[0].name for c in rings}) == 4
    scene.preset(blender.scene, "CYCLES", (48, 48), samples=2)
    out = tmp_path / "block.png"
    scene.render(blender.scene, str(out))
    image = bpy.data.images.load(str(out))
    pixels = np.array(image.pixels[:]).reshape(48, 48, 4)[..., :3]
    assert pixels.std() > 0.02  # not a blank frame: the strands are in view
    background = pixels[0, 0]
    assert np.any(np.abs(pixels - background).sum(axis=2) > 0.2, axis=1).sum() >= 5


def test_add_scaffold_and_errors_reach_the_panel(blender):
    assert bpy.ops.lkspace.add_scaffold(scaffold="cube", twist="2") == {"FINISHED"}
    obj = blender.active_object
    assert obj.lkspace.components == 6 and obj.lkspace.holds_together
    with pytest.raises(RuntimeError, match="periodic"):
        bpy.ops.lkspace.add_scaffold(scaffold="tiling:square", twist="1")
    # a mesh lkspace cannot use: two faces of a book at the same angle around the hinge
    flat = add_object(
        blender,
        "flat",
        [(0, 0, -1), (0, 0, 1), (1, 0, 1), (1, 0, -1), (2, 0, 1), (2, 0, -1), (-1, 0, 1), (-1, 0, -1)],
        [(0, 1, 2, 3), (0, 1, 4, 5), (0, 1, 6, 7)],
    )
    with pytest.raises(RuntimeError, match="same angle|radial"):
        bpy.ops.lkspace.regenerate()
    assert flat.lkspace.message


def test_zip_installs_and_says_how_to_install_lkspace_when_missing(tmp_path):
    zip_path = tmp_path / "dist" / "lkspace_blender.zip"
    subprocess.run([sys.executable, "-m", "lkspace.blender", "build", "-o", str(zip_path)], check=True)
    code = (
        "import sys, bpy, addon_utils\n"
        "missing = sys.argv[1] == 'missing'\n"
        "if missing: sys.modules['lkspace'] = None\n"
        f"bpy.ops.preferences.addon_install(filepath={str(zip_path)!r})\n"
        "addon_utils.enable('lkspace_blender', default_set=True)\n"
        "import lkspace_blender\n"
        "print(sorted(c.__name__ for c in lkspace_blender.REGISTERED))\n"
        "print(lkspace_blender.INSTALL)\n"
        "addon_utils.disable('lkspace_blender')\n"
    )
    env = {**os.environ, "BLENDER_USER_SCRIPTS": str(tmp_path / "scripts")}
    for mode in ("present", "missing"):
        run = subprocess.run(
            [sys.executable, "-c", code, mode], capture_output=True, text=True, env=env, check=True, cwd=tmp_path
        )
        lines = run.stdout.strip().splitlines()
        if mode == "missing":
            assert "LKSPACE_PT_missing" in lines[-2] and "LKSPACE_OT_regenerate" not in lines[-2]
            assert "-m pip install" in lines[-1] and sys.executable in lines[-1]
            assert "install lkspace with" in run.stderr
        else:
            assert "LKSPACE_OT_regenerate" in lines[-2] and "LKSPACE_PT_missing" not in lines[-2]


def test_live_rebuilds_of_large_meshes_skip_the_clearance_measurement(blender, tmp_path):
    bpy.ops.mesh.primitive_uv_sphere_add(segments=24, ring_count=8)
    obj = blender.active_object
    assert len(obj.data.polygons) > 150
    pairs = {p: 1 for p in edge_pairs(obj)}
    set_twists(obj, pairs)
    assert bpy.ops.lkspace.regenerate(measure=False) == {"FINISHED"}
    assert not obj.lkspace.measured
    blender.scene.lkspace.live = True
    pairs = {p: -1 for p in edge_pairs(obj)}
    set_twists(obj, pairs)
    blender.view_layer.update()
    assert not obj.lkspace.measured
    _, scaffold, labels, result = independent(obj, tmp_path, pairs)
    assert_same_strands(obj, result)
    # a live preview draws the construction, sampled half as finely: no smoothing, which needs the clearance proved
    coarse = lkspace.GeometryParams(smooth=False, samples_per_turn=16, edge_samples=12, corner_samples=6)
    preview = lkspace.realize(scaffold, labels, params=coarse, options=lkspace.RealizeOptions(embedding="later"))
    drawn = [curve_points(c) for c in sorted(strand_curves(obj), key=lambda c: c.name)]  # NAME.strand.k: curve k
    assert [len(p) for p in drawn] == [len(c) for c in preview.curves]
    assert all(np.allclose(p, c, atol=1e-6) for p, c in zip(drawn, preview.curves))  # Blender keeps float32
    assert {c.data.bevel_resolution for c in strand_curves(obj)} == {1}  # lighter tubes (the scene's: 3)


def test_edit_mode_set_twist_cut_and_live_move(blender):
    bpy.ops.mesh.primitive_cube_add()
    obj = blender.active_object
    assert bpy.ops.lkspace.regenerate() == {"FINISHED"} and obj.lkspace.components == 6
    blender.scene.lkspace.live = True
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    assert bpy.ops.lkspace.set_twist(twist=1) == {"FINISHED"} and obj.mode == "EDIT"
    bm = bmesh.from_edit_mesh(obj.data)
    bm.verts.ensure_lookup_table()
    bm.verts[0].co.x += 0.3  # a live rebuild follows a vertex moved in Edit Mode
    bmesh.update_edit_mesh(obj.data)
    key = obj.lkspace.key
    blender.view_layer.update()
    assert obj.lkspace.key != key and obj.lkspace.message == ""
    bpy.ops.mesh.select_all(action="DESELECT")
    bm = bmesh.from_edit_mesh(obj.data)
    bm.edges.ensure_lookup_table()
    bm.edges[0].select = True
    bmesh.update_edit_mesh(obj.data)
    assert bpy.ops.lkspace.set_null(null=True) == {"FINISHED"}
    # both sides of the edge are cut: one closed strand cut twice or two cut once, two open strands either way
    assert obj.lkspace.open_strands == 2
    bpy.ops.object.mode_set(mode="OBJECT")
    nulls = [d.value for d in obj.data.attributes["lk_null"].data]
    assert [obj.data.loops[i].edge_index for i, cut in enumerate(nulls) if cut] == [0, 0]
    assert len(bpy.data.meshes) == 1  # the temporary copies read in Edit Mode are gone


def curve_points(curve):
    spline = curve.data.splines[0]
    co = np.zeros(4 * len(spline.points))
    spline.points.foreach_get("co", co)
    return co.reshape(-1, 4)[:, :3]


def test_relax_checkbox_builds_relaxed_strands(blender, tmp_path):
    obj = add_object(blender, "tet", TETRAHEDRON, [(0, 1, 2), (0, 3, 1), (0, 2, 3), (1, 3, 2)])
    pairs = {p: 1 for p in edge_pairs(obj)}  # the Borromean rings
    set_twists(obj, pairs)
    assert bpy.ops.lkspace.regenerate() == {"FINISHED"} and not obj.lkspace.relaxed
    plain = {c["lk_strand"]: curve_points(c) for c in strand_curves(obj)}
    blender.scene.lkspace.relax = True
    assert bpy.ops.lkspace.regenerate() == {"FINISHED"} and obj.lkspace.relaxed
    _, scaffold, labels, result = independent(obj, tmp_path, pairs)
    assert_same_strands(obj, result)  # same components, each around the same faces
    tight = {c["lk_strand"]: curve_points(c) for c in strand_curves(obj)}
    want = lkspace.relax(lkspace.realize(scaffold, labels))
    assert sorted(len(p) for p in tight.values()) == sorted(len(c) for c in want.curves)
    # every strand moved: some relaxed point is off the default curve (by 2% of its size: the default
    # smoothing is within a few percent of tight on the small knots since issue 34, the trefoil's 3.9%)
    for k, after in tight.items():
        before = plain[k]
        gaps = np.linalg.norm(after[:, None] - before[None], axis=2).min(axis=1)
        assert gaps.max() > 0.02 * np.linalg.norm(before - before.mean(axis=0), axis=1).max()
    assert all(c.data.splines[0].use_cyclic_u for c in strand_curves(obj))
    cut = np.zeros(12, bool)  # a null side: open strands, which relax refuses in one line; the curves stay
    cut[0] = True
    attr = obj.data.attributes.get("lk_null") or obj.data.attributes.new("lk_null", "BOOLEAN", "CORNER")
    attr.data.foreach_set("value", cut.tolist())
    obj.data.update()
    with pytest.raises(RuntimeError, match="closed strands"):
        bpy.ops.lkspace.regenerate()
    assert "closed strands" in obj.lkspace.message and "\n" not in obj.lkspace.message
    assert len(strand_curves(obj)) == result.components
