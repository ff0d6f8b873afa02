"""Motifs and gradients on supercells (``lkspace.design.motifs``) against hand-made expansions."""

from __future__ import annotations

import itertools
import json

import numpy as np
import pytest

from lkspace import load
from lkspace.design.motifs import (
    cell_map,
    check_tiles,
    gradient_labels,
    motif_classes,
    motif_labels,
    tiling_matrix,
)
from lkspace.errors import LabelError
from lkspace.symmetry.group import symmetry_group
from tests.cli_calls import one_line_error, run


def square_edges(sizes):
    """Per supercell edge of ``tiling:square@AxB``: (base edge 0 = x / 1 = y, cell), from edge midpoints."""
    sc = load(f"tiling:square@{sizes[0]}x{sizes[1]}")
    out = []
    for a, b, *delta in sc.edge_keys.tolist():
        pa = sc.vertices[a, :2]
        pb = sc.vertices[b, :2] + np.asarray(delta) @ sc.lattice.basis[:, :2]
        mid = (pa + pb) / 2
        if abs(mid[0] - round(mid[0])) < 1e-9:  # an x-edge: from cell x - 1 to cell x
            out.append((0, (int(round(mid[0])) - 1) % sizes[0], int(np.floor(mid[1])) % sizes[1]))
        else:
            out.append((1, int(np.floor(mid[0])) % sizes[0], (int(round(mid[1])) - 1) % sizes[1]))
    return sc, out


def test_cell_map_matches_the_midpoints():
    sc, expected = square_edges((3, 2))
    base_edge, cell = cell_map(load("tiling:square"), sc, (3, 2))
    assert [(int(e), int(c[0]), int(c[1])) for e, c in zip(base_edge, cell, strict=True)] == expected


def test_brick_bond_motif_shifts_each_row():
    sc, edges = square_edges((4, 2))
    base_edge, cell = cell_map(load("tiling:square"), sc, (4, 2))
    motif = np.array([[1, -1], [2, 0]])  # two cells of a block, (x-edge, y-edge) each
    labels = motif_labels(base_edge, cell, motif, tiling_matrix((2, 1), (1,)))
    assert labels.tolist() == [int(motif[(x - y) % 2, e]) for e, x, y in edges]


def test_gradient_follows_the_layers():
    sc, edges = square_edges((4, 1))
    base_edge, cell = cell_map(load("tiling:square"), sc, (4, 1))
    assert gradient_labels(base_edge, cell, [0, 1, 2, -1], (1, 0)).tolist() == [[0, 1, 2, -1][x] for _, x, _ in edges]
    per_edge = np.array([[0, 1], [1, 1], [2, 1], [0, 0]])
    assert gradient_labels(base_edge, cell, per_edge, (1, 0)).tolist() == [int(per_edge[x, e]) for e, x, _ in edges]


def brute_square_classes(sizes, rows):
    """Orbits of label rows on ``tiling:square@AxB`` under its motions, found from midpoints."""
    sc, _ = square_edges(sizes)
    mids = []
    for a, b, *delta in sc.edge_keys.tolist():
        pb = sc.vertices[b, :2] + np.asarray(delta) @ sc.lattice.basis[:, :2]
        mids.append((sc.vertices[a, :2] + pb) / 2)
    mids = np.array(mids)
    period = np.array(sizes, float)

    def key(p):
        return tuple(np.round(np.mod(p, period), 6) % period)

    index = {key(m): i for i, m in enumerate(mids)}
    perms = []
    quarter = np.array([[0, -1], [1, 0]])
    mirror = np.array([[1, 0], [0, -1]])  # a half-turn about the x axis, proper in space
    for k, flip in itertools.product(range(4), (False, True)):
        q = np.linalg.matrix_power(quarter, k) @ (mirror if flip else np.eye(2))
        if np.any(np.mod(q @ np.diag(period), period[:, None]) != 0):
            continue  # q must map the supercell's periods to periods, or it is no motion of the torus
        for shift in itertools.product(range(sizes[0]), range(sizes[1])):
            image = [key(q @ (m - 0.5) + 0.5 + np.array(shift)) for m in mids]
            if all(i in index for i in image):
                perms.append(np.array([index[i] for i in image]))
    seen, classes = set(), 0
    for row in rows:
        if tuple(row) in seen:
            continue
        classes += 1
        for p in perms:
            img = np.empty_like(row)
            img[p] = row
            seen.add(tuple(img))
    return classes


@pytest.mark.parametrize(
    ("sizes", "block", "shifts"), [((2, 2), (1, 1), ()), ((4, 2), (2, 1), (1,)), ((2, 2), (2, 1), (0,))]
)
def test_motif_classes_match_brute_force(sizes, block, shifts):
    sc, _ = square_edges(sizes)
    base_edge, cell = cell_map(load("tiling:square"), sc, sizes)
    tiling = tiling_matrix(block, shifts)
    perms, signs = symmetry_group(sc).action("rotations")
    classes = motif_classes(base_edge, cell, tiling, [-1, 0, 1], perms, signs)
    n_vars = int(np.prod(block)) * 2
    rows = [motif_labels(base_edge, cell, np.array(m), tiling) for m in itertools.product([-1, 0, 1], repeat=n_vars)]
    assert sum(c.motifs for c in classes) == 3**n_vars
    assert len(classes) == brute_square_classes(sizes, rows)


def test_a_tiling_that_does_not_close_is_refused():
    with pytest.raises(LabelError, match="does not repeat evenly"):
        check_tiles(tiling_matrix((3, 1)), (4, 2))


def test_cli_motifs_report_threads_and_holding(capsys):
    code, out, _ = run(capsys, "motifs", "tiling:square", "--supercell", "4x2", "--block", "2x1", "--offsets", "1",
                       "--labels", "-1,1", "--json")  # fmt: skip
    assert code == 0
    payload = json.loads(out)
    assert sum(r["motifs"] for r in payload["classes"]) == 2**4
    for row in payload["classes"]:
        assert len(row["periods"]) == row["components"] and isinstance(row["holds_together"], bool)
    code, out, _ = run(capsys, "motifs", "tiling:square", "--supercell", "4x1", "--gradient", "1,0:0,1,-1,1", "--json")
    assert (
        code == 0
        and json.loads(out)["classes"][0]["labels"]
        == gradient_labels(
            *cell_map(load("tiling:square"), load("tiling:square@4x1"), (4, 1)), [0, 1, -1, 1], (1, 0)
        ).tolist()
    )
    code, out, err = run(capsys, "motifs", "tiling:square", "--supercell", "4x2", "--block", "3x1")
    assert code == 2 and out == ""
    one_line_error(err, "does not repeat evenly")
