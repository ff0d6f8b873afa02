"""The batched walk (many residue classes per compiled call) against independent paths.

* every row's strands and holding together against :func:`lkspace.trace` (tracing.py and
  holding_together.py: the per-assignment code, no batch kernels);
* batched classes against one class per call (the per-class kernel);
* ``--mode residues`` rows against :func:`~lkspace.design.walk.residue_row` (per class);
* counts (batched Burnside, and the census) against brute-force orbits.
"""

from __future__ import annotations

import numpy as np
import pyarrow as pa
import pytest

import lkspace.design.batch as batch
import lkspace.design.walk as walk_mod
from lkspace import load, trace
from lkspace.catalog.batches import space_batches
from lkspace.design.census import census
from lkspace.design.counting import count_space
from lkspace.design.space import make_space
from lkspace.design.walk import residue_row
from tests.brute_orbits import brute_orbits

SPACES = [
    ("honeycomb:oF", "-1..1", "rotations", False),  # tiny classes, periodic (3D lift)
    ("honeycomb:cF", "-2..2", "isometries", False),  # reflections, periodic
    ("voronoi:cube-faces", "-1..1", "rotations", False),  # edges of degree 3 and 4
    ("tiling:square@2x2", "-2..2", "rotations", False),  # 2D lift
    ("cube", "-2..2", "rotations", True),  # large classes
    ("whitehead", "-2..2", "isometries", False),  # degree-1 edges
    ("cubes:piano", "0,2", "rotations", False),  # degree 4 and 2
]


def table(space, mode="designs", components=None):
    return pa.Table.from_batches(list(space_batches(space, mode, None, components, None, None, 0)))


@pytest.fixture(scope="module")
def tiny_classes():
    """``honeycomb:oF`` with -1..1: 134,136 designs, one assignment per residue class."""
    space = make_space(load("honeycomb:oF"), "-1..1")
    return space, table(space)


@pytest.mark.parametrize("args", SPACES, ids=lambda a: f"{a[0]} {a[1]} {a[2]}")
def test_rows_agree_with_trace(args, tiny_classes):
    space, full = (
        tiny_classes if args[:2] == ("honeycomb:oF", "-1..1") else (make_space(load(args[0]), *args[1:]), None)
    )
    full = table(space) if full is None else full
    rng = np.random.default_rng(1)
    periodic = space.scaffold.periodic
    for row in full.take(rng.choice(len(full), size=min(150, len(full)), replace=False)).to_pylist():
        tr = trace(space.scaffold, row["labels"])
        lengths = np.diff(tr.strand_starts)
        order = np.argsort(-lengths, kind="stable")
        assert row["components"] == tr.components
        assert row["strand_lengths"] == lengths[order].tolist()
        assert row["holds_together"] == tr.holds_together, row["labels"]
        if periodic:
            assert row["strand_periods"] == tr.periods[order].tolist()
            assert row["n_infinite"] == int(np.any(tr.periods != 0, axis=1).sum())


PER_CLASS = [  # small enough for the per-class references
    ("honeycomb:oF", "0,1", "rotations", False),
    ("honeycomb:cF", "-2..2", "isometries", False),
    ("voronoi:cube-faces", "0,1", "rotations", False),
    ("tiling:square@2x2", "-2..2", "rotations", False),
    ("cube", "-1..1", "rotations", False),
    ("whitehead", "-2..2", "isometries", False),
    ("cubes:piano", "0,2", "rotations", False),
]


@pytest.mark.parametrize("args", PER_CLASS[:5], ids=lambda a: f"{a[0]} {a[1]}")
def test_batched_classes_equal_one_class_per_call(args, monkeypatch):
    space = make_space(load(args[0]), *args[1:])
    batched = table(space)
    monkeypatch.setattr(batch, "BATCH_ASSIGNMENTS", 1)  # every class alone, through the per-class kernel
    monkeypatch.setattr(walk_mod, "BATCH_ASSIGNMENTS", 1)
    monkeypatch.setattr(walk_mod, "CHUNK", 100)  # and large classes in chunks
    single = table(make_space(load(args[0]), *args[1:]))
    assert batched.equals(single)


@pytest.mark.parametrize("args", PER_CLASS, ids=lambda a: f"{a[0]} {a[1]} {a[2]}")
def test_residue_rows_equal_per_class_rows(args):
    space = make_space(load(args[0]), *args[1:])
    got = table(space, "residues").to_pylist()
    co = space.classes
    want = [residue_row(space, co.indices[c], co.stabilizers[c]) for c in range(len(co.codes))]
    assert len(got) == len(want)
    for g, w in zip(got, want, strict=True):
        assert g == {k: w[k] for k in g}


def test_component_filter_and_max_designs(tiny_classes):
    space, full = tiny_classes
    full = full.select(["key", "components"]).to_pandas()
    two = table(space, components=2).to_pandas()
    assert len(two) == int((full.components == 2).sum())
    assert list(two.key) == list(full.key[full.components == 2])
    head = pa.Table.from_batches(list(space_batches(space, "designs", None, None, 1000, None, 0)))
    assert head.column("key").to_pylist() == list(full.key[:1000])


@pytest.mark.parametrize(
    "args",
    [
        ("tetrahedron", "-3..3", "isometries", False),
        ("cube", "-1..1", "rotations", True),
        ("honeycomb:cF", "-1..2", "rotations", False),
        ("honeycomb:cF", "-1..1", "isometries", False),
        ("whitehead", "-1..1", "isometries", False),
    ],
)
def test_counts_against_brute_force(args):
    space = make_space(load(args[0]), *args[1:])
    reps, sizes = brute_orbits(space)
    comps = np.array([trace(space.scaffold, r).components for r in reps])
    want = {int(c): int(n) for c, n in zip(*np.unique(comps, return_counts=True), strict=True)}
    assert count_space(space).by_components == want
    found = census(space, shard_choices=997)  # many shards, unequal
    assert found.by_components == want
    assert sum(found.assignments_by_components.values()) == len(space.walk_labels) ** space.scaffold.n_edges
    assert sum(sizes) == len(space.walk_labels) ** space.scaffold.n_edges


def test_census_beyond_class_limit(monkeypatch):
    """Past MAX_CLASSES the count splits by components through the census; equal to the class walk."""
    space = make_space(load("honeycomb:oF"), "-1..1")
    want = count_space(space)
    import lkspace.design.counting as counting

    monkeypatch.setattr(counting, "MAX_CLASSES", 10)
    got = count_space(make_space(load("honeycomb:oF"), "-1..1"))
    assert got.by_components == want.by_components and got.assignments_covered == want.assignments_covered
    two = count_space(make_space(load("honeycomb:oF"), "-1..1"), components=2)
    assert two.by_components == {2: want.by_components[2]}
    assert two.assignments_covered == count_space(space, components=2).assignments_covered


@pytest.mark.parametrize("scaffold, labels", [("cube", "-1..1"), ("book:3", "-2..2")])
def test_census_counts_the_same_in_short_compiled_calls(monkeypatch, scaffold, labels):
    """A shard walked in many short kernel calls (so that Ctrl-C is seen between them) counts what one call counts."""
    import lkspace.design.census as census_mod

    space = make_space(load(scaffold), labels)
    items = [(g, 0, t.size) for g, t in enumerate(census_mod.terms(space))]
    one_call = [census_mod.shard_term((space, census_mod.terms(space)), item) for item in items]
    ports = space.scaffold.n_corners * 2
    monkeypatch.setattr(census_mod, "CALL_PORT_VISITS", 7 * ports)  # 7 (or so) choices per call: calls end mid-digit
    short_calls = [census_mod.shard_term((space, census_mod.terms(space)), item) for item in items]
    assert all(np.array_equal(a, b) for a, b in zip(one_call, short_calls, strict=True))
    assert sum(int(h.sum()) for h in short_calls) == sum(
        t.size for t in census_mod.terms(space) if 0 not in t.n_choices
    )
