"""Designer tolerances: rounded meshes keep their symmetry, distorted ones do not, and near misses are said.

The book of three pages (``book:3``) written by hand with 3-decimal coordinates is the
user's case: 6 rotations and 10,233 designs with labels -1..1 (Burnside by hand:
``(3^10 + 2 * 3^4 + 3 * 3^6) / 6``), checked against :mod:`tests.brute_symmetry`.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lkspace import Scaffold, count_designs, load
from lkspace.design.space import make_space
from lkspace.errors import LkspaceWarning, UsageError
from lkspace.inverse.pipeline import symmetry_actions
from lkspace.symmetry.group import symmetry_group
from lkspace.symmetry.nearby import example_motion, near_symmetry
from lkspace.symmetry.slots import RadialCheck
from lkspace.symmetry.tolerance import default_tolerance, shortest_edge
from tests.brute_symmetry import brute_motions, burnside_designs
from tests.cli_calls import one_line_error, run

S = 0.866  # sqrt(3)/2 as a modelling tool writes it
BOOK = [[0, 0, 0], [0, 0, 1], [1, 0, 0], [1, 0, 1], [-0.5, S, 0], [-0.5, S, 1], [-0.5, -S, 0], [-0.5, -S, 1]]
PAGES = [[0, 2, 3, 1], [0, 4, 5, 1], [0, 6, 7, 1]]


def write_obj(path, vertices, faces):
    lines = [f"v {x:.3f} {y:.3f} {z:.3f}" for x, y, z in vertices]
    lines += ["f " + " ".join(str(v + 1) for v in f) for f in faces]
    path.write_text("\n".join(lines) + "\n")
    return path


def book_at(degrees):
    """Pages at these angles (degrees) about the z axis, unit squares, coordinates rounded to 3 decimals."""
    vertices = [[0, 0, 0], [0, 0, 1]]
    for a in np.radians(degrees):
        vertices += [[np.cos(a), np.sin(a), 0], [np.cos(a), np.sin(a), 1]]
    faces = [[0, 2 + 2 * i, 3 + 2 * i, 1] for i in range(len(degrees))]
    return np.round(np.array(vertices, float), 3), faces


def test_rounded_book_by_the_cli(tmp_path, capsys):
    obj = write_obj(tmp_path / "book.obj", BOOK, PAGES)
    code, out, err = run(capsys, "info", obj, "--json")
    info = json.loads(out)
    assert code == 0 and info["symmetry_group_order"] == {"rotations": 6, "isometries": 12}
    assert info["group"] == "6 rotations, 12 isometries"
    assert info["symmetry_tolerance"] == pytest.approx(0.01 * np.hypot(0.5, S))  # 1/100 of the shortest edge
    assert info["symmetry_note"] is None and err == ""
    code, out, err = run(capsys, "enumerate", obj, "--labels", "-1..1", "--json")
    assert code == 0 and json.loads(out)["designs"] == 10_233 == (3**10 + 2 * 3**4 + 3 * 3**6) // 6


def test_rounded_book_agrees_with_brute_force():
    vertices = np.array(BOOK, float)
    tol = 0.01 * np.hypot(0.5, S)
    motions = brute_motions(vertices, PAGES, tol)
    assert sum(p for _, p in motions) == 6 and len(motions) == 12
    assert burnside_designs(vertices, PAGES, motions, 3) == 10_233
    exact = brute_motions(vertices, PAGES, 1e-6)  # the old, exact tolerance: 2 rotations, 29,889 designs
    assert sum(p for _, p in exact) == 2 and burnside_designs(vertices, PAGES, exact, 3) == 29_889
    sc = Scaffold.from_faces(vertices, PAGES, name="book")
    assert make_space(sc, "-1..1").group_order == 6
    assert make_space(sc, "-1..1", tolerance=1e-6).group_order == 2
    assert make_space(sc, "-1..1", tolerance=1e-6).action[0].shape[0] == 2


def test_tight_tolerance_says_what_was_missed(tmp_path, capsys):
    obj = write_obj(tmp_path / "book.obj", BOOK, PAGES)
    code, out, err = run(capsys, "enumerate", obj, "--labels", "-1..1", "--tolerance", "1e-6", "--json")
    payload = json.loads(out)
    assert code == 0 and payload["designs"] == 29_889 and payload["group"] == "2 rotations, 4 isometries"
    assert err.count("\n") == 1 and err.startswith("lkspace: note: book.obj has 6 rotations (12 isometries) if ")
    assert "a 1/3 turn about the axis (0.00, 0.00, 1.00) through the centroid misses by 2.5e-05" in err
    assert "pass --tolerance 3e-05" in err
    assert payload["symmetry_note"] == err.removeprefix("lkspace: note: ").strip()
    code, out, _ = run(capsys, "info", obj, "--tolerance", "3e-05", "--json")
    assert code == 0 and json.loads(out)["symmetry_group_order"]["rotations"] == 6  # the advice works


def test_distorted_book_stays_asymmetric(tmp_path, capsys):
    vertices, faces = book_at([0, 110, 240])  # 10 degrees off: a different shape
    obj = write_obj(tmp_path / "bent.obj", vertices, faces)
    code, out, err = run(capsys, "info", obj, "--json")
    info = json.loads(out)
    assert code == 0 and info["symmetry_group_order"] == {"rotations": 1, "isometries": 2}  # the mirror z = 1/2
    assert info["symmetry_note"] is None and err == ""
    motions = brute_motions(vertices, faces, info["symmetry_tolerance"])
    assert len(motions) == 2 and [m for m in motions if m[1]] == [(tuple(range(8)), True)]


def test_irregular_tetrahedron_is_told_how_to_fix_it(capsys):
    tet = load("tetrahedron")
    v = tet.vertices.copy()
    v[0] *= 1.03  # a hand-made tetrahedron, one vertex 3% too far out
    sc = Scaffold.from_faces(v, tet.faces(), name="tet")
    group = symmetry_group(sc)
    assert (group.n_rotations, group.order) == (3, 6)
    near = near_symmetry(sc)
    assert near is not None and (near.rotations, near.isometries) == (12, 24)
    assert near.tolerance < near.miss < near.suggested
    message = near.message("tet", group.n_rotations, group.order)
    assert message.startswith(f"tet has 12 rotations (24 isometries) if points {near.suggested:g} apart count as one")
    # twenty-one motions miss by the same amount up to the last bits: the example is chosen by rule, not by noise
    assert "but only 3 (6) within the tolerance 0.028: e.g. a 1/3 turn about the axis (-0.58, -0.58, 0.58)" in message
    assert (
        f"pass `tolerance={near.suggested:g}`" in message and "correct the coordinates" in message
    )  # a flag on the CLI
    assert symmetry_group(sc, near.suggested).n_rotations == 12
    brute = brute_motions(v, tet.faces(), near.suggested)
    assert sum(p for _, p in brute) == 12 and len(brute) == 24


def test_tolerance_bad_values_are_usage_errors(tmp_path, capsys):
    for value in ("0", "-1", "nan", "inf", "x"):
        code, out, err = run(capsys, "info", "cube", "--tolerance", value)
        assert code == 2 and out == ""
        one_line_error(err, "--tolerance")
    code, _, err = run(capsys, "info", "cube", "--tolerance", "1")  # the cube's edges are 2 long
    assert code == 2
    one_line_error(err, "--tolerance 1", "shortest edge is 2 long", "below half of it (1)")
    with pytest.raises(UsageError, match="shortest edge"):
        symmetry_group(load("cube"), tolerance=5.0)


def test_tolerance_is_a_parameter_not_state():
    sc = Scaffold.from_faces(np.array(BOOK, float), PAGES, name="book")
    assert symmetry_group(sc, 1e-6).n_rotations == 2
    assert symmetry_group(sc).n_rotations == 6  # the default is not changed by the call before
    assert symmetry_group(sc, 1e-6).n_rotations == 2
    assert default_tolerance(sc) == pytest.approx(0.01 * shortest_edge(sc))
    assert count_designs(sc, "-1..1", tolerance=1e-6).designs == 29_889
    assert count_designs(sc, "-1..1").designs == 10_233
    labels = np.arange(-1, 2)
    assert len(symmetry_actions(sc, "rotations", labels, 1e-6)) == 1  # solve --distinct-up-to: non-identity actions
    assert len(symmetry_actions(sc, "rotations", labels)) == 5


def test_catalog_records_its_tolerance(tmp_path, capsys):
    from lkspace.catalog.reader import read_metadata

    obj = write_obj(tmp_path / "book.obj", BOOK, PAGES)
    cat = tmp_path / "b.parquet"
    code, _, _ = run(capsys, "enumerate", obj, "--labels", "-1..1", "--tolerance", "0.002", "-o", cat)
    assert code == 0
    meta = read_metadata(str(cat))
    assert meta["symmetry_tolerance"] == 0.002 and meta["group_order"] == 6 and meta["rows"] == 10_233


@pytest.mark.parametrize("name", ["book:3", "book:5", "cubes:piano", "cube"])
def test_radial_orders_are_kept_exactly(name):
    """Every symmetry keeps the cyclic order of the sides around its edges; a wrong handedness does not."""
    from lkspace.symmetry.finite import segment_hashes

    sc = load(name)
    check = RadialCheck(sc, segment_hashes(sc.side_edge, sc.face_starts))
    group = symmetry_group(sc)
    wide = sc.edge_degrees >= 3
    for sigma, perm, proper in zip(group.vertex_perms, group.edge_perms, group.proper, strict=True):
        hashes = segment_hashes(perm[sc.side_edge], sc.face_starts)
        assert check.keeps(sigma, perm, hashes, bool(proper))
        if wide.any():  # K >= 3: the other handedness turns the sides the wrong way round
            assert not check.keeps(sigma, perm, hashes, not bool(proper))


SOLIDS = ["tetrahedron", "cube", "octahedron", "book:3"]


@settings(max_examples=20, deadline=None)
@given(name=st.sampled_from(SOLIDS), seed=st.integers(0, 2**32 - 1), size=st.floats(0.0, 0.3))
def test_small_perturbations_keep_the_group(name, seed, size):
    """Moving every vertex by under 0.3 tolerance keeps the whole group (the fit's misses stay under 1)."""
    sc = load(name)
    tol = default_tolerance(sc)
    rng = np.random.default_rng(seed)
    step = rng.normal(size=sc.vertices.shape)
    step *= size * tol * rng.uniform(size=(len(step), 1)) / np.linalg.norm(step, axis=1, keepdims=True)
    moved = Scaffold.from_faces(sc.vertices + step, sc.faces(), name="moved")
    assert symmetry_group(moved, tol).order == symmetry_group(sc).order


@settings(max_examples=20, deadline=None)
@given(name=st.sampled_from(SOLIDS), seed=st.integers(0, 2**32 - 1), size=st.floats(10.0, 20.0))
def test_large_perturbations_lose_the_group(name, seed, size):
    """Moving every vertex by 10 to 20 tolerances in random directions breaks the group.

    What is left is exactly what fits within the tolerance: random steps can, by chance, keep
    a half turn (hypothesis found one), so the brute force says which motions survive.
    """
    sc = load(name)
    tol = default_tolerance(sc)
    rng = np.random.default_rng(seed)
    step = rng.normal(size=sc.vertices.shape)
    step *= size * tol / np.linalg.norm(step, axis=1, keepdims=True)
    moved = Scaffold.from_faces(sc.vertices + step, sc.faces(), name="moved")
    order = symmetry_group(moved, tol).order
    assert order < symmetry_group(sc).order
    if sc.n_vertices <= 6:
        assert order == len(brute_motions(moved.vertices, sc.faces(), tol))


def without_tolerance(file):
    """Rewrite the catalog file as one written before ``symmetry_tolerance`` (and the footer digest) was recorded."""
    import pyarrow.parquet as pq

    from lkspace.catalog.schema import METADATA_KEY

    meta = json.loads(pq.read_metadata(file).metadata[METADATA_KEY])  # a part alone: no reader takes it
    del meta["symmetry_tolerance"]
    meta.pop("digest", None)  # older still than the tolerance: no digest either
    table = pq.read_table(file)
    pq.write_table(table.replace_schema_metadata({METADATA_KEY: json.dumps(meta).encode()}), file)


@pytest.mark.filterwarnings("ignore:.*has no digest:lkspace.errors.LkspaceWarning")  # said once below
def test_catalogs_from_before_the_tolerance_still_read_and_resume(tmp_path, capsys):
    from lkspace import Execution, write_catalog
    from lkspace.catalog.reader import read_catalog, read_metadata
    from lkspace.catalog.transaction import MANIFEST, file_sha256

    space = make_space(load("tetrahedron"), "-1..1")
    one = tmp_path / "t.parquet"
    first = write_catalog(space, one)
    without_tolerance(one)
    with pytest.warns(LkspaceWarning, match="has no digest"):  # read, with a warning (verify refuses it)
        assert "symmetry_tolerance" not in read_metadata(one)
    assert len(read_catalog(one).labels) == first.designs == 87
    code, _, err = run(capsys, "export", one, "--row", 5, "-o", tmp_path / "row5.obj")
    assert code == 0 and (tmp_path / "row5.obj").exists(), err
    assert (
        write_catalog(space, one, execution=Execution(resume=True)).shards_resumed == 1
    )  # the old file is kept as it is
    # a sharded build from before: every part and the manifest without the key, part 1 lost
    write_catalog(space, tmp_path / "c", execution=Execution(shards=3))
    build = tmp_path / ".c.lkspace-build"
    (tmp_path / "c").rename(build)
    manifest = json.loads((build / MANIFEST).read_text())  # as an earlier version wrote it
    manifest.pop("complete")
    del manifest["symmetry_tolerance"]
    for entry in manifest["parts"].values():
        without_tolerance(build / entry["file"])
        entry["sha256"] = file_sha256(str(build / entry["file"]))
    (build / manifest["parts"].pop("1")["file"]).unlink()
    (build / MANIFEST).write_text(json.dumps(manifest, indent=1))
    again = write_catalog(space, tmp_path / "c", execution=Execution(shards=3, resume=True))
    assert again.shards_resumed == 2 and again.designs == 87
    assert len(read_catalog(tmp_path / "c").labels) == 87


def test_near_symmetry_example_ignores_float_noise_and_order():
    """Ties in the miss (equal but for the last bits, which vary by machine) never decide the example."""
    rng = np.random.default_rng(7)
    eye, turn, half = np.eye(3), np.array([[0.0, 0, 1], [1, 0, 0], [0, 1, 0]]), np.diag([1.0, -1, -1])
    misses = [
        (0.0367 + 3e-16, False, 4, [1, 0, 3, 2], half),  # a half turn moves all four vertices
        (0.0367, True, 2, [1, 0, 2, 3], -eye),  # a reflection is never the example while a rotation ties
        (0.0367 + 1e-16, False, 3, [1, 2, 0, 3], turn),  # fewest vertices moved, then smallest permutation
        (0.0367 - 2e-16, False, 3, [2, 0, 1, 3], turn.T),
        (0.05, False, 3, [0, 2, 3, 1], eye),  # a clearly worse fit
    ]
    for _ in range(20):
        order = rng.permutation(len(misses))
        miss, fit = example_motion([misses[i] for i in order], 1e-9)
        assert miss == 0.0367 - 2e-16
        assert fit is turn
