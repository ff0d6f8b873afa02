"""``lkspace enumerate --identify``: knot names as catalog columns."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from lkspace.catalog.reader import read_metadata
from lkspace.cli import main

pytest.importorskip("snappy")


def test_enumerate_identify_dihedron(tmp_path, capsys):
    out = tmp_path / "d3.parquet"
    assert (
        main(["enumerate", "dihedron:3", "--labels", "-1..1", "-o", str(out), "--identify", "--jobs", "2", "--json"])
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
    assert read_metadata(out)["identified"] is True


def test_identify_needs_an_output(capsys):
    assert main(["enumerate", "dihedron:3", "--identify"]) == 2
    assert "give -o" in capsys.readouterr().err
