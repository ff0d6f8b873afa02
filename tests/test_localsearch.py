"""Local search behind the solver's fast path (non-manifold and periodic scaffolds)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import lkspace
from lkspace import trace
from lkspace.inverse.local_search import local_search, residue_options
from lkspace.inverse.query import Query

from .strategies import traceable_scaffolds


@pytest.mark.parametrize("name", ["honeycomb:cI@2x2x2", "honeycomb:cF@2x2x2", "honeycomb:cP@3x3x3", "cubes:piano"])
@pytest.mark.parametrize("no_zero", [False, True])
def test_fast_path_answers_honeycomb_supercells(name, no_zero):
    s = lkspace.load(name)
    result = lkspace.solve(s, 1, no_zero=no_zero, options=lkspace.SolveOptions(time_limit=20))
    assert result.status in ("feasible", "optimal") and result.method == "fast-path"
    labels = result.solutions[0].labels
    assert trace(s, labels).components == 1
    assert not no_zero or np.all(labels != 0)


def test_residue_options_are_cheapest_per_class():
    s = lkspace.load("book:3")
    options = residue_options(s, Query(1, label_set=np.arange(-4, 5)))
    spine = int(np.flatnonzero(s.edge_degrees == 3)[0])
    assert sorted(options[spine].tolist()) == [-1, 0, 1]  # residues 2, 0, 1 with the smallest |t|


@settings(max_examples=60, deadline=None)
@given(data=st.data(), scaffold=traceable_scaffolds())
def test_local_search_returns_only_exact_designs(data, scaffold):
    target = data.draw(st.integers(1, scaffold.n_faces))
    query = Query(target, label_set=np.arange(-2, 3))
    start = np.zeros(scaffold.n_edges, np.int64)
    found = local_search(scaffold, query, start, 3, data.draw(st.integers(0, 99)), time_budget=0.2)
    assert len({d.tobytes() for d in found}) == len(found)
    for labels in found:
        assert trace(scaffold, labels).components == target
        assert np.all(np.abs(labels) <= 2)
