"""Identification keyed by invariants: names shared by key, equal to the geometric path's.

The reference is :func:`lkspace.knots.recognition.identify`: each design realized,
projected and named on its own, no key and no template.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from lkspace import load
from lkspace.knots.batch import identify_batch
from lkspace.knots.identification import NameFields
from lkspace.knots.key_names import KeyCache, candidates, disk_cache, trusted
from lkspace.knots.keyed import keys_of
from lkspace.knots.recognition import identify

pytest.importorskip("snappy")


def reference(scaffold, labels):
    r = identify(scaffold, labels, geometric=True)
    return None if r.split else r.name, r.mirror, r.components, r.linking_matrix  # rows keep a split link unnamed


@pytest.mark.parametrize("name, label_set", [("tetrahedron", (-2, 3)), ("octahedron", (-1, 2)), ("book:3", (-2, 3))])
def test_keyed_names_equal_the_geometric_path(name, label_set):
    scaffold = load(name)
    labels = np.random.default_rng(11).integers(*label_set, size=(40, scaffold.n_edges))
    cache = KeyCache()
    found = identify_batch(scaffold, labels, cache=cache, progress=False)
    for row, lab in zip(found.itertuples(), labels, strict=True):
        got = (row.knot_name, row.mirror, row.components, json.loads(row.linking_matrix))
        want = reference(scaffold, lab)
        assert (got[0] if isinstance(got[0], str) else None, *got[1:]) == want, lab.tolist()


def test_designs_with_one_key_are_named_once():
    cube = load("cube")
    # one design and its images under rotations and relabellings of the same type: the
    # zero design's 6 unlinked loops, and single twists on different edges (a Hopf link each)
    labels = np.zeros((13, 12), np.int64)
    for e in range(12):
        labels[e + 1, e] = 2
    cache = KeyCache()
    found = identify_batch(cube, labels, cache=cache, progress=False)
    assert cache.full == 2  # the unlink of 6 and the Hopf link (+ 4 loops), each named once
    assert found["status"].eq("identified").all()
    assert len(set(found["linking_matrix"][1:])) > 1  # different components link, same type
    assert len(cache.named) == 2


def test_keys_are_invariants_of_the_link_not_of_the_diagram():
    cube = load("cube")
    labels = np.array([[1, -1, 2, 0, 0, 1, -2, 1, 0, 1, 1, -1]])
    a = keys_of(cube, labels, seed=0)
    b = keys_of(cube, labels, seed=9)
    assert a.crossings[0] != b.crossings[0] or a.template.n_crossings != b.template.n_crossings
    assert a.keys.tolist() == b.keys.tolist()


def test_a_key_the_tables_share_is_not_trusted():
    # 5_1 and 10_132 share the Jones polynomial (and HOMFLY-PT): the key cannot tell them apart
    from lkspace.knots.jones import jones

    pd_51 = [[1, 7, 2, 6], [3, 9, 4, 8], [5, 1, 6, 10], [7, 3, 8, 2], [9, 5, 10, 4]]
    five_one = jones(pd_51)
    found = candidates(five_one, 1)
    assert {name for name, _ in found} == {"5_1", "10_132"}
    assert not trusted(NameFields(knot_name="5_1", mirror=False, status="identified"), found)
    # a diagram of at most 9 crossings cannot be 10_132
    assert {name for name, _ in candidates(five_one, 1, None, 9)} == {"5_1"}
    # the trefoil's Jones polynomial is its own: trusted, and a wrong name is not
    trefoil = jones([[1, 5, 2, 4], [3, 1, 4, 6], [5, 3, 6, 2]])
    found = candidates(trefoil, 1)
    assert trusted(NameFields(knot_name="3_1", mirror=False, status="identified"), found)
    assert not trusted(NameFields(knot_name="4_1", mirror=None, status="identified"), found)
    assert not trusted(NameFields(knot_name="3_1", mirror=False, status="unknown: time limit 1 s reached"), found)


def test_the_disk_cache_keeps_the_names_of_earlier_runs(tmp_path, monkeypatch):
    monkeypatch.setenv("LKSPACE_CACHE", str(tmp_path))
    tetra = load("tetrahedron")
    labels = np.random.default_rng(3).integers(-2, 3, size=(30, 6))
    first = disk_cache()
    first.shipped = {}  # the user cache alone (the shipped file: tests/test_shipped_keys.py)
    a = identify_batch(tetra, labels, cache=first, progress=False)
    assert first.full > 0
    (path,) = tmp_path.glob("names-by-key-*.jsonl")
    with open(path, "a", encoding="utf-8") as fh:
        fh.write('{"key": [1, 2], "fie')  # a run interrupted mid-line
    again = disk_cache()
    again.shipped = {}
    lines = path.read_text().splitlines()
    assert set(again.stored) == {json.dumps(json.loads(line)["key"]) for line in lines[:-1]} | {"[1, 2]"}
    assert not again.named and not again.own  # read when met, not at start
    assert not again.known((1, 2))  # the torn line is refused when its key is met
    b = identify_batch(tetra, labels, cache=again, progress=False)
    assert again.full < first.full  # only designs of keys trusted at no level are named again
    assert set(first.named) <= set(again.named)
    assert a.drop(columns="crossings").equals(b.drop(columns="crossings"))


def test_a_key_shared_by_a_prime_link_and_a_sum_keeps_them_apart():
    # same components, linking numbers, Jones and HOMFLY-PT polynomials: the prime L11n420
    # (the first two) and the sum L2a1#L4a1, whose diagrams simplify to 6 crossings
    tetra = load("tetrahedron")
    labels = np.array(
        [
            [-2, -2, -2, -2, 2, -1],
            [-2, -2, -2, 2, -2, -1],
            [-2, -2, 0, 2, 0, 1],
            [-2, 0, -2, 0, 2, 1],
            [0, -2, -2, 0, 2, 1],
            [0, 0, -2, 2, 2, 1],
        ]
    )
    found = keys_of(tetra, labels)
    assert len({tuple(k) for k in found.keys.tolist()}) == 1
    names = identify_batch(tetra, labels, cache=KeyCache(), progress=False)["knot_name"].tolist()
    assert names == [identify(tetra, lab).name for lab in labels] == ["L11n420"] * 2 + ["L2a1#L4a1"] * 4


def test_keys_in_threads_equal_keys_in_one(monkeypatch):
    """design_keys releases Python's lock and keys_of splits a batch over threads: the parts must join exactly."""
    import lkspace.knots.keyed as keyed

    cube = load("cube")
    labels = np.random.default_rng(3).integers(-2, 3, size=(701, cube.n_edges))
    monkeypatch.setattr(keyed, "FIRST_STEP", 50)  # then steps sized by time: any split must join exactly
    monkeypatch.setattr(keyed, "key_threads", lambda: 1)
    one = keys_of(cube, labels)
    monkeypatch.setattr(keyed, "key_threads", lambda: 3)
    three = keys_of(cube, labels)
    for name in ("keys", "crossings", "components", "keyed", "link_offsets", "link_values", "free", "jones_at"):
        assert np.array_equal(getattr(one, name), getattr(three, name)), name
    assert [three.linking_matrix(d) for d in range(len(labels))] == [one.linking_matrix(d) for d in range(len(labels))]
    assert keyed.design_keys.compiled.targetoptions["nogil"]


def test_names_made_before_an_interrupt_are_kept(tmp_path, monkeypatch):
    """Names in full stream: each key is written to the cache file as its name comes, not after the whole batch."""
    import lkspace.knots.batch as batch
    from lkspace.knots.key_names import share_names

    tetra = load("tetrahedron")
    labels = np.random.default_rng(5).integers(-2, 3, size=(60, tetra.n_edges))
    found = keys_of(tetra, labels)
    path = tmp_path / "names.jsonl"
    cache = KeyCache(path=str(path))
    calls = []
    real = batch._name_fields

    def interrupted_on_the_fourth(item):
        calls.append(1)
        if len(calls) == 4:
            raise KeyboardInterrupt
        return real(item)

    monkeypatch.setattr(batch, "_name_fields", interrupted_on_the_fourth)
    with batch.Namer(1, False, 60.0) as namer, pytest.raises(KeyboardInterrupt):
        share_names(found, cache, lambda indices: namer.name([found.diagram(d)[:2] for d in indices]))
    lines = [json.loads(line) for line in path.read_text().splitlines()]
    assert len(lines) == 3
    assert all(tuple(item["key"]) in cache.named or tuple(item["key"]) in cache.own for item in lines)
