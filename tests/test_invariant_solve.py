"""``solve --invariant``: every symmetric design with N components, checked by brute force."""

from __future__ import annotations

import functools
import json

import numpy as np
import pytest

from lkspace import load
from tests.brute_symmetric import all_assignments, fixed_rows, motions, raw_edges, signed_edge_action
from tests.cli_calls import one_line_error, run
from tests.reference import reference_trace


@functools.lru_cache(maxsize=2)
def cube_c3_table():
    """The brute force for the cube, labels -1..1, rotations about vertex 0 (shared by the tests)."""
    return brute_residues_by_components("cube", (-1, 0, 1), lambda q, s: np.linalg.det(q) > 0 and s[0] == 0)


def brute_residues_by_components(name, label_set, h_filter):
    """``{components: set of residue vectors}`` of the assignments fixed by the motions ``h_filter`` keeps."""
    sc = load(name)
    faces = sc.faces()
    edges = raw_edges(faces)
    sub = [signed_edge_action(q, s, edges) for q, s in motions(sc.vertices, faces) if h_filter(q, s)]
    moduli = np.array(
        [sum(1 for f in faces for i in range(len(f)) if tuple(sorted((f[i], f[(i + 1) % len(f)]))) == e) for e in edges]
    )
    out: dict[int, set] = {}
    for row in fixed_rows(all_assignments(label_set, len(edges)), sub):
        n = len(reference_trace(sc.vertices.tolist(), faces, dict(zip(edges, row.tolist(), strict=True))))
        out.setdefault(n, set()).add(tuple((row % moduli).tolist()))
    return out, sub


@pytest.mark.parametrize("components", [1, 2, 3, 4, 5, 6])
def test_solve_finds_exactly_the_symmetric_designs(capsys, components):
    table, sub = cube_c3_table()
    code, out, _ = run(
        capsys,
        "solve",
        "cube",
        "-n",
        components,
        "--labels",
        "-1..1",
        "--invariant",
        "C3:vertex=0",
        "--count",
        50,
        "--json",
    )
    assert code == 0
    result = json.loads(out)
    found = np.array([s["labels"] for s in result["solutions"]], np.int64).reshape(-1, 12)
    assert len(fixed_rows(found, sub)) == len(found)  # every answer is fixed by the rotations about vertex 0
    assert {tuple((row % 2).tolist()) for row in found} == table.get(components, set())
    assert result["status"] == ("feasible" if components in table else "infeasible")


def test_solve_invariant_with_mirrors_forces_zero_labels(capsys):
    # the cube's 8 motions fixing face 0 tie every edge to a mirror mapping it onto itself: all labels 0
    code, out, _ = run(capsys, "solve", "cube", "-n", 6, "--invariant", "isometry-stabilizer:face=0", "--json")
    assert code == 0 and json.loads(out)["solutions"][0]["labels"] == [0] * 12
    code, out, _ = run(capsys, "solve", "cube", "-n", 4, "--invariant", "isometry-stabilizer:face=0", "--json")
    assert code == 0 and json.loads(out)["status"] == "infeasible"


def test_solve_bad_subgroup_is_one_usage_line(capsys):
    code, out, err = run(capsys, "solve", "cube", "-n", 2, "--invariant", "C5")
    assert code == 2 and out == ""
    one_line_error(err, "no rotation of order 5")
