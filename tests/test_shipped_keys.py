"""The key -> name file shipped in lkspace/data: keys as the compiled kernel computes them, names as identification gives them.

References: the compiled :func:`~lkspace.knots.keyed.design_keys` for the keys, and
:func:`lkspace.knots.recognition.identify` (each design realized, projected and named on
its own by spherogram and SnapPy, no key) or :func:`~lkspace.knots.naming.name_pd` on a
table PD code for the names, chirality included.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from lkspace import load
from lkspace.knots import shipped_keys as shipped_module
from lkspace.knots.batch import identify_batch
from lkspace.knots.key_names import KeyCache, disk_cache
from lkspace.knots.keyed import KEY_VERSION, keys_of
from lkspace.knots.recognition import identify
from lkspace.knots.shipped_keys import SEARCHED, SHIPPED, ShippedKeys, shipped_keys

pytest.importorskip("snappy")


def shipped_cache() -> KeyCache:
    return KeyCache(shipped=shipped_keys())


def test_the_shipped_file_is_of_this_key_version():
    import gzip

    with gzip.open(SHIPPED, "rt", encoding="utf-8") as fh:
        header = json.loads(fh.readline())
    assert header["key_version"] == KEY_VERSION, "rebuild it: python experiments/build_key_names.py"
    assert header["knots"] >= 12 and header["links"] >= 11
    assert len(shipped_keys().lines()) == header["keys"] > 5000


def test_a_key_searched_in_the_text_is_the_line_the_index_reads():
    every = shipped_keys().lines()
    keys = sorted(every, key=str)[:: len(every) // (SEARCHED - 4)][: SEARCHED - 4]
    searched = ShippedKeys(shipped_keys().text)  # a fresh one: its first lookups search the text
    for key in keys:
        assert searched.get(key) == every[key]
    assert searched.get((1, 2)) is None and searched.get(("diagram", "0" * 32)) is None
    assert searched._index is None  # no line was indexed for these lookups
    for key in keys:  # past SEARCHED lookups: the same answers from the index
        assert searched.get(key) == every[key]
    assert searched._index is not None and searched.get((1, 2)) is None


def test_keys_of_pd_codes_equal_the_compiled_keys():
    from lkspace.knots.table_keys import pd_key, unknot_key

    cube = load("cube")
    labels = np.random.default_rng(5).integers(-1, 2, size=(60, cube.n_edges))
    found = keys_of(cube, labels)
    compared = 0
    for d in range(len(labels)):
        if not found.keyed[d] or found.free[d]:
            continue
        pd = found.diagram(d)[0]
        want = tuple(int(v) for v in found.keys[d])
        assert (pd_key(pd) if pd else unknot_key()) == want, labels[d].tolist()
        compared += 1
    assert compared > 30


@pytest.mark.parametrize(
    "pd, name",
    [
        ([[1, 5, 2, 4], [3, 1, 4, 6], [5, 3, 6, 2]], "3_1"),
        ([[4, 2, 5, 1], [8, 6, 1, 5], [6, 3, 7, 4], [2, 7, 3, 8]], "4_1"),
        ([[4, 1, 3, 2], [2, 3, 1, 4]], "L2a1"),
        ([[1, 5, 2, 4], [3, 9, 4, 8], [5, 1, 6, 10], [7, 3, 8, 2], [9, 7, 10, 6]], "5_2"),
    ],
)
def test_shipped_names_of_small_pd_codes_equal_name_pd_both_mirror_images(pd, name):
    import spherogram

    from lkspace.knots.identification import NameFields
    from lkspace.knots.jones import jones
    from lkspace.knots.key_names import candidates
    from lkspace.knots.naming import name_pd, one_based
    from lkspace.knots.recognition import status_of
    from lkspace.knots.table_keys import pd_key

    lines = shipped_keys().lines()
    for code in (pd, one_based(spherogram.Link(pd).mirror().PD_code())):
        n_components = len(spherogram.Link(code).link_components)
        live = name_pd(code, n_components, floer=False)
        assert live.name == name
        shipped = json.loads(lines[pd_key(code)])["fields"]
        if shipped is None:  # the tables hold another type of this Jones polynomial (4_1 and 11n_19)
            assert len({n for n, _ in candidates(jones(code), n_components)}) > 1
        else:
            assert NameFields.from_json(shipped) == NameFields.of(live, status_of(live))


def test_shipped_names_equal_the_geometric_path():
    scaffold = load("cube")
    labels = np.random.default_rng(23).integers(-1, 2, size=(25, scaffold.n_edges))
    cache = shipped_cache()
    found = identify_batch(scaffold, labels, cache=cache, progress=False)
    assert cache.full < 5  # the shipped file named (nearly) every key
    for row, lab in zip(found.itertuples(), labels, strict=True):
        want = identify(scaffold, lab)
        got = (row.knot_name if isinstance(row.knot_name, str) else None, row.mirror, row.components)
        name = None if want.split else want.name  # a catalog row names a split link by its pieces, not `name`
        assert got == (name, want.mirror, want.components), lab.tolist()


def test_the_shipped_file_keeps_a_prime_link_and_a_sum_of_one_key_apart():
    # L11n420 (shipped, trusted at the first level) and the sum L2a1#L4a1 of the same key
    tetra = load("tetrahedron")
    labels = np.array([[-2, -2, -2, -2, 2, -1], [-2, -2, 0, 2, 0, 1], [0, 0, -2, 2, 2, 1]])
    names = identify_batch(tetra, labels, cache=shipped_cache(), progress=False)["knot_name"].tolist()
    assert names == ["L11n420", "L2a1#L4a1", "L2a1#L4a1"]


def test_the_user_cache_is_read_beside_the_shipped_file(tmp_path, monkeypatch):
    monkeypatch.setenv("LKSPACE_CACHE", str(tmp_path))
    cache = disk_cache()
    assert cache.shipped is shipped_keys()
    monkeypatch.setattr(shipped_module, "SHIPPED", str(tmp_path / "missing.gz"))
    shipped_keys.cache_clear()
    try:
        assert disk_cache().shipped.lines() == {}
    finally:
        monkeypatch.undo()
        shipped_keys.cache_clear()


def test_shipped_names_of_a_sample_of_table_entries_equal_name_pd():
    import random

    import spherogram

    from lkspace.knots.identification import NameFields
    from lkspace.knots.naming import name_pd, one_based
    from lkspace.knots.recognition import status_of
    from lkspace.knots.table_keys import pd_key
    from lkspace.knots.tables import tables

    entries = sorted({e.table_name: e for es in tables().values() for e in es if e.pd}.items())
    knots = [e for _, e in entries if e.components == 1 and 9 <= e.crossings <= 12]
    links = [e for _, e in entries if e.components > 1 and 7 <= e.crossings <= 11]
    sample = random.Random(7).sample(knots, 5) + random.Random(7).sample(links, 5)
    lines = shipped_keys().lines()
    compared = 0
    for entry in sample:
        pd = entry.pd_code()
        for mirror, code in ((False, pd), (True, one_based(spherogram.Link(pd).mirror().PD_code()))):
            assert pd_key(code) == pd_key(pd, mirror)  # the mirror image's key, from spherogram's mirror
            shipped = json.loads(lines[pd_key(pd, mirror)])["fields"]
            if shipped is None:
                continue  # a key the tables share: named design by design
            live = name_pd(code, entry.components, floer=False)
            assert NameFields.from_json(shipped) == NameFields.of(live, status_of(live)), (entry.table_name, mirror)
            compared += 1
    assert compared >= 8  # of 20: the others are keys the tables share
