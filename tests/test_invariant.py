"""Symmetric designs (``--invariant``) against brute force from the vertex coordinates."""

from __future__ import annotations

import json
import re
from collections import Counter

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lkspace import load, read_catalog, symmetric_designs
from lkspace.design.invariant import make_invariant_space
from lkspace.design.invariant_walk import invariant_blocks
from lkspace.errors import UsageError
from lkspace.symmetry.group import symmetry_group
from lkspace.symmetry.subgroups import parse_subgroup
from tests.brute_symmetric import (
    all_assignments,
    fixed_rows,
    key,
    motions,
    normalizer,
    orbit_table,
    raw_edges,
    signed_edge_action,
)
from tests.cli_calls import one_line_error, run
from tests.reference import reference_trace


def _rot(q, sigma, sc, edges):
    return np.linalg.det(q) > 0


def _fixes_vertex(v, proper=True):
    return lambda q, s, sc, edges: s[v] == v and (np.linalg.det(q) > 0 or not proper)


def _fixes_edge(e, proper=True):
    def keep(q, s, sc, edges):
        a, b = edges[e]
        return {int(s[a]), int(s[b])} == {a, b} and (np.linalg.det(q) > 0 or not proper)

    return keep


def _fixes_face(f, proper=True, order=None):
    def keep(q, s, sc, edges):
        cycle = sc.faces()[f]
        fixed = sorted(s[cycle].tolist()) == sorted(cycle)
        small = order is None or np.allclose(np.linalg.matrix_power(q, order), np.eye(3))
        return fixed and small and (np.linalg.det(q) > 0 or not proper)

    return keep


def _about_normal(q, s, sc, edges):
    v = sc.vertices - sc.vertices.mean(axis=0)
    normal = np.cross(v[0], v[1])
    return np.linalg.det(q) > 0 and np.allclose(q @ normal, normal)


def _about_shared_edge(q, s, sc, edges):
    return np.linalg.det(q) > 0 and s[0] == 0 and s[1] == 1


CASES = [
    ("tetrahedron", [-2, -1, 0, 1, 2], "rotations", "C3:vertex=0", _fixes_vertex(0)),
    ("tetrahedron", [-2, -1, 0, 1, 2], "rotations", "C2", _fixes_edge(0)),
    ("tetrahedron", [-2, -1, 0, 1, 2], "rotations", "rotations", _rot),
    ("tetrahedron", [-2, -1, 0, 1, 2], "isometries", "isometry-stabilizer:edge=0", _fixes_edge(0, proper=False)),
    ("tetrahedron", [-1, 0, 1], "isometries", "isometries", lambda q, s, sc, e: True),
    ("tetrahedron", [-2, -1, 0, 1, 2], "none", "C3:vertex=1", _fixes_vertex(1)),
    ("cube", [-1, 0, 1], "rotations", "C3:vertex=0", _fixes_vertex(0)),
    ("cube", [-1, 0, 1], "rotations", "C4:face=0", _fixes_face(0)),
    ("cube", [-1, 0, 1], "rotations", "C2:face=0", _fixes_face(0, order=2)),
    ("cube", [-1, 0, 1], "rotations", "C2:edge=0", _fixes_edge(0)),
    ("cube", [-1, 0, 1], "isometries", "stabilizer:vertex=0", _fixes_vertex(0)),
    ("cube", [-1, 0, 1], "isometries", "isometry-stabilizer:vertex=0", _fixes_vertex(0, proper=False)),
    ("cube", [0, 1], "rotations", "isometry-stabilizer:face=0", _fixes_face(0, proper=False)),
    ("cube", [0, 1], "rotations", "C3:vertex=0", _fixes_vertex(0)),
    ("dihedron:4", [-2, -1, 0, 1, 2], "isometries", "C4", _about_normal),
    ("dihedron:4", [-2, -1, 0, 1, 2], "rotations", "stabilizer:vertex=0", _fixes_vertex(0)),
    ("book:3", [-1, 0, 1], "rotations", "C3:edge=0", _about_shared_edge),
    ("book:3", [-1, 0, 1], "isometries", "isometries", lambda q, s, sc, e: True),
]


def brute_force(name, label_set, mode, h_filter):
    """``(n_elements of H, fixed rows, {canonical row: orbit size})`` from coordinates alone."""
    sc = load(name)
    faces = sc.faces()
    edges = raw_edges(faces)
    assert edges == [tuple(e) for e in sc.edge_vertices.tolist()]
    degree = Counter(tuple(sorted((f[i], f[(i + 1) % len(f)]))) for f in faces for i in range(len(f)))
    moduli = np.array([degree[e] for e in edges])
    every = motions(sc.vertices, faces)
    sub = [(q, s) for q, s in every if h_filter(q, s, sc, edges)]
    in_mode = {"rotations": [m for m in every if np.linalg.det(m[0]) > 0], "isometries": every, "none": []}[mode]
    norm = normalizer([q for q, _ in in_mode], [q for q, _ in sub])
    sigma_of = {key(q): s for q, s in every}
    n_actions = [signed_edge_action(q, sigma_of[key(q)], edges) for q in norm]
    if mode == "none":
        n_actions = [(np.arange(len(edges)), 1)]
    distinct = {(p.tobytes(), s): (p, s) for p, s in n_actions}
    rows = fixed_rows(all_assignments(label_set, len(edges)), [signed_edge_action(q, s, edges) for q, s in sub])
    return len(sub), rows, orbit_table(rows, list(distinct.values()), moduli)


@pytest.mark.parametrize(
    ("name", "label_set", "mode", "spec", "h_filter"), CASES, ids=[f"{c[0]}-{c[3]}-{c[2]}" for c in CASES]
)
def test_symmetric_designs_match_brute_force(name, label_set, mode, spec, h_filter):
    order, fixed, table = brute_force(name, label_set, mode, h_filter)
    space = make_invariant_space(load(name), np.array(label_set), mode, spec)
    assert len(space.elements) == order
    assert space.n_fixed == len(fixed)
    assert space.count_designs() == len(table)
    got = {}
    for block in invariant_blocks(space):
        for row, size in zip(block.labels.tolist(), block.orbit_sizes.tolist(), strict=True):
            got[tuple(row)] = size
    assert got == table
    assert sum(got.values()) == len(fixed)


def test_the_space_shrinks_to_one_label_per_orbit():
    space = make_invariant_space(load("dodecahedron"), np.arange(-2, 3), "rotations", "C5:face=0")
    assert space.n_orbits == 6 and space.n_fixed == 5**6  # 30 edges in 6 orbits of 5
    assert space.count_designs() < space.n_fixed


def test_rows_trace_like_the_reference_tracer():
    sc = load("cube")
    df = next(symmetric_designs(sc, "C3:vertex=0", "-1..1"))
    edges = [tuple(e) for e in sc.edge_vertices.tolist()]
    for labels, components in zip(df["labels"], df["components"], strict=True):
        strands = reference_trace(sc.vertices.tolist(), sc.faces(), dict(zip(edges, labels, strict=True)))
        assert len(strands) == components


def test_trivial_subgroup_gives_the_plain_walk():
    import lkspace

    plain = next(lkspace.designs("tetrahedron", "-2,0,2"))
    sym = next(symmetric_designs("tetrahedron", "identity", "-2,0,2"))
    assert sorted(map(tuple, plain["labels"])) == sorted(map(tuple, sym["labels"]))
    assert sorted(plain.orbit_size) == sorted(sym.orbit_size)


def test_ambiguous_cyclic_names_give_axes_that_work():
    sc = load("cube")
    group = symmetry_group(sc)
    with pytest.raises(UsageError) as info:
        parse_subgroup("C2", sc, group)
    hints = re.findall(r"C2:\w+=\d+", str(info.value))
    assert len(hints) == 2
    subgroups = {parse_subgroup(h, sc, group).tobytes() for h in hints}
    assert len(subgroups) == 2 and all(len(parse_subgroup(h, sc, group)) == 2 for h in hints)


def test_perm_generators_name_the_group_they_generate():
    sc = load("cube")
    group = symmetry_group(sc)
    three = parse_subgroup("C3:vertex=0", sc, group)
    perm = ",".join(map(str, group.vertex_perms[three[1]].tolist()))
    assert np.array_equal(parse_subgroup(f"perm:{perm}", sc, group), three)


def test_cli_writes_a_symmetric_catalog(tmp_path, capsys):
    out = tmp_path / "c3.parquet"
    code, stdout, _ = run(
        capsys, "enumerate", "cube", "--labels", "-1..1", "--invariant", "C3:vertex=0", "-o", out, "--json"
    )
    assert code == 0
    payload = json.loads(stdout)
    _, fixed, table = brute_force("cube", [-1, 0, 1], "rotations", _fixes_vertex(0))
    assert payload["designs"] == len(table) and payload["fixed_assignments"] == len(fixed)
    cat = read_catalog(out)
    assert {tuple(r): int(s) for r, s in zip(cat.labels.tolist(), cat.frame.orbit_size, strict=True)} == table
    inv = cat.metadata["invariant"]
    assert inv["subgroup"] == "C3:vertex=0" and inv["order"] == 3 and inv["fixed_assignments"] == len(fixed)
    code, stdout, _ = run(
        capsys, "enumerate", "cube", "--labels", "-1..1", "--invariant", "C3:vertex=0", "--count-only", "--json"
    )
    assert code == 0 and json.loads(stdout)["designs"] == len(table)


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--invariant", "C7"], ["no rotation of order 7"]),
        (["--invariant", "C2"], ["C2:edge=", "C2:face="]),
        (["--invariant", "stabilizer:face=99"], ["face 99 out of range"]),
        (["--invariant", "frob"], ["unknown subgroup"]),
        (["--invariant", "perm:1,0"], ["2 images"]),
        (["--invariant", "C3", "--mode", "residues"], ["--mode"]),
    ],
)
def test_cli_bad_subgroups_are_one_usage_line(capsys, args, words):
    code, stdout, err = run(capsys, "enumerate", "cube", "--labels", "-1..1", *args)
    assert code == 2 and stdout == ""
    one_line_error(err, *words)


@settings(max_examples=25, deadline=None)
@given(
    name=st.sampled_from(["tetrahedron", "cube", "octahedron"]),
    picks=st.lists(st.integers(0, 47), min_size=1, max_size=2),
    label_set=st.sampled_from([(-1, 0, 1), (0, 1), (-1, 1)]),
    mode=st.sampled_from(["rotations", "isometries", "none"]),
)
def test_generated_subgroups_give_consistent_rows(name, picks, label_set, mode):
    sc = load(name)
    group = symmetry_group(sc)
    perms = ";".join(",".join(map(str, group.vertex_perms[p % group.order].tolist())) for p in picks)
    if mode == "isometries" and label_set == (0, 1):
        mode = "rotations"  # isometries need a label set closed under negation
    space = make_invariant_space(sc, np.array(label_set), mode, f"perm:{perms}")
    h = space.elements
    rows, sizes = [], []
    for block in invariant_blocks(space):
        rows += block.labels.tolist()
        sizes += block.orbit_sizes.tolist()
    assert len(set(map(tuple, rows))) == len(rows) == space.count_designs()
    assert sum(sizes) == space.n_fixed
    for row in np.array(rows, np.int64).reshape(-1, sc.n_edges):
        for p, s in zip(group.edge_perms[h], group.edge_signs[h], strict=True):
            image = np.empty_like(row)
            image[p] = s * row
            assert np.array_equal(image, row)  # fixed by every element of the subgroup
