"""The design file (lkspace.io.design_json), its studio endpoints and the download names.

Bad files get one message naming the field; the studio answers them as a JSON error (4xx).
"""

import json

import numpy as np
import pytest

import lkspace
from lkspace.errors import LabelError, ScaffoldError
from lkspace.io.design_json import design_to_dict, format_design, read_design
from lkspace.io.scaffold_json import format_scaffold_json
from lkspace.scaffolds import builtin
from lkspace.studio.filenames import design_stem

pytest.importorskip("starlette")
httpx = pytest.importorskip("httpx")

from lkspace.studio.app import Studio  # noqa: E402
from tests.studio_harness import serving  # noqa: E402

CUBE_VIEW = {"position": [3.0, 2.0, 4.0], "target": [0.0, 0.1, 0.0], "up": [0.0, 1.0, 0.0]}


def design(**fields):
    base = {"format": "lkspace-design", "version": 1, "scaffold": "cube", "labels": [1] * 12}
    return json.dumps({**base, **fields})


def read(text):
    return read_design(text, "d.json", builtin)


def test_round_trip_builtin():
    cube = builtin("cube")
    labels = np.array([1, -1, 0, 2, 1, 1, 1, 1, 1, 1, 1, -3])
    nulls = np.zeros(cube.n_corners, bool)
    nulls[[0, 7]] = True
    text = format_design(design_to_dict(cube, "cube", labels, nulls, None, CUBE_VIEW))
    back = read(text)
    assert back.builtin == "cube" and back.scaffold.n_edges == 12
    assert back.labels.tolist() == labels.tolist()
    assert np.flatnonzero(back.nulls).tolist() == [0, 7]
    assert back.view == {k: tuple(v) for k, v in CUBE_VIEW.items()}
    assert (
        lkspace.trace(back.scaffold, back.labels, back.nulls).components
        == lkspace.trace(cube, labels, nulls).components
    )


def test_round_trip_embedded_periodic():
    sc = builtin("honeycomb:cP")
    labels = np.arange(sc.n_edges) % 3 - 1
    data = design_to_dict(sc, None, labels, None, (2, 1, 3))
    assert isinstance(data["scaffold"], dict) and "labels" not in data["scaffold"]

    def no_builtins(name):
        raise AssertionError(f"embedded scaffold resolved by name {name}")

    back = read_design(format_design(data), "d.json", no_builtins)
    assert back.builtin is None and back.block == (2, 1, 3)
    assert back.scaffold.content_hash() == sc.content_hash()
    assert back.labels.tolist() == labels.tolist()


@pytest.mark.parametrize(
    ("text", "error", "message"),
    [
        ('{"format": "lkspace-design",', ScaffoldError, "d.json line 1: invalid JSON"),
        ("[1, 2]", ScaffoldError, "expected a JSON object, got list"),
        (design(format="lkspace-scaffold"), ScaffoldError, "format 'lkspace-scaffold' is not 'lkspace-design'"),
        (design(version=2), ScaffoldError, "design file version 2 is not supported (expected 1)"),
        (design(colour="red"), ScaffoldError, "unknown key ['colour']"),
        (design(scaffold=7), ScaffoldError, "scaffold: a built-in name or a scaffold file object"),
        (design(labels=[1] * 11), LabelError, "labels: expected 12 twist labels (one per edge of cube), got 11"),
        (design(labels=[1] * 11 + [0.5]), LabelError, "labels[11] (edge"),
        (
            design(labels=[1] * 11 + [2**70]),
            LabelError,
            "labels: cube: label 11: 1180591620717411303424 is out of range",
        ),
        (design(nulls=[[6, 0]]), ScaffoldError, "nulls[0][0] (face): 6 out of range 0..5"),
        (design(nulls=[[0, 4]]), ScaffoldError, "nulls[0][1] (side): 4 out of range 0..3"),
        (design(block=[2, 2, 2]), ScaffoldError, "block: cube is not periodic"),
        (design(view={"position": [1, 2]}), ScaffoldError, "view.position: expected 3 entries, got 2"),
        (design(view={**CUBE_VIEW, "zoom": 2}), ScaffoldError, "view: unknown key ['zoom']"),
        (design(view={**CUBE_VIEW, "target": [3, 2, 4]}), ScaffoldError, "position and target are the same point"),
    ],
)
def test_bad_files_one_clear_message(text, error, message):
    with pytest.raises(error) as info:
        read(text)
    assert message in str(info.value)
    assert str(info.value).startswith("d.json")


def test_missing_labels_and_unknown_scaffold():
    with pytest.raises(LabelError, match="d.json: labels missing"):
        read(json.dumps({"format": "lkspace-design", "version": 1, "scaffold": "cube"}))
    with pytest.raises(ScaffoldError):
        read(design(scaffold="no-such-solid"))


def test_design_stem_short_long_and_safe():
    assert design_stem("cube", [1, -1, 0, 2] + [1] * 8) == "cube_t1.-1.0.2.1.1.1.1.1.1.1.1"
    long = design_stem("honeycomb:cP@3x3x3", [1] * 81)
    assert long.startswith("honeycomb-cP-3x3x3_") and len(long.split("_")[1]) == 8
    assert design_stem("cube", [1] * 12, [3]) != design_stem("cube", [1] * 12)  # nulls are named too
    assert design_stem("../a b/c", [0]) == "a-b-c_t0"


@pytest.fixture(scope="module")
def client():
    with serving(Studio()) as c:
        yield c


def test_save_then_open_over_http(client):
    labels = [2, -1, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1]
    body = {"key": "cube", "labels": labels, "nulls": [5], "block": None, "view": CUBE_VIEW}
    r = client.post("/api/design-file", json=body)
    assert r.status_code == 200
    name = r.headers["content-disposition"].split('filename="')[1].rstrip('"')
    assert name == design_stem("cube", labels, [5]) + ".design.json"
    saved = r.json()
    assert saved["scaffold"] == "cube" and saved["labels"] == labels and saved["view"] == CUBE_VIEW
    back = client.post(
        "/api/open-design", content=r.content, headers={"X-Filename": name, "Content-Type": "application/octet-stream"}
    ).json()
    assert back["key"] == "cube" and back["labels"] == labels and back["nulls"] == [5] and back["view"] == CUBE_VIEW


def test_uploaded_scaffold_is_embedded_and_reopens(client):
    tetra = builtin("tetrahedron")
    text = format_scaffold_json(tetra).replace('"tetrahedron"', '"my tetra"')
    held = client.post(
        "/api/upload",
        content=text.encode(),
        headers={"X-Filename": "my.json", "Content-Type": "application/octet-stream"},
    ).json()
    r = client.post("/api/design-file", json={"key": held["key"], "labels": [1, 2, 3, 1, 2, 3]})
    saved = r.json()
    assert saved["scaffold"]["name"] == "my tetra"
    assert r.headers["content-disposition"].endswith('filename="my-tetra_t1.2.3.1.2.3.design.json"')
    back = client.post(
        "/api/open-design",
        content=r.content,
        headers={"X-Filename": "x.json", "Content-Type": "application/octet-stream"},
    ).json()
    assert back["key"] == held["key"] and back["labels"] == [1, 2, 3, 1, 2, 3] and back["view"] is None


def test_open_design_errors_are_json(client):
    for text, words in [
        (b"{oops", "invalid JSON"),
        (design(labels=[1] * 5).encode(), "expected 12 twist labels"),
        (design(scaffold="id:0123456789abcdef").encode(), "is not a built-in scaffold"),
        (b"\xff\xfe", "not a text file"),
        (design(scaffold="honeycomb:cP", labels=[1] * 3, block=[5, 5, 5]).encode(), "block: 125 copies > 64"),
    ]:
        r = client.post(
            "/api/open-design",
            content=text,
            headers={"X-Filename": "bad.json", "Content-Type": "application/octet-stream"},
        )
        assert 400 <= r.status_code < 500
        assert words in r.json()["error"]["message"] and r.json()["error"]["message"].startswith("bad.json")


def test_server_exports_and_filename_agree(client):
    labels = [1, -1, 0, 2] + [1] * 8
    r = client.post("/api/export", json={"key": "cube", "labels": labels, "format": "svg"})
    assert r.headers["content-disposition"] == 'attachment; filename="cube_t1.-1.0.2.1.1.1.1.1.1.1.1.svg"'
    stem = client.post("/api/filename", json={"key": "cube", "labels": labels}).json()["stem"]
    assert stem == "cube_t1.-1.0.2.1.1.1.1.1.1.1.1"
    big = client.post("/api/filename", json={"key": "honeycomb:cP@3x3x3"}).json()["stem"]
    assert big.startswith("honeycomb-cP-3x3x3_") and len(big) == len("honeycomb-cP-3x3x3_") + 8


def test_open_design_takes_files_only_as_octet_stream(client):
    """A design file sent as text/plain (what a cross-site form can send) is refused before it is read."""
    r = client.post("/api/open-design", content=b"{}", headers={"X-Filename": "d.json", "Content-Type": "text/plain"})
    assert r.status_code == 415 and "application/octet-stream" in r.json()["error"]["message"]
