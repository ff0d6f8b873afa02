"""``lkspace enumerate --identify``: knot names as catalog columns."""

from __future__ import annotations

import json

import pandas as pd
import pyarrow.parquet as pq
import pytest

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
