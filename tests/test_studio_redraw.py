"""The incremental redraw: strand curves reused between edits equal lkspace.realize, and travel by content key."""

import base64

import numpy as np
import pytest

import lkspace
from lkspace.geometry.params import RealizeOptions
from lkspace.geometry.realization import realize_reusing


def edits(scaffold, seed, cut, n=6):
    """Labels after each of ``n`` random edits of one or two edges (from all 1); null sides: ``cut`` of them, one more in the last."""
    rng = np.random.default_rng(seed)
    labels = np.ones(scaffold.n_edges, np.int64)
    nulls = np.zeros(scaffold.n_corners, bool)
    nulls[rng.choice(scaffold.n_corners, cut, replace=False)] = True
    for i in range(n):
        if i:
            labels[rng.integers(scaffold.n_edges, size=2)] = rng.integers(-2, 3, size=2)
        if i == n - 1:
            nulls[int(rng.integers(scaffold.n_corners))] = True
        yield labels.copy(), nulls.copy() if nulls.any() else None


@pytest.mark.parametrize(
    "name, block, cut",
    [
        ("honeycomb:cP", [[0, 0, 0], [1, 0, 0], [0, 1, 1]], 0),  # threads smoothed in the cell: realized in full
        ("tiling:square@3x3", None, 0),
        ("cube", None, 0),  # closed loops are smoothed as a whole: realized in full
        ("octahedron", None, 2),  # open strands
    ],
)
def test_reused_curves_equal_realize_bit_for_bit(name, block, cut):
    sc = lkspace.load(name)
    known, reused = {}, 0
    for labels, nulls in edits(sc, len(name), cut):
        tr = lkspace.trace(sc, labels, nulls)
        how = RealizeOptions(embedding="later", trace=tr, translations=None if block is None else np.array(block))
        try:
            expected = lkspace.realize(sc, labels, nulls, options=how)
        except lkspace.errors.GeometryError:  # twists too tight: the reusing path refuses alike
            with pytest.raises(lkspace.errors.GeometryError):
                realize_reusing(sc, tr, known, how)
            continue
        real, entries = realize_reusing(sc, tr, known, how)
        assert len(real.curves) == len(expected.curves)
        for a, b in zip(real.curves, expected.curves, strict=True):
            np.testing.assert_array_equal(a, b)
        assert real.closed.tolist() == expected.closed.tolist()
        assert real.strand_of.tolist() == expected.strand_of.tolist()
        assert real.copy_of.tolist() == expected.copy_of.tolist()
        assert real.tube_radius == expected.tube_radius and real.scale == expected.scale
        reused += len(set(entries) & set(known))
        known = entries
    if cut:  # open strands are built strand by strand
        assert reused > 0


pytest.importorskip("starlette")
httpx = pytest.importorskip("httpx")

from lkspace.studio.app import Studio  # noqa: E402
from lkspace.studio.curves import curve_key  # noqa: E402
from tests.studio_harness import serving  # noqa: E402


@pytest.fixture(scope="module")
def client():
    with serving(Studio()) as c:
        yield c


def nulls_of(sc, corners):
    """(n_corners,) bool with ``corners`` set."""
    out = np.zeros(sc.n_corners, bool)
    out[corners] = True
    return out


def test_curves_the_page_holds_travel_as_keys_alone(client):
    # open strands are built strand by strand (closed ones, and periodic thread classes, are smoothed together)
    name, nulls = "octahedron", [2]
    sc = lkspace.load(name)
    labels = [1] * sc.n_edges
    first = client.post("/api/design", json={"key": name, "labels": labels, "nulls": nulls}).json()["curves"]
    real = lkspace.realize(sc, labels, nulls_of(sc, nulls), options=RealizeOptions(embedding="later"))
    assert first["keys"] == [curve_key(c, cl) for c, cl in zip(real.curves, real.closed, strict=True)]
    assert all(first["sent"]) and len(set(first["keys"])) == len(first["keys"])
    labels[4] = 2
    body = {"key": name, "labels": labels, "nulls": nulls, "have": first["keys"]}
    second = client.post("/api/design", json=body).json()["curves"]
    real = lkspace.realize(sc, labels, nulls_of(sc, nulls), options=RealizeOptions(embedding="later"))
    keys = [curve_key(c, cl) for c, cl in zip(real.curves, real.closed, strict=True)]
    assert second["keys"] == keys and second["counts"] == [len(c) for c in real.curves]
    new = [k not in first["keys"] for k in keys]
    assert second["sent"] == new and 0 < sum(new) < len(new)  # the edit changed some strands, not all
    points = np.frombuffer(base64.b64decode(second["points"]), "<f4").reshape(-1, 3)
    expected = np.vstack([c for c, sent in zip(real.curves, new, strict=True) if sent])
    np.testing.assert_array_equal(points, expected.astype("<f4"))
    ports = [s["port"] for s in client.post("/api/design", json=body).json()["strands"]]
    tr = lkspace.trace(sc, labels, nulls_of(sc, nulls))
    assert ports == [int(tr.steps[a:b].min()) for a, b in zip(tr.strand_starts[:-1], tr.strand_starts[1:], strict=True)]


@pytest.mark.parametrize("have", ["abc", [1, 2], ["x" * 40], ["k"] * 50_001])
def test_a_bad_have_list_is_one_json_error(client, have):
    answer = client.post("/api/design", json={"key": "cube", "have": have})
    assert answer.status_code == 400 and "have" in answer.json()["error"]["message"]
