"""Naming by key only (``enumerate --identify-by-key``): no design named in full, and what each status claims holds.

References: KnotInfo's own Jones polynomials (the ``jones_polynomial`` text of
``database_knotinfo``) against regina's Jones polynomial of each design's diagram, so
neither the shipped key file, the compiled Jones polynomial nor the hashes judge
"not in the tables" (where a table knot shares the Jones polynomial, a naming in full
must not give it); and ``--identify`` (names in full) for the rows both name.
"""

from __future__ import annotations

import json
import os
import re

import numpy as np
import pandas as pd
import pyarrow.parquet as pq
import pytest

from lkspace import identify, load
from lkspace.knots import batch
from lkspace.knots.batch import NamerOptions, identify_batch
from lkspace.knots.key_names import NOT_IN_TABLES, KeyCache
from lkspace.knots.keyed import keys_of
from lkspace.knots.shipped_keys import shipped_keys
from tests.cli_calls import run

regina = pytest.importorskip("regina")
dki = pytest.importorskip("database_knotinfo")
pytest.importorskip("snappy")


def knotinfo_jones(text: str) -> dict[int, int]:
    """KnotInfo's Jones polynomial text (in t: ``t-t^2+ 2*t^3``, ``t^(-2)``) as ``{exponent of x = sqrt(t): coefficient}``."""
    poly: dict[int, int] = {}
    for term in re.split(r"(?<![\^(])(?=[+-])", text.replace(" ", "")):
        if not term:
            continue
        match = re.fullmatch(r"([+-]?)(\d*)\*?(t(?:\^\(?(-?\d+)\)?)?)?", term)
        assert match is not None, (text, term)
        sign, digits, power, exponent = match.groups()
        e = 0 if power is None else int(exponent or 1)
        poly[2 * e] = poly.get(2 * e, 0) + (-1 if sign == "-" else 1) * int(digits or 1)
    return {e: c for e, c in poly.items() if c}


def regina_jones(pd_code: list[list[int]]) -> dict[int, int]:
    """regina's Jones polynomial of a PD code, ``{exponent of x: coefficient}``."""
    poly = regina.Link.fromPD(pd_code).jones()
    return {e: int(str(poly[e])) for e in range(poly.minExp(), poly.maxExp() + 1) if int(str(poly[e]))}


def mirrored(poly: dict[int, int]) -> dict[int, int]:
    return {-e: c for e, c in poly.items()}


def frozen(poly: dict[int, int]) -> frozenset[tuple[int, int]]:
    return frozenset(poly.items())


def table_knots(max_crossings: int) -> dict[str, dict[int, int]]:
    """KnotInfo's knots up to ``max_crossings`` (the unknot too): name -> Jones polynomial."""
    out = {}
    for row in dki.link_list():
        name, crossings = row.get("name"), row.get("crossing_number")
        if name in (None, "Name") or not str(crossings).isdigit() or int(crossings) > max_crossings:
            continue
        out[name] = knotinfo_jones(row["jones_polynomial"]) if name != "0_1" else {0: 1}
    return out


def test_the_jones_text_reader_on_hand_checked_knots():
    assert knotinfo_jones("t+ t^3-t^4") == {2: 1, 6: 1, -0 + 8: -1}  # 3_1: t + t^3 - t^4
    assert knotinfo_jones("t^(-2)-t^(-1)+ 1-t+ t^2") == {-4: 1, -2: -1, 0: 1, 2: -1, 4: 1}  # 4_1


@pytest.fixture(scope="module")
def cube_sample():
    """800 random cube -2..2 designs named by key only, with the shipped keys alone."""
    cube = load("cube")
    labels = np.random.default_rng(11).integers(-2, 3, size=(800, cube.n_edges))
    frame = identify_batch(
        cube, labels, NamerOptions(by_key=True), progress=False, cache=KeyCache(shipped=shipped_keys())
    )
    return cube, labels, frame


def test_by_key_names_no_design_in_full(monkeypatch):
    def refuse(self, items):
        if items:
            raise AssertionError("a design was named in full")
        return iter(())

    monkeypatch.setattr(batch.Namer, "name", refuse)
    cube = load("cube")
    labels = np.random.default_rng(3).integers(-2, 3, size=(300, cube.n_edges))
    frame = identify_batch(cube, labels, NamerOptions(by_key=True), progress=False, cache=KeyCache())
    assert frame["status"].str.startswith(NOT_IN_TABLES.status).sum() > 50
    assert frame["knot_name"].notna().sum() == 0  # an empty cache, no shipped file: no name is trusted
    assert frame["status"].str.endswith("(named by key only)").all()


def test_not_in_the_tables_is_no_knotinfo_knot_and_names_are_knotinfos(cube_sample):
    cube, labels, frame = cube_sample
    knots = table_knots(12)
    by_jones: dict[frozenset[tuple[int, int]], set[str]] = {}
    for name, poly in knots.items():
        for side in (poly, mirrored(poly)):
            by_jones.setdefault(frozen(side), set()).add(name)
    found = keys_of(cube, labels, 0, np.arange(-2, 3))
    checked = {"not in the tables": 0, "named": 0, "named in full": 0}
    for d, row in enumerate(frame.itertuples()):
        if row.components != 1:
            continue
        if row.status == NOT_IN_TABLES.status:
            alike = by_jones.get(frozen(regina_jones(found.diagram(d)[0])), set())
            if alike:  # the second level's HOMFLY-PT polynomial or crossings told them apart: so must a full naming
                assert identify(cube, labels[d]).name not in alike, (labels[d], alike)
                checked["named in full"] += 1
            checked["not in the tables"] += 1
        elif row.knot_name in knots:
            jones = regina_jones(found.diagram(d)[0])
            table = knots[row.knot_name]
            sides = [mirrored(table)] if row.mirror else [table] if row.mirror is False else [table, mirrored(table)]
            assert jones in sides, (labels[d], row.knot_name)
            checked["named"] += 1
    assert checked["not in the tables"] >= 30 and checked["named"] >= 60 and checked["named in full"] >= 1, checked


def test_statuses_of_a_sample_say_what_they_prove(cube_sample):
    _, _, frame = cube_sample
    statuses = frame["status"]
    named = frame["knot_name"].notna()
    assert (statuses[named] == "identified").all()
    assert named.sum() > 100 and statuses.str.startswith(NOT_IN_TABLES.status).sum() > 100
    matched = statuses.str.startswith("unknown: its invariants match ")
    for row in frame[matched].itertuples():  # the candidates are listed, and named in the status
        assert row.status.startswith("unknown: its invariants match ")


def test_cli_by_key_names_as_in_full_where_the_tables_decide(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("LKSPACE_CACHE", str(tmp_path / "cache"))
    by_key, full = tmp_path / "key.parquet", tmp_path / "full.parquet"
    code, out, _ = run(capsys, "enumerate", "cube", "--labels", "-1..1", "--identify-by-key", "-o", by_key, "--json")
    assert code == 0 and json.loads(out)["identified"]["rows"] == 22_815
    assert not os.path.exists(tmp_path / "cache" / "names-by-key")  # nothing named in full was kept
    assert run(capsys, "enumerate", "cube", "--labels", "-1..1", "--identify", "-o", full)[0] == 0
    k, f = pd.read_parquet(by_key), pd.read_parquet(full)
    assert (k["labels"].map(tuple) == f["labels"].map(tuple)).all()
    same = (k["knot_name"] == f["knot_name"]) | (k["knot_name"].isna() & f["knot_name"].isna())
    assert same.sum() >= 22_800
    differ = k[~same]
    assert differ["knot_name"].isna().all() and f.loc[~same, "knot_name"].notna().all()
    assert differ["identify_status"].str.endswith("(named by key only)").all()
    assert json.loads(pq.read_metadata(by_key).metadata[b"lkspace"])["named_by"] == "key"
    assert "named_by" not in json.loads(pq.read_metadata(full).metadata[b"lkspace"])
    code, out, _ = run(capsys, "verify", by_key)
    assert code == 0 and "intact" in out


def test_a_folder_named_by_key_is_not_resumed_in_full_and_its_manifest_must_agree(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("LKSPACE_CACHE", str(tmp_path / "cache"))
    out = tmp_path / "tet.parquet"
    args = ["enumerate", "tetrahedron", "--labels", "-1..1", "-o", out, "--shards", "2"]
    assert run(capsys, *args, "--identify-by-key", "--jobs", "2")[0] == 0  # the parts in two processes
    manifest = out / "_lkspace.json"
    meta = json.loads(manifest.read_text())
    assert meta["named_by"] == "key"
    del meta["named_by"]  # an edited manifest: the parts say by key, the manifest in full
    manifest.write_text(json.dumps(meta))
    code, _, err = run(capsys, "verify", out)
    assert code != 0 and "by key where it says in full" in err and "Traceback" not in err
    assert run(capsys, *args, "--identify", "--resume")[0] == 0  # starts afresh: no part named by key is kept
    for part in sorted(out.glob("part-*.parquet")):
        footer = json.loads(pq.read_metadata(part).metadata[b"lkspace"])
        assert footer["identified"] is True and "named_by" not in footer
    assert run(capsys, "verify", out)[0] == 0


def test_atlas_of_a_catalog_named_by_key_groups_what_is_not_in_the_tables(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("LKSPACE_CACHE", str(tmp_path / "cache"))
    out = tmp_path / "cube.parquet"
    args = ["enumerate", "cube", "--labels", "-2..2", "--max-designs", "300", "--identify-by-key", "-o", out]
    assert run(capsys, *args)[0] == 0
    statuses = pd.read_parquet(out)["identify_status"]
    beyond = int((statuses == NOT_IN_TABLES.status).sum())
    assert beyond > 0
    code, text, _ = run(capsys, "atlas", out, "--json")
    assert code == 0
    listed = json.loads(text)["types"]
    assert all(t["examples"] and t["examples"][0]["labels"] == t["simplest"] for t in listed)  # what lookup shows
    types = {t["name"]: t["designs"] for t in listed}
    grouped = {name: n for name, n in types.items() if name.startswith("not in the tables (")}
    assert sum(grouped.values()) == beyond and sum(types.values()) == 300
