"""``identify`` from labels (the default) against the geometric path, and its PD code read by spherogram.

The reference for names is ``identify(..., geometric=True)``: the strands realized,
projected and named on their own.  The reference for the PD code is spherogram and SnapPy
reading it, compared with the table's own diagram (KnotInfo, LinkInfo, HTLinkExteriors):
no lkspace code judges it.
"""

from __future__ import annotations

import functools
import json

import numpy as np
import pytest

pytest.importorskip("snappy")
spherogram = pytest.importorskip("spherogram")
pytest.importorskip("regina")
dki = pytest.importorskip("database_knotinfo")

import lkspace  # noqa: E402
from lkspace.cli import main  # noqa: E402
from lkspace.knots import from_labels  # noqa: E402
from lkspace.knots.key_names import KeyCache  # noqa: E402
from lkspace.knots.naming import split_name  # noqa: E402
from lkspace.linktypes.atlas import type_key  # noqa: E402

TREFOIL = [0, 0, 0, 0, 0, -1, 0, -1, -1, -1, -1, -1]
SPLIT = [1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0]
WHITEHEAD = [0, 0, -2, 0, -1, 0, -1, 2]
KNOT_13 = [-1, 0, -1, 2, -2, 2, 1, 2, -2, -1, 1, 0]  # 13n_1915 on the cube
LINK_14 = [-1, -1, 2, 1, -2, -1, -2, 2, 0, -1, 1, 2]  # L14n38135 (HTLinkExteriors) on the cube

FAST = [("dihedron:3", [1, 1, 1]), ("cube", SPLIT), ("whitehead", WHITEHEAD)]
SLOW = [
    ("cube", TREFOIL),
    ("cube", [0] * 12),
    ("cube", [-1] * 12),
    ("cube", KNOT_13),
    ("cube", LINK_14),
    ("cube", [0, 0, -2, -2, -2, -2, -2, 2, -2, 1, 1, -1]),  # L2a1#L8n1, a sum
    ("tetrahedron", [1] * 6),
    ("tetrahedron", [0, -2, -2, 0, 2, 1]),
    ("octahedron", [1, -1, 0, 1, 1, 0, -1, 1, 0, 0, 1, -1]),
    ("book:4", 3),
    ("figure-eight", [-1, -1, -1, -1, 0]),
    ("dodecahedron", [1] * 5 + [0] * 25),
    ("dodecahedron", [1] * 30),  # too wide for the compiled state sum: keyed by regina's Jones polynomial
]


@pytest.fixture
def key_cache(monkeypatch):
    """One in-memory key cache for the test (the user's cache on disk is neither read nor written)."""
    cache = KeyCache()
    monkeypatch.setattr(from_labels, "disk_cache", lambda first=None: cache)
    return cache


def summary(found):
    return found.name, found.mirror, found.components, found.split, found.linking_matrix


def compare_paths(mesh, labels, cache):
    scaffold = lkspace.load(mesh)
    cold = lkspace.identify(scaffold, labels)  # named in full, its key remembered
    named_before = cache.full
    warm = lkspace.identify(scaffold, labels)  # from the key, unless the key is not trusted
    geometric = lkspace.identify(scaffold, labels, geometric=True)
    assert cold.details["method"] == warm.details["method"] == "combinatorial"
    assert geometric.details["method"] == "geometric"
    assert summary(cold) == summary(warm) == summary(geometric), (mesh, labels)
    assert cold.status == warm.status == geometric.status
    return cold, cache.full > named_before


@pytest.mark.parametrize("mesh, labels", FAST)
def test_labels_path_names_as_the_geometric_path(mesh, labels, key_cache):
    compare_paths(mesh, labels, key_cache)


@pytest.mark.slow
@pytest.mark.parametrize("mesh, labels", SLOW)
def test_labels_path_names_as_the_geometric_path_across_scaffolds(mesh, labels, key_cache):
    found, _ = compare_paths(mesh, labels, key_cache)
    if found.name and not found.split and "#" not in found.name:
        assert_spherogram_reads(found)


@functools.cache
def table_codes() -> dict[str, str]:
    """Name -> PD code (JSON text) of every KnotInfo knot and LinkInfo link (its first orientation)."""
    codes = {row["name"]: row["pd_notation"] for row in dki.link_list() if row.get("name") and row.get("pd_notation")}
    for row in dki.link_list(proper_links=True):
        name, pd = (row.get("name") or "").split("{")[0], row.get("pd_notation_vector")
        if name and pd and name not in codes:
            codes[name] = pd.replace("{", "[").replace("}", "]")
    return codes


def table_link(name):
    """The table's own diagram of ``name`` as a spherogram link (KnotInfo, LinkInfo, else HTLinkExteriors)."""
    import snappy

    if name in table_codes():
        return spherogram.Link(json.loads(table_codes()[name]))
    return snappy.HTLinkExteriors[name].link()


def self_writhe(link):
    """Writhe of the crossings of a component with itself (independent of the components' orientations)."""
    return sum(c.sign for c in link.crossings if c.strand_components[0] == c.strand_components[1])


def assert_spherogram_reads(found):
    """spherogram's link of ``pd_code`` is the table's link, or its mirror image when ``mirror`` says so."""
    ours = spherogram.Link(found.details["pd_code"])
    table = table_link(found.name)
    if found.mirror:
        table = table.mirror()
    ours.simplify("global")
    table.simplify("global")
    assert len(ours.link_components) == len(table.link_components) == found.components
    mine, theirs = ours.exterior(), table.exterior()
    if mine.solution_type() == "all tetrahedra positively oriented":
        assert mine.is_isometric_to(theirs)
        cs, cs_table = float(mine.chern_simons()), float(theirs.chern_simons())
        told_apart = min(abs(cs_table % 0.5), abs(cs_table % 0.5 - 0.5), abs(cs_table % 0.5 - 0.25)) > 1e-6
        if found.mirror is not None and told_apart:  # the Chern-Simons invariant changes sign in a mirror
            assert abs((cs - cs_table + 0.25) % 0.5 - 0.25) < 1e-6
    else:  # torus knots and links: minimal diagrams, alternating, whose writhe tells the chirality (Tait)
        assert len(ours.crossings) == len(table.crossings)
        if found.mirror is not None:
            assert self_writhe(ours) == self_writhe(table)


@pytest.mark.parametrize("mesh, labels", [("dihedron:3", [1, 1, 1]), ("dihedron:3", [-1, -1, -1]), ("cube", TREFOIL)])
def test_pd_code_opens_in_spherogram_as_the_trefoil_it_names(mesh, labels, key_cache):
    found = lkspace.identify(mesh, labels)
    assert found.name == "3_1" and found.details["method"] == "combinatorial"
    link = spherogram.Link(found.details["pd_code"])
    link.simplify("global")
    writhe = sum(c.sign for c in link.crossings)
    assert len(link.crossings) == 3 and abs(writhe) == 3
    assert found.mirror is (writhe < 0)  # KnotInfo's 3_1 is the right-handed (positive) trefoil
    assert_spherogram_reads(found)


def test_pd_code_of_the_whitehead_link_reads_back(key_cache):
    for labels in (WHITEHEAD, [-t for t in WHITEHEAD]):
        found = lkspace.identify("whitehead", labels)
        assert found.name == "L5a1"
        assert_spherogram_reads(found)


def test_split_links_and_unlinks_are_named_as_such(capsys, key_cache):
    code = main(["identify", "cube", "--twist", ",".join(map(str, SPLIT)), "--json"])
    data = json.loads(capsys.readouterr().out)
    assert code == 0 and data["status"] == "identified" and data["method"] == "combinatorial"
    assert data["name"] == "split: 0_1 + 0_1 + 3_1" and data["split"] is True
    sizes = []
    for piece in spherogram.Link(data["pd_code"]).split_link_diagram():
        piece.simplify("global")
        sizes.append(len(piece.crossings))
    assert max(sizes) == 3  # the trefoil; the unknots lose their crossings
    code = main(["identify", "cube", "--twist", "0"])
    out = capsys.readouterr().out
    assert code == 0 and "split: 0_1 + 0_1 + 0_1 + 0_1 + 0_1 + 0_1 (unlink of 6 components)" in out
    code = main(["identify", "cube", "--twist", "0", "--json"])
    data = json.loads(capsys.readouterr().out)
    assert data["name"] == "split: " + " + ".join(["0_1"] * 6) and data["common_name"] == "unlink of 6 components"


def test_split_name_is_the_atlas_type():
    pieces = ("3_1", "0_1", "L2a1", "0_1")
    assert split_name(pieces) == type_key({"split": True, "pieces": list(pieces)}) == "split: 0_1 + 0_1 + 3_1 + L2a1"
    assert split_name(("3_1", None)) is None


def test_geometric_path_on_request_and_where_labels_do_not_apply(capsys, key_cache):
    from lkspace.geometry.params import GeometryParams

    assert lkspace.identify("dihedron:3", 1, geometric=True).details["method"] == "geometric"
    shaped = lkspace.identify("dihedron:3", 1, params=GeometryParams(radius=0.3))
    assert shaped.details["method"] == "geometric" and shaped.name == "3_1"
    code = main(["identify", "dihedron:3", "--twist", "1", "--geometric", "--json"])
    data = json.loads(capsys.readouterr().out)
    assert code == 0 and data["method"] == "geometric" and data["name"] == "3_1" and "min_distance" in data
    assert len(data["pd_code"]) == data["projected_crossings"]


def test_one_design_key_equals_the_compiled_key():
    from lkspace.knots.keyed import keys_of

    for mesh in ("cube", "octahedron", "tetrahedron"):
        scaffold = lkspace.load(mesh)
        labels = np.random.default_rng(3).integers(-2, 3, size=(6, scaffold.n_edges))
        compiled = keys_of(scaffold, labels)
        for d, lab in enumerate(labels):
            one = from_labels.design_keys_of(scaffold, lab)
            assert bool(one.keyed[0]) == bool(compiled.keyed[d])
            assert one.keys[0].tolist() == compiled.keys[d].tolist()
            assert one.linking_matrix(0) == compiled.linking_matrix(d)
            if len(one.pd):  # the key of a diagram too wide for the state sum comes from regina's Jones
                keys = np.zeros((1, 2), np.uint64)
                assert from_labels._regina_key(one.pd, one.link_values, int(one.components[0]), keys, None)
                assert keys[0].tolist() == compiled.keys[d].tolist()
    wide = lkspace.load("dodecahedron")
    assert not keys_of(wide, [[1] * 30]).keyed[0] and from_labels.design_keys_of(wide, np.ones(30, np.int64)).keyed[0]


def test_projection_without_scipy_matches_scipy():
    from scipy.spatial.transform import Rotation

    from lkspace.knots.diagram import DRAWS, random_rotation

    for seed in range(6):
        assert np.allclose(random_rotation(seed), Rotation.random(random_state=seed).as_matrix(), atol=1e-14)
    for seed, draw in DRAWS.items():
        assert draw == tuple(np.random.RandomState(seed).normal(size=4).tolist())


def test_a_known_key_is_named_without_the_heavy_libraries():
    import subprocess
    import sys

    code = """
import sys
import numpy as np
import lkspace
from lkspace.knots import from_labels
from lkspace.knots.identification import NameFields
from lkspace.knots.key_names import KeyCache

found = from_labels.design_keys_of(lkspace.load("dihedron:3"), np.array([1, 1, 1]))
cache = KeyCache()
key = (int(found.keys[0, 0]), int(found.keys[0, 1]))
cache.named[key] = NameFields(knot_name="3_1", mirror=False, split=False, crossings=3, table="knotinfo")
from_labels.disk_cache = lambda first=None: cache
r = lkspace.identify("dihedron:3", 1)
heavy = ("snappy", "spherogram", "regina", "database_knotinfo", "numba", "scipy", "pandas")
print(r.name, r.details["method"], [m for m in heavy if m in sys.modules])
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["3_1", "combinatorial", "[]"]
