"""``lkspace enumerate --identify``: knot names as catalog columns."""

from __future__ import annotations

import json
import subprocess
import sys

import pandas as pd
import pyarrow.parquet as pq
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lkspace.catalog.reader import read_metadata
from lkspace.cli import main

pytest.importorskip("snappy")


def test_enumerate_identify_dihedron(tmp_path, capsys):
    out = tmp_path / "d3.parquet"
    assert (
        main(
            ["enumerate", "dihedron:3", "--labels", "-1..1", "-o", str(out), "--identify", "--shards", "2"]
            + ["--jobs", "2", "--json"]
        )
        == 0
    )
    payload = json.loads(capsys.readouterr().out)
    assert payload["identified"]["rows"] == 10
    df = pd.read_parquet(out)
    names = {tuple(r.labels): r.knot_name for r in df.itertuples()}
    # a two-sided triangle whose labels add up to s is the torus knot/link T(2, s)
    assert names[(1, 1, 1)] == "3_1" and names[(-1, -1, -1)] == "3_1"
    assert df.set_index(df.labels.map(tuple)).loc[[(1, 1, 1)], "mirror"].item() is False
    assert df.set_index(df.labels.map(tuple)).loc[[(-1, -1, -1)], "mirror"].item() is True
    assert names[(0, 1, 1)] == "L2a1"
    assert names[(0, 0, 1)] == "0_1"
    meta = read_metadata(out)
    assert meta["identified"] is True and meta["label_set"] == [-1, 0, 1] and meta["scaffold"]["name"] == "dihedron:3"
    assert "rows" in meta and meta["group_order"] == 6  # the part's totals and the space survive the rewrite
    for part in sorted(out.glob("part-*.parquet")):  # every part keeps the catalog's metadata
        schema_meta = json.loads(pq.read_schema(part).metadata[b"lkspace"])
        assert schema_meta["identified"] is True and schema_meta["symmetry"] == "rotations"
        assert schema_meta["scaffold"]["content_hash"] == meta["scaffold"]["content_hash"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d3.parquet"]  # built beside, put in place whole
    again = ["enumerate", "dihedron:3", "--labels", "-1..1", "-o", str(out), "--identify", "--shards", "2"]
    assert main([*again, "--resume", "--json"]) == 0  # the checksums cover the identified parts
    assert json.loads(capsys.readouterr().out)["shards_resumed"] == 2
    row = int(df.knot_name.notna().to_numpy().argmax())  # a named row of an identified catalog, back to its name
    assert main(["identify", str(out), "--row", str(row), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["name"] == df.knot_name.iloc[row]


def test_identify_single_file_keeps_metadata(tmp_path, capsys):
    out = tmp_path / "t.parquet"
    assert main(["enumerate", "tetrahedron", "--labels", "-1,1", "-o", str(out), "--identify", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["identified"]["rows"] == 12
    meta = read_metadata(out)
    assert meta["identified"] is True and meta["label_set"] == [-1, 1] and meta["symmetry"] == "rotations"
    assert meta["scaffold"]["name"] == "tetrahedron" and meta["rows"] == 12 and meta["group_order"] == 12


def test_identify_needs_an_output(capsys):
    assert main(["enumerate", "dihedron:3", "--identify"]) == 2
    assert "give -o" in capsys.readouterr().err


def test_identify_status_says_why_a_row_is_unnamed(tmp_path):
    """Every identified row carries a status: ``identified`` for a named row or a split link
    whose pieces are named, else why not (12-crossing links of the tetrahedron's -2,2 designs
    past every table)."""
    statuses = []
    for labels in ("-1..1", "-2,2"):
        out = tmp_path / f"t{labels}.parquet"
        assert main(["enumerate", "tetrahedron", f"--labels={labels}", "-o", str(out), "--identify"]) == 0
        statuses.append(pd.read_parquet(out))
    df = pd.concat(statuses, ignore_index=True)
    named, split = df["knot_name"].notna(), df["split"].fillna(False).astype(bool)
    assert split.any() and (~named & ~split).any()
    assert (df.loc[named | split, "identify_status"] == "identified").all()
    assert df.loc[~named & ~split, "identify_status"].str.startswith("unknown: not in the tables").all()


def test_identify_columns_are_built_as_pyarrow_builds_them():
    import pyarrow as pa

    from lkspace.catalog.columns import value_column

    cases = [
        (["3_1", None, "L2a1#L2a1", "", "é"], pa.string()),
        ([None, None], pa.string()),
        ([True, None, False], pa.bool_()),
        ([3, None, -7, 0], pa.int32()),
        ([], pa.int32()),
    ]
    for values, type_ in cases:
        assert value_column(values, type_).equals(pa.array(values, type=type_))


def test_enumerate_identify_imports_neither_pandas_nor_scipys_spatial_tools(tmp_path):
    out = tmp_path / "c.parquet"
    code = (
        "import sys; from lkspace.cli import main;"
        f"sys.argv = ['lkspace', 'enumerate', 'dihedron:4', '--labels', '-1..1', '--identify', '-o', {str(out)!r}];"
        "import atexit; atexit.register(lambda: print('LOADED', sorted(m for m in ('pandas', 'scipy.spatial', 'scipy.sparse')"
        " if m in sys.modules), file=sys.stderr)); main()"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "LOADED []" in run.stderr
    assert pq.read_table(out).column("knot_name").null_count < pq.read_table(out).num_rows


@settings(max_examples=60, deadline=None)
@given(
    rows=st.lists(st.lists(st.integers(-128, 127), min_size=5, max_size=5), max_size=12),
    cuts=st.lists(st.integers(0, 12), max_size=3),
    bits=st.sampled_from([8, 16, 64]),
    large=st.booleans(),
    start=st.integers(0, 3),
)
def test_label_rows_read_the_arrow_buffers_as_the_lists_hold_them(rows, cuts, bits, large, start):
    """Chunks, slices, widths and large lists: the matrix from the raw buffers equals the lists' own values."""
    import numpy as np
    import pyarrow as pa

    from lkspace.catalog.arrow_values import label_rows
    from lkspace.errors import CatalogError

    item = pa.int8() if bits == 8 else pa.int16() if bits == 16 else pa.int64()
    kind = pa.large_list(item) if large else pa.list_(item)
    whole = pa.array(rows, kind).slice(min(start, len(rows)))
    bounds = sorted({0, len(whole), *(min(c, len(whole)) for c in cuts)})
    column = pa.chunked_array([whole.slice(a, b - a) for a, b in zip(bounds[:-1], bounds[1:])], kind)
    expected = np.array(whole.to_pylist(), np.int64).reshape(-1, 5)
    assert np.array_equal(label_rows(column, 5), expected)
    if len(whole):
        assert np.array_equal(label_rows(column), expected)  # the width of the first list
        with pytest.raises(CatalogError, match="lists of 4 labels"):
            label_rows(column, 4)
        ragged = pa.chunked_array([pa.array([*rows[:1], rows[0][:4]], kind)])
        with pytest.raises(CatalogError, match="lists of 5 labels"):
            label_rows(ragged, 5)
        with pytest.raises(CatalogError, match="without nulls"):
            label_rows(pa.chunked_array([pa.array([rows[0], None], kind)]), 5)
