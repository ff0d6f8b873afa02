"""Identification with the mathematics as the oracle: torus families, classical links, mirrors."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

pytest.importorskip("snappy")
pytest.importorskip("spherogram")
pytest.importorskip("regina")
pytest.importorskip("database_knotinfo")

import lkspace  # noqa: E402
from lkspace import identify  # noqa: E402
from lkspace.cli import main  # noqa: E402
from lkspace.errors import LkspaceError  # noqa: E402
from lkspace.knots.batch import NamerOptions, identify_batch  # noqa: E402
from lkspace.knots.diagram import project  # noqa: E402
from lkspace.knots.recognition import identify_curves  # noqa: E402
from tests.test_geometry import gauss_linking  # noqa: E402  (at import: @given may not run inside a test)


def name_of(mesh, twists):
    scaffold = lkspace.load(mesh)
    return identify(scaffold, np.asarray(twists) if not np.isscalar(twists) else twists).to_dict()


def torus(p: int, q: int, n: int = 400, sign: int = 1) -> list[np.ndarray]:
    """The (p, q) torus knot or link on the standard torus; ``sign=-1`` is its mirror."""
    g = np.gcd(p, q)
    s = np.linspace(0, 2 * np.pi / g, n, endpoint=False)
    out = []
    for k in range(g):
        th = q * s + 2 * np.pi * k / g
        r = 2 + np.cos(th)
        out.append(np.column_stack([r * np.cos(p * s), r * np.sin(p * s), -sign * np.sin(th)]))
    return out


def test_projection_linking_number_matches_the_gauss_integral():
    a, b = torus(2, 4)
    d = project([a, b], seed=3)
    assert d.linking_matrix()[0, 1] == round(gauss_linking(a, b)) == 2
    d = project([a, b[::-1]], seed=5)
    assert d.linking_matrix()[0, 1] == -2


@pytest.mark.parametrize("p, q, name", [(2, 3, "3_1"), (2, 5, "5_1"), (3, 4, "8_19"), (2, 4, "L4a1"), (3, 3, "L6n1")])
def test_parametric_torus_links(p, q, name):
    r = identify_curves(torus(p, q))
    assert r.name == name
    m = identify_curves(torus(p, q, sign=-1))
    assert m.name == name
    if np.gcd(p, q) == 1:  # knots: KnotInfo's diagrams are the positive ones
        assert (r.mirror, m.mirror) == (False, True)


@pytest.mark.parametrize(
    "mesh, twists, name, components",
    [
        ("dihedron:3", 1, "3_1", 1),
        ("dihedron:3", [2, 2, -1], "3_1", 1),  # only the sum s = 3 matters: T(2, 3)
        ("dihedron:5", [1, 1, 1, 0, 0], "3_1", 1),
        ("dihedron:5", 1, "5_1", 1),
        ("dihedron:7", 1, "7_1", 1),
        ("dihedron:3", [1, 0, 0], "0_1", 1),  # s = 1: unknot
        ("dihedron:3", [-1, 0, 0], "0_1", 1),
        ("dihedron:4", 1, "L4a1", 2),  # Solomon link T(2, 4)
        ("dihedron:4", [1, 1, 0, 0], "L2a1", 2),  # Hopf link T(2, 2)
        ("dihedron:8", 1, "L8a14", 2),
        ("book:3", 2, "3_1", 1),  # T(3, 2)
        ("book:5", 2, "5_1", 1),  # T(5, 2) = T(2, 5)
        ("book:4", 3, "8_19", 1),  # T(4, 3)
        ("book:3", 3, "L6n1", 3),  # T(3, 3)
        ("book:3", 1, "0_1", 1),  # T(3, 1)
        ("tetrahedron", 1, "L6a4", 3),  # Borromean rings
        ("figure-eight", [1, 1, 1, 1, 0], "4_1", 1),
        ("whitehead", [0, 0, -2, 0, -1, 0, -1, 2], "L5a1", 2),
    ],
)
def test_known_knots_and_links(mesh, twists, name, components):
    r = name_of(mesh, twists)
    assert r["components"] == components
    assert r["name"] == name, r


@pytest.mark.parametrize(
    "mesh, twist, name", [("dihedron:3", 1, "3_1"), ("dihedron:5", 1, "5_1"), ("book:4", 3, "8_19")]
)
def test_mirror_labels_give_mirror_knots(mesh, twist, name):
    pos = name_of(mesh, twist)
    neg = name_of(mesh, -twist)
    assert pos["name"] == neg["name"] == name
    assert pos["mirror"] is False and neg["mirror"] is True  # positive twists: positive torus knots
    assert pos["chiral_name"] == name and neg["chiral_name"] == "m" + name


def test_amphichiral_and_link_mirrors():
    assert name_of("figure-eight", [-1, -1, -1, -1, 0])["name"] == "4_1"
    w = name_of("whitehead", [0, 0, -2, 0, -1, 0, -1, 2])
    wm = name_of("whitehead", [0, 0, 2, 0, 1, 0, 1, -2])
    assert w["name"] == wm["name"] == "L5a1" and w["mirror"] is not wm["mirror"]
    assert name_of("tetrahedron", -1)["name"] == "L6a4"


def test_linking_matrix_of_the_solomon_link():
    r = name_of("dihedron:4", 1)
    lk = np.array(r["linking_matrix"])
    assert lk.shape == (2, 2) and abs(lk[0, 1]) == 2 and lk[0, 1] == lk[1, 0]


def test_unknown_beyond_the_tables_keeps_invariants():
    r = name_of("book:4", 4)  # T(4, 4): 12 crossings, beyond LinkInfo
    assert r["components"] == 4 and r["name"] is None
    assert r["jones"] and r["crossings"] >= 12
    assert len(r["linking_matrix"]) == 4


def test_split_link_is_named_as_such():
    r = name_of("cube", 0)  # six separate face loops
    assert r["components"] == 6 and r["split"] is True and r["name"] == "split: " + " + ".join(["0_1"] * 6)


def test_open_strands_cannot_be_identified(tetra):
    with pytest.raises(LkspaceError, match="open strands"):
        identify(tetra, 1, nulls=[0])


def test_identify_batch_in_two_processes():
    sc = lkspace.load("dihedron:3")
    labels = np.array([[1, 1, 1], [-1, -1, -1], [1, 0, 0], [2, 2, 1], [0, 0, 0]])
    df = identify_batch(sc, labels, NamerOptions(processes=2))
    assert list(df["knot_name"][:4]) == ["3_1", "3_1", "0_1", "5_1"]
    assert list(df["mirror"][:2]) == [False, True]
    assert pd.isna(df["knot_name"][4]) and bool(df["split"][4]) and pd.isna(df["error"][4])  # two loops
    assert list(df["components"]) == [1, 1, 1, 1, 2]
    assert json.loads(df["linking_matrix"][0]) == [[0]]


def test_cli_identify_json(capsys):
    code = main(["identify", "book:4", "--twist", "3", "--json"])
    out, _ = capsys.readouterr()
    assert code == 0
    data = json.loads(out)
    assert data["components"] == 1 and data["name"] == "8_19" and data["linking_matrix"] == [[0]]
    assert data["crossings"] == 8


def test_cli_identify_human_and_errors(capsys):
    assert main(["identify", "tetrahedron", "--twist", "1"]) == 0
    out, _ = capsys.readouterr()
    assert "L6a4" in out
    assert main(["identify", "tetrahedron", "--twist", "1", "--null", "0.0"]) == 1
    _, err = capsys.readouterr()
    assert err.count("\n") == 1 and "open strands" in err


def test_missing_extra_names_the_install_hint(monkeypatch, tetra):
    from lkspace.errors import MissingDependencyError

    monkeypatch.setitem(__import__("sys").modules, "spherogram", None)
    with pytest.raises(MissingDependencyError, match=r"pip install 'lkspace\[knots\]'"):
        identify(tetra, 1)
    code = main(["identify", "tetrahedron", "--twist", "1"])
    assert code == 1


TORUS_2 = {1: "0_1", 2: "L2a1", 3: "3_1", 4: "L4a1", 5: "5_1", 6: "L6a3", 7: "7_1", 8: "L8a14", 9: "9_1"}


@settings(max_examples=15, deadline=None)
@given(st.integers(3, 6).flatmap(lambda n: st.lists(st.integers(-3, 3), min_size=n, max_size=n)))
def test_any_dihedron_labelling_is_the_torus_link_of_its_sum(labels):
    """dihedron:N with labels adding up to s realizes T(2, s), whatever the individual labels."""
    s = sum(labels)
    assume(s != 0 and abs(s) in TORUS_2)
    r = identify(lkspace.load(f"dihedron:{len(labels)}"), np.array(labels)).to_dict()
    assert r["components"] == (2 if s % 2 == 0 else 1)
    assert r["name"] == TORUS_2[abs(s)]
    if abs(s) % 2 and abs(s) > 1:
        assert r["mirror"] is (s < 0)  # positive twists: positive torus knots


@settings(max_examples=6, deadline=None)
@given(st.lists(st.integers(-2, 2), min_size=6, max_size=6), st.integers(0, 10))
def test_diagram_linking_numbers_match_the_gauss_integral(labels, seed):
    from lkspace import realize

    real = realize(lkspace.load("tetrahedron"), np.array(labels))
    lk = project(real.curves, seed=seed).linking_matrix()
    n = real.n_curves
    for a in range(n):
        for b in range(a + 1, n):
            assert lk[a, b] == round(gauss_linking(real.curves[a], real.curves[b]))


def test_composite_knots_are_named_by_their_factors():
    import spherogram

    from lkspace.knots.naming import name_pd, one_based

    trefoil = spherogram.Link("K3a1")
    granny = name_pd(one_based(trefoil.connected_sum(spherogram.Link("K3a1")).PD_code()), 1)
    square = name_pd(one_based(trefoil.connected_sum(trefoil.mirror()).PD_code()), 1)
    assert granny.name == square.name == "3_1#3_1" and granny.prime is False
    assert sorted(map(str, square.factors or ())) == ["3_1", "m3_1"] and len(set(granny.factors or ())) == 1
    mixed = name_pd(one_based(trefoil.connected_sum(spherogram.Link("K4a1")).PD_code()), 1)
    assert mixed.name == "3_1#4_1"
