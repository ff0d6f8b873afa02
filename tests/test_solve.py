"""lkspace.solve against exhaustive enumeration, plus options, fast path and CLI."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

import lkspace
from lkspace import Lattice, Scaffold, trace
from lkspace import solve as solve_design
from lkspace.cli import main
from lkspace.errors import LabelError, SolveVerificationError
from lkspace.inverse.cpsat_model import build_model
from lkspace.inverse.pipeline import SolveOptions, verify
from lkspace.inverse.query import Query
from lkspace.model.specs import parse_label_set
from tests.brute import allowed_per_edge, component_census, residue_classes


def random_mesh(seed: int) -> Scaffold:
    """Four random polygons on five generic points: boundary, K = 3 and K = 4 edges."""
    rng = np.random.default_rng(seed)
    vertices = rng.normal(size=(5, 3))
    faces = [list(rng.permutation(5)[: rng.integers(3, 5)]) for _ in range(4)]
    return Scaffold.from_faces(vertices, faces, name=f"random{seed}")


def square_torus(a: int, b: int) -> Scaffold:
    """The periodic square tiling as an a x b supercell (every edge class has K = 2)."""
    vertices = [[i, j, 0.0] for i in range(a) for j in range(b)]
    faces, offsets = [], []
    for i in range(a):
        for j in range(b):
            corners = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
            faces.append([(x % a) * b + (y % b) for x, y in corners])
            offsets.append([[x // a, y // b] for x, y in corners])
    return Scaffold.from_faces(
        vertices, faces, offsets=offsets, lattice=Lattice(np.diag([a, b, 1.0])[:2]), name=f"torus{a}x{b}"
    )


def mobius(n: int = 5) -> Scaffold:
    """A Mobius band of n quads (non-orientable; boundary and K = 2 edges)."""
    vertices = []
    for k in range(n):
        phi = 2 * np.pi * k / n
        for s in (-0.4, 0.4):
            r = 1 + s * np.cos(phi / 2)
            vertices.append([r * np.cos(phi), r * np.sin(phi), s * np.sin(phi / 2)])
    faces = [[2 * k, 2 * k + 1, 2 * k + 3, 2 * k + 2] for k in range(n - 1)] + [[2 * n - 2, 2 * n - 1, 0, 1]]
    return Scaffold.from_faces(vertices, faces, name=f"mobius{n}")


def solve(scaffold, n, **kw):
    kw["options"] = dataclasses.replace(kw.get("options") or SolveOptions(), workers=1)
    return solve_design(scaffold, n, **kw)


CASES = [
    ("tetrahedron", "-1,1"),
    ("tetrahedron", "0,1"),
    ("tetrahedron", "-2..2"),
    ("cube", "-1,1"),
    ("cube", "0,1"),
    ("octahedron", "1,2"),
    ("book:3", "-2..2"),
    ("book:4", "-2..2"),
    ("book:6", "0..5"),
    ("book:2", "1"),
    ("dihedron:3", "-1..1"),
    ("dihedron:4", "-1..1"),
    ("dihedron:6", "0,1"),
]


def _scaffold(name):
    if name.startswith("random"):
        return random_mesh(int(name[6:]))
    if name.startswith("torus"):
        a, b = name[5:].split("x")
        return square_torus(int(a), int(b))
    if name == "mobius":
        return mobius()
    return lkspace.load(name)


def _check_against_census(scaffold, labels, **query):
    allowed = allowed_per_edge(
        scaffold,
        parse_label_set(labels),
        query.get("no_zero", False),
        query.get("fixes"),
        query.get("parities"),
    )
    census = component_census(scaffold, allowed)
    for n in range(1, max(census) + 2):
        for fast in (True, False):
            result = solve(scaffold, n, label_set=labels, **query, options=SolveOptions(fast_path=fast))
            assert result.status == ("feasible" if n in census else "infeasible"), (scaffold.name, labels, n, fast)
            for sol in result.solutions:
                assert sol.components == n == trace(scaffold, sol.labels).components
                assert all(
                    int(t) in opts
                    for t, opts, k in zip(sol.labels, allowed, scaffold.edge_degrees, strict=True)
                    if k > 1 or True
                )


@pytest.mark.parametrize("name, labels", CASES)
def test_feasibility_matches_enumeration(name, labels):
    _check_against_census(_scaffold(name), labels)


@pytest.mark.parametrize(
    "name, labels",
    [
        ("random1", "-2..2"),
        ("random5", "-2..2"),
        ("random7", "-2..2"),
        ("random14", "-2..2"),
        ("torus2x2", "0,1"),
        ("torus3x1", "-1..1"),
        ("mobius", "-1..1"),
    ],
)
def test_feasibility_matches_enumeration_irregular(name, labels):
    _check_against_census(_scaffold(name), labels)


def test_cube_plus_minus_one_has_no_single_component():
    result = solve(lkspace.load("cube"), 1, label_set="-1,1")
    assert result.status == "infeasible" and result.solutions == []


@pytest.mark.parametrize("name", ["cube", "random5", "book:4"])
def test_fixes_and_parities_match_enumeration(name):
    scaffold = _scaffold(name)
    inner = np.flatnonzero(scaffold.edge_degrees > 1)
    fixes = {int(inner[0]): 1}
    parities = {int(inner[-1]): 0} if len(inner) > 1 else {}
    _check_against_census(
        scaffold, "-2..2" if name != "cube" else "0..2", fixes=fixes, parities=parities, no_zero=name == "random5"
    )


@pytest.mark.parametrize(
    "name, labels, n",
    [
        ("tetrahedron", "0,1", 1),
        ("tetrahedron", "0,1", 2),
        ("book:4", "-2..2", 2),
        ("random7", "-2..2", 2),
        ("random5", "-2..2", 3),
    ],
)
def test_count_returns_every_distinct_design_and_no_more(name, labels, n):
    scaffold = _scaffold(name)
    allowed = allowed_per_edge(scaffold, parse_label_set(labels))
    classes = residue_classes(scaffold, allowed, n)
    result = solve(scaffold, n, label_set=labels, options=SolveOptions(count=len(classes) + 3))
    got = {tuple((s.labels % scaffold.edge_degrees).tolist()) for s in result.solutions}
    assert got == classes and len(result.solutions) == len(classes)
    assert result.exhausted and result.status == "feasible"


@pytest.mark.parametrize("fast", [True, False])
def test_count_gives_distinct_single_component_designs(fast):
    cube = lkspace.load("cube")
    result = solve(cube, 1, no_zero=True, options=SolveOptions(count=4, fast_path=fast))
    residues = {tuple((s.labels % 2).tolist()) for s in result.solutions}
    assert len(result.solutions) == 4 == len(residues)
    assert all(np.all(s.labels != 0) for s in result.solutions)


def test_fast_path_on_default_and_nonorientable():
    for scaffold in (lkspace.load("tetrahedron"), lkspace.load("icosahedron"), mobius(7), square_torus(3, 2)):
        result = solve(scaffold, 1, no_zero=True)
        assert result.method == "fast-path" and result.status == "feasible"
        assert np.all(result.solutions[0].labels != 0)
        assert trace(scaffold, result.solutions[0].labels).components == 1


def test_fast_path_respects_pinned_edges_or_falls_back():
    cube = lkspace.load("cube")
    result = solve(cube, 1, parities={e: 1 for e in range(5)}, fixes={7: 2})
    assert result.status == "feasible"
    labels = result.solutions[0].labels
    assert np.all(labels[:5] % 2 == 1) and labels[7] == 2
    # the three edges at a vertex join three faces in a triangle of the dual graph: no
    # spanning tree holds all three, so pinning them odd sends the query to CP-SAT
    star = np.flatnonzero(np.any(cube.edge_vertices == 0, axis=1))
    result = solve(cube, 1, label_set="0,1", parities={int(e): 1 for e in star})
    assert len(star) == 3 and result.method == "cp-sat"
    allowed = allowed_per_edge(cube, [0, 1], parities={int(e): 1 for e in star})
    assert result.status == ("feasible" if 1 in component_census(cube, allowed) else "infeasible")
    for sol in result.solutions:
        assert np.all(sol.labels[star] % 2 == 1)


@pytest.mark.parametrize("name", ["cube", "dodecahedron"])
def test_objectives_agree_between_fast_path_and_cp_sat(name):
    scaffold = lkspace.load(name)
    fast = solve(scaffold, 1, objective="min-abs")
    slow = solve(scaffold, 1, objective="min-abs", options=SolveOptions(fast_path=False))
    assert fast.method == "fast-path" and fast.status == slow.status == "optimal"
    assert np.abs(fast.solutions[0].labels).sum() == np.abs(slow.solutions[0].labels).sum() == scaffold.n_faces - 1
    nonzero = solve(scaffold, 2, objective="min-nonzero", options=SolveOptions(fast_path=False))
    assert nonzero.status == "optimal"


def test_min_abs_optimum_matches_enumeration():
    scaffold = lkspace.load("tetrahedron")
    allowed = allowed_per_edge(scaffold, range(-2, 3), no_zero=True)
    for n in (1, 2, 3):
        best = min((int(np.abs(t).sum()) for t, c in _designs(scaffold, allowed) if c == n), default=None)
        result = solve(scaffold, n, no_zero=True, objective="min-abs")
        assert result.status == "optimal"
        assert int(np.abs(result.solutions[0].labels).sum()) == best


def _designs(scaffold, allowed):
    from tests.brute import designs

    return designs(scaffold, allowed)


def test_time_out_is_unknown_never_infeasible():
    result = solve(lkspace.load("dodecahedron"), 3, options=SolveOptions(time_limit=0.0, fast_path=False))
    assert result.status == "unknown" and result.solutions == []


def test_contradictions_and_empty_choices():
    cube = lkspace.load("cube")
    with pytest.raises(LabelError):
        solve(cube, 1, no_zero=True, fixes={0: 0})
    with pytest.raises(LabelError):
        solve(cube, 1, fixes={0: 1}, parities={0: 0})
    result = solve(cube, 1, label_set="1", parities={3: 0})
    a, b = cube.edge_vertices[3]
    assert result.status == "infeasible"
    assert result.reason == f"edge {a}-{b} has no allowed label", result.reason  # edge 3, named by its vertices
    with pytest.raises(LabelError):
        solve(cube, 0)


def test_model_contracts_fixed_links():
    model = build_model(lkspace.load("book:3"), Query(1))
    assert model.n_nodes == 3 and model.n_fixed_cycles == 0  # every page is one path through the spine
    model = build_model(lkspace.load("cube"), Query(2, label_set=np.array([0])))
    assert model.decided == "infeasible" and model.n_fixed_cycles == 6


def test_verify_fails_loudly():
    with pytest.raises(SolveVerificationError):
        verify(lkspace.load("cube"), np.ones(12, np.int64), 1)


def test_top_level_api():
    result = lkspace.solve(lkspace.load("cube"), 1, no_zero=True)
    assert result.solutions[0].components == 1


def _run(capsys, *args):
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_default_scaffold_as_typed(capsys):
    code, out, err = _run(capsys, "solve", "--components", "1")
    assert code == 0 and "tetrahedron" in err and "feasible" in out


def test_cli_json_and_output_file(capsys, tmp_path):
    path = tmp_path / "design.json"
    code, out, _ = _run(
        capsys,
        "solve",
        "cube",
        "--components",
        "2",
        "--labels",
        "-1,1,2",
        "--fix",
        "0-1=2",
        "--parity",
        "1=odd",
        "--count",
        "2",
        "--workers",
        "1",
        "-o",
        str(path),
        "--json",
    )
    data = json.loads(out)
    assert code == 0 and data["status"] == "feasible" and len(data["solutions"]) == 2
    cube = lkspace.load("cube")
    for sol in data["solutions"]:
        assert sol["components"] == 2 and sol["labels"][0] == 2 and sol["labels"][1] % 2 == 1
        assert set(sol["labels"]) <= {-1, 1, 2}
    design = lkspace.load(str(path))
    assert design.labels.tolist() == data["solutions"][0]["labels"]
    assert trace(design).components == 2 == trace(cube, design.labels).components


def test_cli_infeasible_is_an_answer(capsys):
    code, out, _ = _run(capsys, "solve", "cube", "-n", "1", "--labels", "-1,1", "--json")
    assert code == 0 and json.loads(out)["status"] == "infeasible"


@pytest.mark.parametrize(
    "args",
    [
        ["--fix", "0-9=1"],
        ["--fix", "3"],
        ["--parity", "0=blue"],
        ["--fix", "0=x"],
        ["--labels", "2..1"],
        ["--distinct-up-to", "sideways"],
        ["-o", "x.obj"],
    ],
)
def test_cli_bad_input_is_one_line(capsys, args):
    code, out, err = _run(capsys, "solve", "cube", "-n", "1", *args)
    assert code == 2 and out == "" and err.count("\n") == 1 and "Traceback" not in err  # no --json: stdout empty


@pytest.mark.parametrize("name", ["book:5", "random1", "random15"])
def test_greedy_fast_path_on_non_manifold(name):
    scaffold = _scaffold(name)
    assert scaffold.edge_degrees.max() >= 3
    result = solve(scaffold, 1, no_zero=True)
    allowed = allowed_per_edge(scaffold, range(-2, 3), no_zero=True)
    assert result.status == ("feasible" if 1 in component_census(scaffold, allowed) else "infeasible")
    if result.method == "fast-path":
        assert trace(scaffold, result.solutions[0].labels).components == 1


def test_distinct_up_to_symmetry_gives_one_design_per_orbit():
    from lkspace.inverse.pipeline import solve_cp_sat

    scaffold = lkspace.load("dihedron:6")
    ev = scaffold.edge_vertices
    index = {tuple(sorted(p)): e for e, p in enumerate(ev.tolist())}
    actions = []
    for shift in range(1, 6):  # rotations of the hexagon act on edges; labels keep their sign
        perm = np.array([index[tuple(sorted(((a + shift) % 6, (b + shift) % 6)))] for a, b in ev.tolist()])
        actions.append((perm, 1))
    classes = residue_classes(scaffold, allowed_per_edge(scaffold, [0, 1]), 2)
    orbits = set()
    for c in classes:
        images = [c] + [tuple(np.array(c)[np.argsort(perm)].tolist()) for perm, _ in actions]
        orbits.add(min(images))
    query = Query(2, label_set=np.array([0, 1]))
    result = solve_cp_sat(scaffold, query, SolveOptions(count=50, workers=1), actions, 0.0)
    got = {
        min([tuple((s.labels % 2).tolist())] + [tuple((s.labels % 2)[np.argsort(p)].tolist()) for p, _ in actions])
        for s in result.solutions
    }
    assert len(result.solutions) == len(orbits) == len(got) and got == orbits and result.exhausted


@pytest.mark.parametrize(
    "name, labels, mode",
    [
        ("tetrahedron", "0,1", "rotations"),
        ("cube", "0,1", "rotations"),
        ("cube", "-1..1", "isometries"),
        ("book:3", "0..2", "rotations"),
    ],
)
def test_distinct_up_to_symmetry_matches_the_residue_orbits(name, labels, mode):
    # solutions are distinct up to symmetry at the level of residues (the design's topology):
    # as many as the one-component residue-class orbits that enumerate --mode residues lists
    import pandas as pd

    scaffold = lkspace.load(name)
    result = solve(scaffold, 1, label_set=labels, options=SolveOptions(count=500, distinct_up_to=mode, fast_path=False))
    orbits = pd.concat(
        list(lkspace.designs(scaffold, labels, mode, selection=lkspace.Selection(mode="residues", components=1)))
    )
    assert result.status == "optimal" or result.exhausted
    assert len(result.solutions) == len(orbits)
    assert all(trace(scaffold, s.labels).components == 1 for s in result.solutions)


def test_distinct_up_to_isometries_needs_a_symmetric_label_set():
    with pytest.raises(LabelError):
        solve(lkspace.load("cube"), 1, label_set="0,1", options=SolveOptions(count=2, distinct_up_to="isometries"))


def test_real_time_out_reports_unknown():
    from lkspace.scaffolds.spheres import cube_sphere

    result = solve(cube_sphere(10), 1, no_zero=True, options=SolveOptions(fast_path=False, time_limit=1.0))
    assert result.status in ("unknown", "feasible")
    assert (result.status == "unknown") == (result.solutions == [])


@pytest.mark.parametrize(
    "name, n", [("cube", 1), ("cube", 3), ("book:4", 2), ("random1", 2), ("torus3x1", 1), ("dodecahedron", 4)]
)
def test_every_design_satisfies_the_model(name, n):
    """The constructive half of exactness: a design's own routes and labels satisfy the model."""
    from ortools.sat.python import cp_model

    scaffold = _scaffold(name)
    allowed = allowed_per_edge(scaffold, range(-2, 3))
    design = next((t for t, c in _designs(scaffold, allowed) if c == n), None) if scaffold.n_edges <= 12 else None
    if design is None:
        design = solve(scaffold, n).solutions[0].labels
    dm = build_model(scaffold, Query(n))
    dm.hint(design % scaffold.edge_degrees)
    solver = cp_model.CpSolver()
    solver.parameters.num_workers = 1
    solver.parameters.fix_variables_to_their_hinted_value = True
    assert solver.solve(dm.model) in (cp_model.OPTIMAL, cp_model.FEASIBLE)


def test_api_rejects_out_of_range_edges():
    cube = lkspace.load("cube")
    for kw in ({"fixes": {12: 1}}, {"parities": {-1: 0}}, {"parities": {0: 2}}):
        with pytest.raises(LabelError):
            solve(cube, 1, **kw)


def test_an_objective_with_ties_gives_the_same_design_at_any_load():
    # the dodecahedron has many designs of least sum |t| (its rotations and others): a parallel
    # search returned whichever worker met one first, so the answer changed from run to run
    # (2 of 4 runs differed); interleaved, the same number of workers gives the same design
    import subprocess
    import sys

    cmd = [sys.executable, "-m", "lkspace", "solve", "dodecahedron", "-n", "2", "--labels", "-1,1,2", "--fix", "0=2",
           "--objective", "min-abs", "--workers", "2", "--json"]  # fmt: skip
    runs = [subprocess.Popen(cmd, stdout=subprocess.PIPE, text=True) for _ in range(4)]  # at once: loaded
    answers = {tuple(json.loads(run.communicate()[0])["solutions"][0]["labels"]) for run in runs}
    assert len(answers) == 1, answers
