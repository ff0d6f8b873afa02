"""The design-space walk against brute force, Burnside and the tracer."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import lkspace
from lkspace import Selection, load
from lkspace.catalog.batches import design_batches, residue_batches
from lkspace.design.counting import burnside_total, count_space
from lkspace.design.space import canonical_form, make_space
from lkspace.design.spanning import all_spanning_trees, dual_edges
from lkspace.design.walk import walk_blocks
from lkspace.errors import LabelError, TooLargeError

from .brute_orbits import brute_orbits
from .test_symmetry import cubic_honeycomb, square_tiling


def walked(space, **kw):
    """All rows of the walk as one DataFrame."""
    import pandas as pd

    frames = [b.to_pandas() for b in design_batches(space, **kw)]
    return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame()


def test_tetrahedron_pm2_has_12_chainmails():
    """The paper: labels {+2, -2} on the tetrahedron give 12 distinct chainmails up to rotation."""
    space = make_space(load("tetrahedron"), "-2,2", "rotations")
    df = walked(space)
    assert len(df) == 12 == burnside_total(space) == count_space(space).designs
    assert df.orbit_size.sum() == 64
    assert (df.components == 4).all()  # t = +-2 = 0 mod 2: every face its own loop


CASES = [
    ("tetrahedron", "-1..1", "rotations"),
    ("tetrahedron", "-1..1", "isometries"),
    ("tetrahedron", "-1..1", "none"),
    ("tetrahedron", "-2..2", "rotations"),
    ("tetrahedron", "-2,2", "isometries"),
    ("cube", "-1,1", "rotations"),
    ("cube", "-1..1", "rotations"),
    ("cube", "-1..1", "isometries"),
    ("octahedron", "-1,1", "isometries"),
    ("dihedron:3", "-2..2", "isometries"),
    ("dihedron:4", "-1..1", "rotations"),
    ("dihedron:5", "0,1,2", "rotations"),
    ("book:3", "-1..1", "rotations"),
    ("book:3", "-1..1", "isometries"),
    ("book:4", "-1..1", "isometries"),
    ("book:3", "0..3", "rotations"),
]


@pytest.mark.parametrize("name, labels, mode", CASES)
def test_walk_matches_brute_force(name, labels, mode):
    space = make_space(load(name), labels, mode)
    reps, sizes = brute_orbits(space)
    df = walked(space)
    got = np.array(df.labels.tolist(), np.int64).reshape(len(df), -1)
    order = np.lexsort(got.T[::-1])
    want = np.lexsort(reps.T[::-1])
    assert np.array_equal(got[order], reps[want])
    assert np.array_equal(df.orbit_size.to_numpy()[order], sizes[want])
    assert df.orbit_size.sum() == space.assignments
    totals = count_space(space).to_dict()
    assert totals["designs"] == len(df) == burnside_total(space)
    assert totals["by_components"] == {str(k): int(v) for k, v in df.components.value_counts().sort_index().items()}


@pytest.mark.parametrize("sc, labels", [(square_tiling(2), "-1..1"), (cubic_honeycomb(1), "-3..3")])
def test_periodic_matches_brute_force(sc, labels):
    for mode in ("rotations", "isometries") if labels.startswith("-") else ("rotations",):
        space = make_space(sc, labels, mode)
        reps, sizes = brute_orbits(space)
        df = walked(space)
        got = np.array(df.labels.tolist(), np.int64).reshape(len(df), -1)
        assert np.array_equal(got[np.lexsort(got.T[::-1])], reps[np.lexsort(reps.T[::-1])])
        assert len(df) == len(reps) == burnside_total(space)
        assert df.orbit_size.sum() == space.assignments
        assert "strand_periods" in df.columns


@pytest.mark.parametrize("name, labels", [("cube", "-1..1"), ("book:3", "-2..2"), ("dihedron:6", "-1..1")])
def test_rows_agree_with_the_tracer(name, labels, rng):
    space = make_space(load(name), labels, "rotations")
    df = walked(space)
    for i in rng.choice(len(df), size=min(60, len(df)), replace=False):
        row = df.iloc[int(i)]
        t = lkspace.trace(space.scaffold, np.asarray(row.labels, np.int64))
        assert t.components == row.components
        assert sorted(t.strand_lengths.tolist(), reverse=True) == list(row.strand_lengths)
        assert t.holds_together == row.holds_together
        assert row.n_zero == int(np.sum(np.asarray(row.labels) == 0))
        assert bytes(np.asarray(row.labels, np.int8)) == row.key


def test_cube_minus2_to_2_counts():
    space = make_space(load("cube"), "-2..2", "rotations")
    totals = count_space(space).to_dict()
    assert totals["designs"] == 10_194_250 == burnside_total(space)
    assert totals["assignments"] == totals["assignments_covered"] == 244_140_625
    assert sum(totals["by_components"].values()) == 10_194_250


def test_filters_apply_during_the_walk():
    space = make_space(load("cube"), "-1..1", "rotations")
    full = walked(space)
    one = walked(space, components=1)
    assert len(one) == int((full.components == 1).sum()) == count_space(space, 1).designs
    nz = walked(make_space(load("cube"), "-1..1", "rotations", no_zero=True))
    assert len(nz) == int((full.n_zero == 0).sum())
    assert len(walked(space, max_designs=1000)) == 1000


def test_residue_mode_sums():
    space = make_space(load("cube"), "-2..2", "rotations")
    import pandas as pd

    df = pd.concat([b.to_pandas() for b in residue_batches(space)])
    assert df.orbit_size.sum() == space.assignments
    assert df.designs.sum() == 10_194_250
    assert df.classes.sum() == 2**12  # every residue class of the 12 edges (K = 2) once
    for _, row in df.sample(20, random_state=0).iterrows():
        assert lkspace.trace(space.scaffold, np.asarray(row.labels, np.int64)).components == row.components


def test_spanning_trees_give_single_components():
    space = make_space(load("cube"), "-1..1", "rotations")
    _, pairs = dual_edges(space)
    assert len(list(all_spanning_trees(6, pairs))) == 384  # spanning trees of the octahedron
    df = next(lkspace.designs("cube", "-1..1", selection=Selection(mode="spanning-trees")))
    assert (df.components == 1).all() and len(df) > 0
    sampled = Selection(mode="spanning-trees", sample=30, seed=7)
    a = next(lkspace.designs("cube", "-2..2", selection=sampled))
    b = next(lkspace.designs("cube", "-2..2", selection=sampled))
    assert a.residues.map(tuple).tolist() == b.residues.map(tuple).tolist()
    assert set(a.residues.map(tuple)) <= set(df.residues.map(tuple))


def test_api_yields_dataframes_and_arrow():
    frames = list(lkspace.designs("tetrahedron", "-1..1", symmetry="isometries", batch_rows=50))
    assert sum(len(f) for f in frames) == burnside_total(make_space(load("tetrahedron"), "-1..1", "isometries"))
    batch = next(lkspace.designs("tetrahedron", [-2, 2], as_arrow=True))
    assert batch.num_rows == 12


def test_errors():
    with pytest.raises(LabelError, match="closed under negation"):
        make_space(load("cube"), "0..2", "isometries")
    with pytest.raises(LabelError, match="unknown symmetry"):
        make_space(load("cube"), "0..2", "mirror")
    with pytest.raises(LabelError, match="no labels"):
        make_space(load("cube"), "0", "rotations", no_zero=True)


@settings(max_examples=40, deadline=None)
@given(
    st.lists(st.integers(-2, 2), min_size=12, max_size=12),
    st.integers(0, 47),
    st.sampled_from(["rotations", "isometries"]),
)
def test_symmetric_relabelings_share_one_canonical_key(labels, g, mode):
    space = make_space(load("cube"), "-2..2", mode)
    perms, signs = space.action
    g %= len(signs)
    t = np.array(labels)
    image = np.empty_like(t)
    image[perms[g]] = signs[g] * t
    a, size_a = canonical_form(space, t)
    b, size_b = canonical_form(space, image)
    assert np.array_equal(a, b) and size_a == size_b


def test_canonical_form_is_the_catalog_row():
    space = make_space(load("book:3"), "-1..1", "isometries")
    df = walked(space)
    keys = set(df.key)
    rng = np.random.default_rng(3)
    for _ in range(30):
        rep, size = canonical_form(space, rng.integers(-1, 2, space.scaffold.n_edges))
        assert rep.tobytes() in keys
        assert df.set_index("key").loc[rep.tobytes(), "orbit_size"] == size


def test_blocks_are_in_class_order():
    space = make_space(load("tetrahedron"), "-1..1", "rotations")
    codes = [int(c) for b in walk_blocks(space) for c in b.class_codes]
    assert codes == sorted(codes)


def test_count_by_cycle_index_for_a_space_too_big_to_list():
    """Dodecahedron, labels -2..2: Burnside from the rotation group's cycle types on the 30 edges
    (identity; 24 five-fold: 6 five-cycles; 20 three-fold: 10 three-cycles; 15 half-turns: 2 fixed
    edges and 14 two-cycles)."""
    space = make_space(load("dodecahedron"), "-2..2", "rotations")
    expected = (5**30 + 24 * 5**6 + 20 * 5**10 + 15 * 5**16) // 60
    totals = count_space(space).to_dict()
    assert totals["designs"] == expected and totals["by_components"] is None
    with pytest.raises(TooLargeError, match="too many"):
        next(design_batches(space))
