"""Table types on built-in scaffolds (label set ``search``): looked up, then named again through the CLI.

The designs come from ``experiments/search_builtin.py`` (shipped in the atlas index); each
is named here by ``python -m lkspace identify SCAFFOLD --twist ...`` and, independently, by
topoly's HOMFLY-PT on the curves lkspace realizes.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np
import pytest

import lkspace

ENV = {**os.environ, "LKSPACE_PROGRESS": "0"}
SEARCHED = ["10_1", "8_17", "9_32", "10_120", "L9a3"]
"""Types the walked spaces of the atlas do not reach; the search put each on a built-in scaffold."""


def cli(*args: str) -> dict:
    done = subprocess.run(
        [sys.executable, "-m", "lkspace", *args, "--json"], capture_output=True, text=True, env=ENV, timeout=300
    )
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def slow_but(*kept: str) -> list:
    """``SEARCHED``, those not in ``kept`` marked slow (each name is two CLI processes, seconds each)."""
    return [n if n in kept else pytest.param(n, marks=pytest.mark.slow) for n in SEARCHED]


@pytest.mark.parametrize("name", slow_but("10_1", "L9a3"))  # a knot and a link by default
def test_lookup_answers_from_a_builtin_scaffold_named_again_by_identify(name):
    pytest.importorskip("snappy")
    answer = cli("lookup", name, "--limit", "3")
    first = answer["designs"][0]
    assert first["constructed"] is False  # the search's design, or a walked space's as simple (L9a3: cube -2..2)
    assert not first["scaffold"].startswith(("knot:", "link:"))
    assert first["command"] == f"lkspace identify {first['scaffold']} --twist {','.join(map(str, first['labels']))}"
    named = cli("identify", first["scaffold"], "--twist", ",".join(map(str, first["labels"])))
    assert named["name"] == name
    assert named["mirror"] is first["mirror"]
    keys = [(d["sum_abs"], d["nonzero"]) for d in answer["designs"]]
    assert keys == sorted(keys)


def test_the_mirror_image_is_the_design_negated():
    pytest.importorskip("snappy")
    mirror = cli("lookup", "m10_1", "--limit", "2")["designs"]
    table = cli("lookup", "10_1", "--limit", "2")["designs"]
    assert all(d["mirror"] is True for d in mirror) and any(d["mirror"] is False for d in table)
    d = mirror[0]
    assert cli("identify", d["scaffold"], "--twist", ",".join(map(str, d["labels"])))["mirror"] is True
    assert [-t for t in d["labels"]] in [e["labels"] for e in table if e["scaffold"] == d["scaffold"]]


@pytest.mark.parametrize("name", ["9_32", *(pytest.param(n, marks=pytest.mark.slow) for n in ["8_17", "10_120"])])
def test_search_designs_are_named_alike_by_topoly(name):
    """Independent: topoly's HOMFLY-PT on the realized curves of the simplest design."""
    topoly = pytest.importorskip("topoly")
    from lkspace.linktypes.lookup import lookup

    d = lookup(name, limit=1).designs[0]
    curves = lkspace.realize(lkspace.load(d.scaffold).with_labels(np.array(d.labels))).curves
    assert len(curves) == 1
    assert topoly.homfly(np.asarray(curves[0]).tolist(), closure=0, max_cross=80) == name


def test_walked_spaces_answer_first_where_they_did():
    """Types the walked spaces reach keep their answers: the search adds rows only for new (type, scaffold) pairs."""
    from lkspace.linktypes.lookup import read_index

    rows, meta = read_index()
    walked = {(r.type, r.scaffold) for r in rows if r.labels != "search"}
    searched = [r for r in rows if r.labels == "search"]
    assert searched and not any((r.type, r.scaffold) in walked for r in searched)
    assert all(not r.complete and r.designs == len(r.examples) for r in searched)
    assert {s["scaffold"] for s in meta["spaces"] if s["labels"] == "search"} == {r.scaffold for r in searched}
    for name in ("3_1", "L6a4"):
        assert cli("lookup", name, "--limit", "1")["designs"][0]["label_set"] != "search"
