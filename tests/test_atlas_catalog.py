"""``atlas CATALOG`` streams the catalog: the same atlas as summing every row at once, whatever the batch size.

The reference reads the whole catalog with pandas and walks its rows one by one in
Python, the way the atlas is defined: a row's type is its ``knot_name`` or, unnamed,
``split`` / ``not in the tables`` / ``unknown (N components)``; a type's simplest design
and its examples (up to five per chirality) are the smallest by (sum |t|, non-zero
labels, largest |t|), the earlier row first among equals.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from lkspace.catalog.reader import catalog_batches, read_catalog
from lkspace.catalog.verify import open_catalog
from lkspace.cli import main
from lkspace.knots.key_names import NOT_IN_TABLES
from lkspace.linktypes.atlas import TypeEntry, sort_types
from lkspace.linktypes.atlas_catalog import atlas_of_catalog
from lkspace.linktypes.examples import EXAMPLES
from lkspace.linktypes.records import AtlasResult, DesignRecord
from tests.cli_calls import run


def known(value):
    """``value`` as Python, ``None`` for a missing one (pandas reads a null as ``None``, ``NaN`` or ``NA``)."""
    return None if value is None or pd.isna(value) else value.item() if hasattr(value, "item") else value


def reference_atlas(path) -> dict:
    """The atlas of the catalog at ``path``, row by row (``AtlasResult.to_json``)."""
    frame = pd.read_parquet(path)
    footer = open_catalog(path).footer
    types: dict[str, TypeEntry] = {}
    offered: dict[tuple[str, str], list] = {}
    for row, design in enumerate(frame.itertuples(index=False)):
        name, split, mirror = (known(getattr(design, c, None)) for c in ("knot_name", "split", "mirror"))
        if name is None:
            status = known(getattr(design, "identify_status", None)) or ""
            group = "not in the tables" if status.startswith(NOT_IN_TABLES.status) else "unknown"
            name = f"{'split' if split else group} ({design.components} components)"
        entry = types.setdefault(name, TypeEntry(name, int(design.components)))
        entry.designs += 1
        entry.assignments += int(design.orbit_size)
        crossings = known(design.crossings)
        if crossings is not None:
            entry.crossings = crossings if entry.crossings is None else min(entry.crossings, crossings)
        side = "undetermined" if mirror is None else "mirror" if mirror else "table"
        entry.chirality[side] += 1
        labels = np.asarray(design.labels, np.int64)
        a = np.abs(labels)
        cost = (int(a.sum()), int((a != 0).sum()), int(a.max()))
        if cost < entry.cost:
            entry.cost, entry.simplest = cost, labels.tolist()
        offered.setdefault((name, side), []).append((cost, row, labels, crossings, mirror))
    for (name, _), designs in offered.items():
        entry = types[name]
        for cost, _, labels, crossings, mirror in sorted(designs, key=lambda d: d[:2])[:EXAMPLES]:
            entry.examples.add(labels, cost, DesignRecord(name, entry.components, None, mirror, crossings))
    listed = tuple(t.record() for t in sort_types(types))
    return AtlasResult(
        "",
        footer.settings.label_set,
        len(frame),
        sum(t.assignments for t in listed),
        listed,
    ).to_json()


SPACES = {
    "tetrahedron.parquet": ["tetrahedron", "--labels", "-2..2", "--identify"],
    "tetrahedron-parts": ["tetrahedron", "--labels", "-2..2", "--identify", "--jobs", "2", "--shards", "3"],
    "octahedron-by-key": ["octahedron", "--labels", "-1..1", "--identify-by-key", "--shards", "2"],
    "cube-by-key.parquet": ["cube", "--labels", "-2..2", "--max-designs", "300", "--identify-by-key"],
}
"""Catalogs the command line writes: one file, a sharded folder, two named by key only (the cube's are no table type)."""


@pytest.fixture(scope="module")
def catalogs(tmp_path_factory):
    """``{name: path}`` of :data:`SPACES`, written by ``lkspace enumerate``."""
    folder = tmp_path_factory.mktemp("atlas-catalogs")
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("LKSPACE_CACHE", str(folder / "cache"))
        for out, args in SPACES.items():
            assert main(["enumerate", *args, "-o", str(folder / out)]) == 0
    return {name: folder / name for name in SPACES}


@pytest.fixture(scope="module")
def references(catalogs):
    """``{name: the reference atlas}`` of each catalog."""
    return {name: reference_atlas(path) for name, path in catalogs.items()}


@pytest.mark.parametrize(
    ("name", "batch_rows"),
    [
        ("tetrahedron.parquet", 1),
        ("tetrahedron.parquet", 7),
        ("tetrahedron.parquet", 100_000),
        ("tetrahedron-parts", 7),  # batches across parts
        ("tetrahedron-parts", 100_000),
        ("octahedron-by-key", 1000),
        ("octahedron-by-key", 100_000),
        ("cube-by-key.parquet", 7),
    ],
)
def test_streamed_atlas_is_the_row_by_row_one(catalogs, references, name, batch_rows):
    got = atlas_of_catalog(str(catalogs[name]), batch_rows).to_json()
    assert got["scaffold"] == SPACES[name][0]
    del got["scaffold"], got["from_catalog"]
    want = dict(references[name])
    del want["scaffold"]
    assert got == want


def test_the_spaces_hold_what_the_comparison_needs(catalogs, references):
    """Ties at the last example kept, every chirality, every group of unnamed rows: else it proves little."""
    frame = pd.read_parquet(catalogs["tetrahedron.parquet"])
    a = np.abs(np.stack(frame["labels"].to_numpy()))
    frame["cost"] = list(zip(a.sum(axis=1), (a != 0).sum(axis=1), a.max(axis=1), strict=True))
    tied = 0
    for _, group in frame.groupby([frame["knot_name"].fillna("-"), frame["mirror"].astype(str)]):
        costs = sorted(group["cost"])
        tied += len(costs) > EXAMPLES and costs[EXAMPLES - 1] == costs[EXAMPLES]
    assert tied > 10
    keyed = references["octahedron-by-key"]["types"]
    assert {side for t in keyed for side, n in t["chirality"].items() if n} == {"table", "mirror", "undetermined"}
    keyed += references["cube-by-key.parquet"]["types"]
    groups = {t["name"].split(" (")[0] for t in keyed if " (" in t["name"]}
    assert groups == {"split", "not in the tables", "unknown"}


def test_atlas_command_prints_the_streamed_atlas(catalogs, capsys):
    path = catalogs["tetrahedron-parts"]
    code, out, err = run(capsys, "atlas", path, "--json")
    assert code == 0, err
    printed = json.loads(out)
    del printed["written"]
    assert printed == atlas_of_catalog(str(path)).to_json()


def test_batches_are_the_catalogs_rows_a_few_at_a_time(catalogs):
    path = catalogs["tetrahedron-parts"]
    whole = read_catalog(path)
    batches = list(catalog_batches(open_catalog(path), ["components", "knot_name"], 100))
    assert max(len(labels) for _, labels in batches) == 100
    assert np.array_equal(np.concatenate([labels for _, labels in batches]), whole.labels)
    names = [n for batch, _ in batches for n in batch.column("knot_name").to_pylist()]
    assert names == [known(n) for n in whole.frame["knot_name"]]
