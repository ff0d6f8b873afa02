"""The parts of the Blender add-on that need no Blender: mesh conversion, label editing, the zip."""

import subprocess
import sys
import zipfile

import numpy as np
import pytest

import lkspace
from lkspace.blender.editing import component_order, fill_orbit, random_labels
from lkspace.blender.meshdata import MeshArrays, mesh_design
from lkspace.errors import LabelError, ScaffoldError


def blender_like(scaffold, seed):
    """``scaffold`` as Blender might store it: edges in a random order, polygons' loops out of order, a loose vertex."""
    rng = np.random.default_rng(seed)
    pairs = scaffold.edge_vertices.copy()
    pairs = pairs[rng.permutation(len(pairs))]
    flip = rng.random(len(pairs)) < 0.5
    pairs[flip] = pairs[flip][:, ::-1]
    loose = len(scaffold.vertices)
    edges = np.vstack([pairs, [[0, loose]]])  # a loose edge to a loose vertex
    vertices = np.vstack([scaffold.vertices, [[9.0, 9.0, 9.0]]])
    faces = scaffold.faces()
    order = rng.permutation(len(faces))  # loops stored in another order than the polygons
    starts = np.zeros(len(faces), np.int64)
    loops = []
    for f in order:
        starts[f] = len(loops)
        loops.extend(faces[f])
    totals = np.array([len(f) for f in faces])
    return MeshArrays(vertices, edges, starts, totals, np.array(loops)), edges


@pytest.mark.parametrize("name", ["tetrahedron", "cube", "book:3", "dihedron:4"])
@pytest.mark.parametrize("seed", [0, 1])
def test_mesh_design_keeps_faces_corners_and_edge_identity(name, seed):
    scaffold = lkspace.load(name)
    arrays, edges = blender_like(scaffold, seed)
    design = mesh_design(arrays, name)
    assert design.scaffold.faces() == scaffold.faces()
    assert design.edge_of[-1] == -1  # the loose edge
    # Blender edge b and lkspace edge edge_of[b] have the same vertex pair
    for b, e in enumerate(design.edge_of[:-1].tolist()):
        assert sorted(edges[b].tolist()) == scaffold.edge_vertices[e].tolist()
    # corners: scaffold corner c is the loop holding the same vertex
    assert np.array_equal(arrays.loop_vertices[design.loop_of], scaffold.corners)
    rng = np.random.default_rng(seed)
    labels = rng.integers(-3, 4, scaffold.n_edges)
    by_pair = {tuple(p): int(t) for p, t in zip(scaffold.edge_vertices.tolist(), labels)}
    twists = np.array([by_pair.get(tuple(sorted(p)), 7) for p in edges.tolist()])
    assert np.array_equal(design.labels(twists), labels)
    assert np.array_equal(design.edge_twists(labels, np.full(len(edges), 5)), np.r_[twists[:-1], 5])
    ours, theirs = lkspace.trace(design.scaffold, labels), lkspace.trace(scaffold, labels)
    assert [ours.strand_faces(k).tolist() for k in range(ours.components)] == [
        theirs.strand_faces(k).tolist() for k in range(theirs.components)
    ]


def test_loop_nulls_become_side_nulls():
    scaffold = lkspace.load("book:3")
    arrays, _ = blender_like(scaffold, 3)
    design = mesh_design(arrays, "book")
    loop_nulls = np.zeros(len(arrays.loop_vertices), bool)
    loop_nulls[design.loop_of[5]] = True
    nulls = design.nulls(loop_nulls)
    assert np.flatnonzero(nulls).tolist() == [5]


def test_mesh_without_faces_or_edges_is_refused():
    empty = MeshArrays(np.zeros((3, 3)), np.zeros((0, 2), np.int64), np.zeros(0), np.zeros(0), np.zeros(0))
    with pytest.raises(ScaffoldError, match="no faces"):
        mesh_design(empty, "empty")
    triangle = MeshArrays(
        np.eye(3), np.array([[0, 1], [1, 2]]), np.array([0]), np.array([3]), np.array([0, 1, 2])
    )  # the side 2 -> 0 has no edge
    with pytest.raises(ScaffoldError, match="vertex 0 to vertex 2 has no mesh edge"):
        mesh_design(triangle, "triangle")


def test_fill_orbit():
    tet = lkspace.load("tetrahedron")
    assert fill_orbit(tet, [3, 0, 0, 0, 0, 0], 0).tolist() == [3] * 6
    book = lkspace.load("book:4")  # the hinge is alone in its orbit; the 4 outer edges parallel to it form one
    hinge = int(np.flatnonzero(book.edge_degrees == 4)[0])
    labels = np.zeros(book.n_edges, np.int64)
    labels[hinge] = 2
    assert fill_orbit(book, labels, hinge).tolist() == labels.tolist()
    cube = lkspace.load("cube")
    assert fill_orbit(cube, [0] * 12, 0).tolist() == [0] * 12
    with pytest.raises(LabelError, match="mirror"):  # a mirror through the edge maps t to -t on itself
        fill_orbit(cube, [1] + [0] * 11, 0, "isometries")


def test_random_labels():
    cube = lkspace.load("cube")
    a = random_labels(cube, "-1,2", seed=5)
    assert set(a.tolist()) <= {-1, 2} and np.array_equal(a, random_labels(cube, "-1,2", seed=5))
    assert not np.array_equal(a, random_labels(cube, "-1,2", seed=6))
    with pytest.raises(LabelError, match="no label"):
        random_labels(cube, "0", seed=1, no_zero=True)


@pytest.mark.parametrize("seed", range(4))
def test_component_order_sorts_strands_by_lowest_corner(seed):
    cube = lkspace.load("cube")
    result = lkspace.trace(cube, np.random.default_rng(seed).integers(-2, 3, 12))
    lowest = [
        int(result.step_corners[result.strand_starts[k] : result.strand_starts[k + 1]].min())
        for k in range(result.components)
    ]
    order = component_order(result).tolist()
    assert sorted(order) == list(range(result.components))
    assert [lowest[k] for k in order] == sorted(lowest)


def test_build_zip_and_its_command_line(tmp_path):
    out = tmp_path / "dist" / "lkspace_blender.zip"
    run = subprocess.run(
        [sys.executable, "-m", "lkspace.blender", "build", "-o", str(out)], capture_output=True, text=True
    )
    assert run.returncode == 0, run.stderr
    with zipfile.ZipFile(out) as archive:
        names = archive.namelist()
        init = archive.read("lkspace_blender/__init__.py").decode()
    assert "lkspace_blender/live.py" in names and all(n.startswith("lkspace_blender/") for n in names)
    assert "bl_info" in init and '"blender": (4, 2, 0)' in init
    bad = subprocess.run(
        [sys.executable, "-m", "lkspace.blender", "build", "-o", str(tmp_path / "x.txt")],
        capture_output=True,
        text=True,
    )
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1 and ".zip" in bad.stderr
    assert not (tmp_path / "x.txt").exists()


def test_render_without_bpy_says_how_to_install_it(tmp_path):
    code = (
        "import sys; sys.modules['bpy'] = None\n"
        "from lkspace.blender.__main__ import main\n"
        f"sys.exit(main(['render', 'tetrahedron', '-o', {str(tmp_path / 't.png')!r}]))\n"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert run.returncode == 1 and "lkspace[blender]" in run.stderr and "Traceback" not in run.stderr
    assert not (tmp_path / "t.png").exists()


def test_lkspace_never_imports_bpy():
    code = (
        "import sys, lkspace, lkspace.blender, lkspace.blender.meshdata, lkspace.blender.editing;"
        "lkspace.trace('tetrahedron', 1); print('bpy' in sys.modules)"
    )
    assert subprocess.run([sys.executable, "-c", code], capture_output=True, text=True).stdout.strip() == "False"
    helped = (
        "import sys\nfrom lkspace.cli import main\ntry:\n    main(['--help'])\nexcept SystemExit:\n    pass\n"
        "print('bpy' in sys.modules, file=sys.stderr)"
    )
    run = subprocess.run([sys.executable, "-c", helped], capture_output=True, text=True)
    assert "Usage" in run.stdout and run.stderr.strip() == "False"
