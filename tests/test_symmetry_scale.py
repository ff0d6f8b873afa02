"""The symmetry search at scale and on degenerate meshes: bounded time and memory, the identity always found."""

from __future__ import annotations

import json
import os
import resource
import subprocess
import sys

import numpy as np
import pytest

import lkspace
from lkspace.cli import main
from lkspace.io.obj import format_obj
from lkspace.model.scaffold import Scaffold
from lkspace.scaffolds.spheres import cube_sphere
from lkspace.symmetry.group import symmetry_group
from lkspace.symmetry.motions import candidate_vertex_perms, finite_motions


def reference_actions(sc: Scaffold) -> set[tuple[bytes, bool]]:
    """(edge permutation, proper) of every element by the exact igraph path (small scaffolds only)."""
    out = set()
    for sigma, q, _, _ in finite_motions(sc, candidate_vertex_perms(sc)):
        ev = sc.edge_vertices
        image = np.sort(np.column_stack([sigma[ev[:, 0]], sigma[ev[:, 1]]]), axis=1)
        lookup = {tuple(e): i for i, e in enumerate(ev.tolist())}
        perm = np.array([lookup[tuple(e)] for e in image.tolist()], np.int64)
        out.add((perm.tobytes(), bool(np.linalg.det(q) > 0)))
    return out


def assert_valid(sc: Scaffold) -> lkspace.symmetry.group.SymmetryGroup:
    """Every element is a rigid motion carrying vertices, edges onto themselves; the identity first."""
    g = symmetry_group(sc)
    assert np.allclose(g.matrices[0], np.eye(3)) and np.array_equal(g.vertex_perms[0], np.arange(sc.n_vertices))
    x = sc.vertices - sc.vertices.mean(axis=0)
    tol = 1e-6 * np.sqrt(np.mean(np.sum(x**2, axis=1)))
    for q, sigma, perm in zip(g.matrices, g.vertex_perms, g.edge_perms, strict=True):
        assert np.allclose(q @ q.T, np.eye(3))
        assert np.abs(x @ q.T - x[sigma]).max() <= tol
        ev = sc.edge_vertices
        assert np.array_equal(np.sort(np.column_stack([sigma[ev[:, 0]], sigma[ev[:, 1]]]), axis=1), ev[perm])
    return g


def write_obj(path, vertices, faces) -> str:
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in np.asarray(vertices, float).tolist()]
    lines += ["f " + " ".join(str(v + 1) for v in f) for f in faces]
    path.write_text("\n".join(lines) + "\n")
    return str(path)


def info(capsys, *args: str) -> tuple[int, dict, str]:
    code = main(["info", *args, "--json"])
    out = capsys.readouterr()
    return code, json.loads(out.out), out.err


@pytest.mark.parametrize(
    "name", ["cube", "dodecahedron", "truncated-octahedron", "book:3", "dihedron:6", "cube-lid", "cubes:vertex"]
)
def test_agrees_with_the_igraph_path(name):
    sc = lkspace.load(name)
    g = assert_valid(sc)
    assert {(p.tobytes(), bool(s)) for p, s in zip(g.edge_perms, g.proper, strict=True)} == reference_actions(sc)


@pytest.mark.parametrize(
    "vertices, faces, orders",
    [
        ([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [[0, 1, 2]], (4, 2)),  # collinear: keep or flip the line
        ([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2, 3]], (16, 8)),  # one flat square
        ([[0, 0, 0], [1, 0, 0], [0, 2, 0]], [[0, 1, 2]], (2, 1)),  # scalene triangle: the mirror in its plane
        ([[0, 0, 0], [3, 0, 0], [0, 1, 0], [0, 0, 1]], [[0, 1, 2], [0, 2, 3]], (1, 1)),  # no symmetry
    ],
)
def test_degenerate_point_sets(vertices, faces, orders):
    sc = Scaffold.from_faces(vertices, faces)
    g = assert_valid(sc)
    assert (g.order, g.n_rotations) == orders
    assert {(p.tobytes(), bool(s)) for p, s in zip(g.edge_perms, g.proper, strict=True)} == reference_actions(sc)


# the scaffold's own checks (lkspace/model) overflow on coordinates near 1e308 and warn; the
# symmetry search does not (test_standard_position_of_extreme_coordinates runs with warnings as errors)


@pytest.mark.parametrize("scale", [1e-8, 1e8, 1e11])
def test_huge_and_tiny_coordinates(scale, tmp_path, capsys):
    tet = lkspace.load("tetrahedron")
    path = write_obj(tmp_path / "t.obj", tet.vertices * scale, tet.faces())
    code, data, _ = info(capsys, path)
    assert code == 0 and data["symmetry_group_order"] == {"rotations": 12, "isometries": 24}


def test_coordinates_near_the_float_limit(tmp_path, capsys):
    """Coordinates past MAX_COORDINATE (1e12) are refused at their line, before any search (no hang)."""
    v = [[1e308, 1e308, 1e308], [-1e308, 1e308, -1e308], [1e308, -1e308, -1e308], [-1e308, -1e308, 1e308]]
    path = write_obj(tmp_path / "huge.obj", v, [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]])
    code, _, err = info(capsys, path)
    assert code == 1 and "huge.obj line 1" in err and "1e+12" in err


@pytest.mark.parametrize("scale", [1e-300, 1.0, 1e300, 1.7e308])
def test_standard_position_of_extreme_coordinates(scale):
    from lkspace.symmetry.pointset import standard_position

    x = standard_position(lkspace.load("cube").vertices * scale)
    assert np.allclose(np.linalg.norm(x, axis=1), 1.0) and np.allclose(x.mean(axis=0), 0.0)


def unwelded(sc: Scaffold) -> tuple[np.ndarray, list[list[int]]]:
    """One vertex copy per face corner, as modelling tools export."""
    faces, k = [], 0
    for f in sc.faces():
        faces.append(list(range(k, k + len(f))))
        k += len(f)
    return sc.vertices[np.concatenate(sc.faces())], faces


@pytest.mark.parametrize("name, orders", [("cube", (48, 24)), ("icosahedron", (120, 60)), ("book:3", (12, 6))])
@pytest.mark.filterwarnings("ignore:.*share no edge:lkspace.errors.LkspaceWarning")
def test_one_vertex_copy_per_face(name, orders, tmp_path, capsys):
    path = write_obj(tmp_path / "u.obj", *unwelded(lkspace.load(name)))
    code, data, _ = info(capsys, path)
    assert code == 0
    assert (data["symmetry_group_order"]["isometries"], data["symmetry_group_order"]["rotations"]) == orders
    assert_valid(lkspace.load(path))


def test_coincident_faces_small_use_the_exact_search():
    tri = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
    sc = Scaffold.from_faces(tri + tri, [[0, 1, 2], [3, 4, 5]])  # two triangles on the same place, unwelded
    g = assert_valid(sc)
    assert g.order == 8  # the mirror of the right triangle x 2 in-plane flips... and swapping the copies
    assert {(p.tobytes(), bool(s)) for p, s in zip(g.edge_perms, g.proper, strict=True)} == reference_actions(sc)


@pytest.mark.filterwarnings("always::lkspace.errors.LkspaceWarning")
def test_coincident_faces_large_fall_back_to_the_identity(tmp_path, capsys):
    tri = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    path = write_obj(tmp_path / "stack.obj", np.tile(tri, (12, 1)), [[3 * i, 3 * i + 1, 3 * i + 2] for i in range(12)])
    code, data, err = info(capsys, path)
    assert code == 0 and data["symmetry_group_order"] == {"rotations": 1, "isometries": 1}
    assert "lkspace: warning:" in err and "identity only" in err


def test_group_tables_past_the_bound(monkeypatch, capsys):
    import lkspace.symmetry.finite as finite

    monkeypatch.setattr(finite, "MAX_GROUP_ENTRIES", 2_000)
    assert main(["info", "dihedron:40"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--symmetry none" in err[0] and "2000" in err[0]


def test_candidates_past_the_bound(monkeypatch, capsys):
    import lkspace.symmetry.pointset as pointset

    monkeypatch.setattr(pointset, "MAX_FRAME_CANDIDATES", 10)
    assert main(["info", "dihedron:40"]) == 2
    assert "candidate motions" in capsys.readouterr().err


def test_progress_is_reported(monkeypatch, capsys):
    import lkspace.runtime.progress as progress

    monkeypatch.setenv("LKSPACE_PROGRESS", "1")
    monkeypatch.setattr(progress, "DELAY", 0.0)
    monkeypatch.setattr(progress, "PLAIN_EVERY", 0.0)
    assert main(["info", "icosahedron"]) == 0
    assert "symmetry search" in capsys.readouterr().err


# runs the command line and prints its peak RSS (kB) last on stderr; VmHWM, unlike ru_maxrss,
# starts afresh at exec and so does not count the forked copy of the test process
PEAK = (
    "import sys; from lkspace.cli import main; code = main(sys.argv[1:]); "
    "print(open('/proc/self/status').read().split('VmHWM:')[1].split()[0], file=sys.stderr); sys.exit(code)"
)


@pytest.mark.parametrize(
    ("n", "vertices"),
    [(90, 48_602), pytest.param(129, 99_848, marks=pytest.mark.slow)],  # a bool matrix V x V: 2.4 GB, 10 GB
)
def test_a_hundred_thousand_vertices_in_bounded_time_and_memory(tmp_path, n, vertices):
    """``lkspace info`` on a 48,602- (default run) or 99,848-vertex cube sphere: seconds and a few hundred MB (main: MemoryError)."""
    sc = cube_sphere(n)
    path = tmp_path / "sphere.obj"
    path.write_text(format_obj(sc))
    keep = ("PATH", "HOME", "PYTHONPATH", "PYTHONDONTWRITEBYTECODE", "LANG")
    env = {k: os.environ[k] for k in keep if k in os.environ} | {"LKSPACE_PROGRESS": "0"}  # not what earlier tests set
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    with open(tmp_path / "out.json", "w+") as out, open(tmp_path / "err.txt", "w+") as err:
        code = subprocess.call(
            [sys.executable, "-c", PEAK, "info", str(path), "--json"], stdout=out, stderr=err, env=env
        )
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime  # CPU seconds, whatever the load
        out.seek(0)
        err.seek(0)
        lines = err.read().splitlines()
        assert code == 0, lines
        peak_mb = int(lines[-1]) / 1024
        stdout = out.read()
    data = json.loads(stdout)
    assert data["vertices"] == vertices
    assert data["symmetry_group_order"] == {"rotations": 24, "isometries": 48}
    assert cpu < 60 and peak_mb < 1_000, (cpu, peak_mb)
