"""Two pages on one studio keep their own jobs; requests with non-finite numbers, a block on a finite
scaffold or an upload that is not a file are refused with 400; split links and crossing numbers named."""

import time

import pytest

import lkspace

pytest.importorskip("starlette")
pytest.importorskip("uvicorn")
httpx = pytest.importorskip("httpx")

from lkspace.studio.answers import table_crossings  # noqa: E402
from lkspace.studio.app import Studio  # noqa: E402
from lkspace.studio.server import start_in_thread  # noqa: E402

SLOW_IDENTIFY = {"key": "dodecahedron", "labels": [2] * 30}  # about 10 s to name
UPLOAD = {"Content-Type": "application/octet-stream"}
JSON = {"Content-Type": "application/json"}


@pytest.fixture(scope="module")
def url():
    address, stop = start_in_thread(Studio())
    yield address
    stop()


def page(url, name):
    return httpx.Client(base_url=url, timeout=120, headers={"X-Lkspace-Page": name})


def state(client, job):
    return client.get(f"/api/job/{job}").json()["state"]


def test_two_pages_never_cancel_each_others_identify(url):
    with page(url, "tabA") as a, page(url, "tabB") as b:
        first = a.post("/api/identify", json=SLOW_IDENTIFY).json()["job"]
        other = b.post("/api/identify", json={**SLOW_IDENTIFY, "labels": [2] * 29 + [1]}).json()["job"]
        assert state(a, first) == "running" and state(b, other) == "running"  # before: tab B's start cancelled A's
        again = a.post("/api/identify", json=SLOW_IDENTIFY).json()["job"]  # the same page asking again replaces its own
        assert state(a, first) == "cancelled" and state(a, again) == "running" and state(b, other) == "running"
        for client, job in ((a, again), (b, other)):
            assert client.post(f"/api/job/{job}/cancel", json={}).json()["state"] == "cancelled"


def test_a_redraw_on_one_page_leaves_the_other_pages_clearance_running(url):
    with page(url, "tabA") as a, page(url, "tabB") as b:
        studio = Studio()  # the jobs of a studio of our own, to start a clearance that stays running
        real = lkspace.realize("cube", [1] * 12)
        job = studio.jobs.start("clearance", real, page="tabA")
        studio.jobs.stop("clearance", "tabB")  # what tab B's redraw does
        assert job.state == "running"
        studio.jobs.stop("clearance", "tabA")
        assert job.state == "cancelled"
        studio.jobs.shutdown()
        for client in (a, b):  # and over HTTP: both measured, neither superseded
            r = client.post("/api/clearance", json={"key": "cube", "labels": [1] * 12})
            assert r.status_code == 200 and r.json()["ok"], r.text


@pytest.mark.parametrize("page_id", ["", "x" * 65, "a b", "é"])
def test_a_page_id_is_checked(url, page_id):
    with httpx.Client(base_url=url, timeout=60) as c:
        r = c.post("/api/clearance", json={"key": "cube", "page": page_id})
        if page_id == "":
            assert r.status_code == 200
        else:
            assert r.status_code == 400 and r.json()["error"]["message"].startswith("page: "), r.text


@pytest.mark.parametrize("number", ["NaN", "Infinity", "-Infinity", "1e999", "-2.5e400"])
@pytest.mark.parametrize(
    ("path", "template"),
    [
        ("/api/design", '{"key": "cube", "labels": [%s, 1]}'),
        ("/api/solve", '{"key": "cube", "components": 1, "time_limit": %s}'),
        ("/api/diagram", '{"key": "cube", "view": [[%s, 0, 0], [0, 1, 0], [0, 0, 1]]}'),
        ("/api/design-file", '{"key": "cube", "view": {"position": [%s, 0, 0]}}'),
        ("/api/catalog", '{"offset": %s}'),
        ("/api/identify", '{"key": "cube", "nulls": [%s]}'),
    ],
)
def test_a_non_finite_number_anywhere_is_refused_with_400_naming_it(url, path, template, number):
    with httpx.Client(base_url=url, timeout=60) as c:
        r = c.post(path, content=(template % number).encode(), headers=JSON)
    assert r.status_code == 400, r.text
    message = r.json()["error"]["message"]
    assert message.startswith(f"request body: {number} ") and "finite numbers" in message


@pytest.mark.parametrize("path", ["/api/design", "/api/clearance", "/api/identify", "/api/diagram", "/api/export"])
def test_a_block_on_a_finite_scaffold_is_refused(url, path):
    with httpx.Client(base_url=url, timeout=60) as c:
        r = c.post(path, json={"key": "cube", "block": [2, 2, 2], "format": "svg"})
        assert r.status_code == 400, r.text
        assert (
            r.json()["error"]["message"] == "block: this scaffold is finite (no lattice to copy along); send no block"
        )
        assert c.post(path, json={"key": "honeycomb:cP", "block": [1, 1, 1], "format": "svg"}).status_code == 200


@pytest.mark.parametrize("endpoint", ["/api/upload", "/api/open-design"])
@pytest.mark.parametrize(
    ("name", "body"),
    [("x.obj", b"\xff\xfe\x00"), ("x.json", b"{bad"), ("x.obj", b""), ("x.obj", b"v 0 0 0\n"), ("x.json", b"[1, 2]")],
)
def test_an_upload_whose_bytes_are_not_a_file_is_a_400(url, endpoint, name, body):
    with httpx.Client(base_url=url, timeout=60) as c:
        r = c.post(endpoint, content=body, headers={**UPLOAD, "X-Filename": name})
    assert r.status_code == 400 and r.json()["error"]["message"].startswith("x."), r.text


def test_crossing_numbers_read_from_names_agree_with_the_tables():
    pytest.importorskip("database_knotinfo")
    from lkspace.knots.tables import tables

    entries = [e for group in tables().values() for e in group]
    assert len(entries) > 1000
    for e in entries:  # every KnotInfo and LinkInfo name: the table's own crossing_number column
        assert table_crossings(e.name) == e.crossings, e.name
        assert table_crossings("m" + e.name) == e.crossings
    assert [table_crossings(n) for n in ("split: 0_1 + 3_1", "3_1#4_1", None, "unknown")] == [None] * 4


@pytest.mark.parametrize(
    ("labels", "name", "common"),
    [
        ([0, 0, -1, -1, 0, 0, 0, 1, 0, 0, 1, 1], "split: 0_1 + 3_1", None),
        ([1, 1, -1, -1, 1, 1, 0, -1, -1, 0, 1, -1], "split: 0_1 + 0_1", "unlink of 2 components"),
    ],
)
def test_a_split_link_is_named_by_its_pieces(url, labels, name, common):
    pytest.importorskip("regina")
    found = lkspace.identify("cube", labels)
    assert found.split and found.name == name and sorted(found.details["pieces"]) == name[7:].split(" + ")
    with page(url, "split") as c:
        job = c.post("/api/identify", json={"key": "cube", "labels": labels}).json()["job"]
        while (j := c.get(f"/api/job/{job}").json())["state"] == "running":
            time.sleep(0.2)
    assert j["state"] == "done", j
    r = j["result"]
    assert (r["name"], r["common_name"], r["split"], r["least_crossings"]) == (name, common, True, None)


BASES = {  # each endpoint with a body it answers 200, and the fields it reads
    "scaffold": {"key": "cube"},
    "orbits": {"key": "tetrahedron"},
    "design": {"key": "cube", "labels": [1] * 12, "nulls": [], "relax": False, "have": []},
    "clearance": {"key": "cube", "labels": [1] * 12},
    "identify": {"key": "tetrahedron", "labels": [1] * 6},
    "solve": {
        "key": "tetrahedron",
        "components": 1,
        "label_set": "-1..1",
        "no_zero": True,
        "count": 1,
        "time_limit": 1,
    },
    "diagram": {"key": "cube", "labels": [1] * 12, "view": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]},
    "thumbnails": {"key": "cube", "designs": [[1] * 12], "names": [None]},
    "design-file": {"key": "cube", "labels": [1] * 12, "view": None},
    "filename": {"key": "cube", "labels": [1] * 12},
    "export": {"key": "tetrahedron", "labels": [1] * 6, "format": "json"},
}
KINDS = {  # every kind of JSON value, as the text a client sends
    "null": "null",
    "true": "true",
    "zero": "0",
    "negative": "-1",
    "huge int": "1" + "0" * 30,
    "fraction": "1.5",
    "tiny": "5e-324",
    "string": '"x"',
    "empty list": "[]",
    "list of string": '["x"]',
    "nested list": "[[1]]",
    "object": '{"a": 1}',
}
NON_FINITE = ["NaN", "Infinity", "-Infinity", "1e999"]


def with_field(base, field, text):
    """The base body as JSON text with ``field`` replaced by the raw JSON ``text``."""
    import json

    return (
        "{" + ", ".join(f'"{k}": {text if k == field else json.dumps(v)}' for k, v in {**base, field: 0}.items()) + "}"
    )


SLOW = {"export", "identify", "solve", "clearance", "design"}
"""Endpoints whose accepted bodies start a worker or relax (seconds each): their sweep runs with ``-m slow``."""


@pytest.mark.parametrize("path", [pytest.param(p, marks=pytest.mark.slow) if p in SLOW else p for p in sorted(BASES)])
def test_every_field_of_every_endpoint_with_every_json_value_kind(url, path):
    base = BASES[path]
    with page(url, "fuzz-" + path.replace("-", "")) as c:
        assert c.post(f"/api/{path}", json=base).status_code == 200
        for field in [*base, "page", "block"]:
            for kind, text in KINDS.items():
                r = c.post(f"/api/{path}", content=with_field(base, field, text).encode(), headers=JSON)
                assert r.status_code < 500, (field, kind, r.text)
                if r.status_code != 200:
                    error = r.json()["error"]
                    assert set(error) == {"type", "message"} and error["message"], (field, kind, r.text)
            for token in NON_FINITE:
                r = c.post(f"/api/{path}", content=with_field(base, field, f"[{token}]").encode(), headers=JSON)
                assert r.status_code == 400 and "finite numbers" in r.json()["error"]["message"], (field, token)


def test_the_solve_time_limit_says_it_is_wall_clock_time(url):
    """Issue 35: the page's solve limit, and its refusal, say what the seconds count."""
    with httpx.Client(base_url=url, timeout=60) as c:
        field = next(line for line in c.get("/").text.splitlines() if 'id="sv-limit"' in line)
        assert "wall-clock" in field, field
        done = c.post("/api/solve", json={"key": "cube", "components": 1, "time_limit": 0})
    assert done.status_code == 400 and "wall-clock" in done.json()["error"]["message"], done.text
