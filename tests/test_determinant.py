"""The determinant filter of ``solve --type`` (lkspace.knots.determinant).

References kept apart from the code under test: KnotInfo's and LinkInfo's ``determinant``
columns (``database_knotinfo``) for the exact form on the tables' own diagrams, and
regina's Jones polynomial at ``t = -1`` (``|V(-1)|``) for the compiled residues of designs' diagrams.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from lkspace import load
from lkspace.knots.determinant import PRIME, determinant, determinants_of, same_determinant
from lkspace.knots.keyed import keys_of
from lkspace.linktypes.names import parse_type

dki = pytest.importorskip("database_knotinfo")
regina = pytest.importorskip("regina")


def _jones_at_minus_one(pd: list[list[int]]) -> int:
    """``|V(-1)|`` from regina's Jones polynomial in ``x = sqrt t``, at ``x = i``."""
    jones = regina.Link.fromPD(pd).jones()
    parts = [0, 0]  # real and imaginary parts: i^k is 1, i, -1, -i
    for k in range(jones.minExp(), jones.maxExp() + 1):
        parts[k % 2] += int(str(jones[k])) * (-1 if k % 4 >= 2 else 1)
    assert 0 in parts  # V(-1) is real or purely imaginary
    return abs(parts[0]) + abs(parts[1])


def _table_rows():
    """(name, PD code, determinant) of KnotInfo's knots up to 10 crossings and LinkInfo's links up to 9."""
    for row in dki.link_list()[1:]:
        pd = json.loads(row["pd_notation"] or "[]")
        if 0 < len(pd) <= 10:
            yield row["name"], pd, int(row["determinant"])
    for row in dki.link_list(proper_links=True)[1:]:
        text = row["pd_notation_vector"]
        if text and int(row["crossing_number"]) <= 9:
            yield row["name"], json.loads(text.replace("{", "[").replace("}", "]")), int(row["determinant"])


def test_exact_determinants_equal_the_tables_column():
    rows = list(_table_rows())
    assert len(rows) > 249 + 100  # every knot up to 10 crossings and the links up to 9
    wrong = [(name, determinant(pd), det) for name, pd, det in rows if determinant(pd) != det]
    assert wrong == []


def test_trivial_and_split_diagrams():
    assert determinant([], n_free=1) == 1  # the unknot
    assert determinant([], n_free=2) == 0  # the unlink
    assert determinant([[1, 5, 2, 4], [3, 1, 4, 6], [5, 3, 6, 2]], n_free=1) == 0  # trefoil and a far circle
    assert parse_type("3_1#4_1").determinant == 15
    assert parse_type("L6a4").determinant == 16


@pytest.mark.parametrize(("mesh", "values"), [("tetrahedron", (-2, 2)), ("cube", (-1, 1)), ("prism:5", (-1, 1))])
def test_design_residues_equal_the_jones_polynomial_at_minus_one(mesh, values):
    scaffold = load(mesh)
    rng = np.random.default_rng(7)
    labels = rng.integers(values[0], values[1] + 1, size=(120, scaffold.n_edges))
    residues = determinants_of(scaffold, labels)
    found = keys_of(scaffold, labels)
    checked = 0
    for d in range(len(labels)):
        pd, n_comp, _ = found.diagram(d)
        if not pd or found.free[d]:
            expected = 1 if (n_comp == 1 and not pd) else 0
        else:
            expected = _jones_at_minus_one(pd)
        assert residues[d] in (expected % PRIME, -expected % PRIME), (labels[d].tolist(), residues[d], expected)
        checked += int(expected > 1)
    assert checked > 20  # most designs have a determinant worth comparing


def test_a_target_is_never_filtered_out_by_its_own_designs():
    cube = load("cube")
    labels = np.array([[1] * 12, [0, 0, -1, -1, -1, -1, 0, 0, 0, -1, -1, -1], [-1] * 12])
    residues = determinants_of(cube, labels)
    assert same_determinant(residues, parse_type("L12a2008").determinant)[0]
    assert same_determinant(residues, parse_type("7_4").determinant)[1]
    assert not same_determinant(residues, parse_type("3_1").determinant)[1]
    assert same_determinant(np.array([-1]), 3)[0]  # not computed: kept
