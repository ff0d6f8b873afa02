"""The studio's bounds: one job of each kind, a cap on workers (429), exports in their own lane, uploads typed,
a block that fits, and no 5xx answer to any JSON a page (or a fuzzer) can send."""

import json
import threading
import time
import urllib.parse

import pytest

import lkspace

pytest.importorskip("starlette")
pytest.importorskip("uvicorn")
httpx = pytest.importorskip("httpx")
hypothesis = pytest.importorskip("hypothesis")
st = hypothesis.strategies

from lkspace.studio.app import Studio  # noqa: E402
from lkspace.studio.browse import Browser  # noqa: E402
from lkspace.studio.jobs import Jobs  # noqa: E402
from lkspace.studio.lanes import Lane  # noqa: E402
from lkspace.studio.server import start_in_thread  # noqa: E402

SLOW_IDENTIFY = {"key": "dodecahedron", "labels": [2] * 30}  # about 10 s to name
SLOW_SOLVE = {"key": "honeycomb:cP@4x4x4", "components": 7, "count": 50, "objective": "min-abs", "time_limit": 60}


@pytest.fixture(scope="module")
def catalog(tmp_path_factory):
    path = str(tmp_path_factory.mktemp("cat") / "tetra.parquet")
    lkspace.write_catalog("tetrahedron", path, label_set="-2..2")
    return path


def serve(studio):
    url, stop = start_in_thread(studio)
    client = httpx.Client(base_url=url, timeout=120)
    client.studio = studio
    return client, stop


@pytest.fixture(scope="module")
def client(catalog):
    studio = Studio(browser=Browser(catalog))
    studio.browser.wait(30)
    c, stop = serve(studio)
    yield c
    c.close()
    stop()


def at_once(n, fn):
    """``fn(i)`` for i < n, in n threads started together; the answers in order."""
    out = [None] * n
    gate = threading.Barrier(n)

    def run(i):
        gate.wait()
        out[i] = fn(i)

    threads = [threading.Thread(target=run, args=(i,)) for i in range(n)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return out


def alive(studio, kind):
    return [j for j in list(studio.jobs._jobs.values()) if j.kind == kind and j.process.is_alive()]


def test_a_burst_of_identify_requests_leaves_one_job_running(client):
    answers = at_once(50, lambda i: client.post("/api/identify", json=SLOW_IDENTIFY))
    assert [a.status_code for a in answers] == [200] * 50
    assert len(alive(client.studio, "identify")) == 1  # 49 were stopped by the next one, on the server
    states = [client.get(f"/api/job/{a.json()['job']}").json()["state"] for a in answers]
    # at most one runs (one burst in three or so reports the last one cancelled too: not yet understood,
    # noted in issue 22's closing note)
    assert states.count("running") <= 1 and states.count("cancelled") >= 49, states


def test_a_new_solve_stops_the_running_one(client):
    first = client.post("/api/solve", json=SLOW_SOLVE).json()["job"]
    second = client.post("/api/solve", json={**SLOW_SOLVE, "components": 5}).json()["job"]
    assert client.get(f"/api/job/{first}").json()["state"] == "cancelled"
    assert [j.id for j in alive(client.studio, "solve")] == [second]
    assert client.post(f"/api/job/{second}/cancel", json={}).json()["state"] == "cancelled"
    assert alive(client.studio, "solve") == []


def test_past_the_cap_a_job_is_refused_with_429_naming_what_runs():
    client, stop = serve(Studio(jobs=Jobs(max_running=1)))
    try:
        job = client.post("/api/identify", json=SLOW_IDENTIFY).json()["job"]
        refused = client.post("/api/solve", json=SLOW_SOLVE)
        assert refused.status_code == 429
        assert refused.json()["error"] == {
            "type": "Busy",
            "message": "the studio is busy: 1 job running (identify); wait or cancel one",
        }
        newer = client.post("/api/identify", json={**SLOW_IDENTIFY, "labels": [2] * 29 + [1]})
        assert newer.status_code == 200  # a newer identify replaces the running one: not refused
        assert client.get(f"/api/job/{job}").json()["state"] == "cancelled"
        client.post(f"/api/job/{newer.json()['job']}/cancel", json={})
        assert client.post("/api/solve", json=SLOW_SOLVE).status_code == 200  # a free slot: accepted
    finally:
        client.close()
        stop()


def test_exports_wait_in_their_own_lane_and_a_redraw_does_not_wait_behind_them():
    studio = Studio(exports=Lane("export", waiting=2))
    client, stop = serve(studio)
    try:
        body = {"key": "tetrahedron", "labels": [1] * 6, "format": "svg"}  # seconds each
        answers: list = []
        exporting = threading.Thread(
            target=lambda: answers.extend(at_once(4, lambda i: client.post("/api/export", json=body)))
        )
        exporting.start()
        end = time.monotonic() + 60
        while studio.exports.pending < 3:
            assert time.monotonic() < end
            time.sleep(0.01)
        d = client.post("/api/design", json={"key": "cube", "labels": [1] * 11 + [2]})
        assert d.status_code == 200 and d.json()["components"] == lkspace.trace("cube", [1] * 11 + [2]).components
        assert studio.exports.pending >= 1  # the redraw answered while exports still ran or waited
        exporting.join(120)
        codes = sorted(a.status_code for a in answers)
        assert codes == [200, 200, 200, 429]
        busy = next(a for a in answers if a.status_code == 429).json()["error"]["message"]
        assert busy == "the studio is busy: 3 exports running or in line; wait for them to finish"
        assert all(a.content.startswith(b"<?xml") for a in answers if a.status_code == 200)
        end = time.monotonic() + 30  # the lane is freed just after the last answer is sent
        while studio.exports.pending and time.monotonic() < end:
            time.sleep(0.01)
        assert studio.exports.pending == 0
    finally:
        client.close()
        stop()


@pytest.mark.parametrize("kind", ["text/plain", "multipart/form-data; boundary=x", "application/x-www-form-urlencoded"])
def test_an_upload_a_cross_site_form_can_send_is_refused_before_its_body_is_read(client, kind):
    big = b"v 0 0 0\n" * 1_100_000  # past the 8 MB limit: a 413 would mean the body was read
    r = client.post("/api/upload", content=big, headers={"Content-Type": kind, "X-Filename": "t.obj"})
    assert r.status_code == 415 and "application/octet-stream" in r.json()["error"]["message"]
    bare = client.post("/api/upload", content=b"v 0 0 0\n", headers={"X-Filename": "t.obj"})
    assert bare.status_code == 415
    obj = lkspace.io.obj.format_obj(lkspace.load("tetrahedron")).encode()
    typed = {"Content-Type": "application/octet-stream", "X-Filename": "t.obj"}
    assert client.post("/api/upload", content=obj, headers=typed).json()["n_faces"] == 4
    assert client.post("/api/upload", content=big, headers=typed).status_code == 413  # the limit holds


@pytest.mark.parametrize(
    ("name", "block"),
    [
        ("honeycomb:cP", [2, 2, 2]),
        ("honeycomb:cP@3x3x3", [2, 2, 2]),
        ("honeycomb:cP@7x7x7", [1, 1, 1]),
        ("tiling:square", [3, 3]),
        ("tiling:square@10x10", [3, 3]),
        ("tiling:square@32x32", [1, 1]),
    ],
)
def test_a_scaffold_opens_with_a_block_that_draws(client, name, block):
    view = client.post("/api/scaffold", json={"key": name}).json()
    assert view["block"] == block
    d = client.post("/api/design", json={"key": name, "block": block}).json()
    assert "failure" not in d and len(d["curves"]["counts"]) > 0


def test_a_block_too_big_is_refused_at_once_with_a_smaller_one_named(client):
    assert "block" not in client.post("/api/scaffold", json={"key": "cube"}).json()
    r = client.post("/api/design", json={"key": "honeycomb:cP@7x7x7", "block": [2, 2, 2]})
    assert r.status_code == 413
    assert r.json()["error"]["message"] == (
        "block 2x2x2: 8 copies of 1,029 faces make 8,232 faces > 4,000 the studio draws at once;"
        " choose a smaller block, such as 1x1x1"
    )


# ---- no 5xx for any JSON: every POST endpoint, the job and lookup GETs

HUGE = [10**30, -(10**30), 2**63, -(2**63) - 1, 2**64]
ODD = [*HUGE, 1e308, -0.0, "NaN", "Infinity", "-1e400", "²", "١٢", "", " "]
PLAUSIBLE = ["cube", "tetrahedron", "dihedron:3", "honeycomb:cP", "tiling:square", "-2..2", "min-abs", "json", "obj"]
leaf = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(-5, 40),
    st.integers(),
    st.sampled_from(ODD + PLAUSIBLE),
    st.floats(allow_nan=False, allow_infinity=False),
    st.text(max_size=12),
)
anything = st.recursive(
    leaf,
    lambda kids: st.lists(kids, max_size=6) | st.dictionaries(st.text(max_size=6), kids, max_size=4),
    max_leaves=16,
)
odd_int = st.integers(-3, 40) | st.sampled_from(HUGE)
FIELDS = {  # each field: values of its own shape, some of them odd
    "labels": st.lists(odd_int | leaf, max_size=31) | st.sampled_from([[1] * 3, [1] * 6, [2] * 12, [-1] * 3]),
    "nulls": st.lists(st.integers(-2, 60) | st.sampled_from(HUGE), max_size=4),
    "block": st.lists(st.integers(-1, 70) | st.sampled_from(HUGE), min_size=1, max_size=4),
    "relax": st.booleans(),
    "components": odd_int,
    "count": odd_int,
    "time_limit": st.sampled_from([0.5, 1, 0, -1, 601, 1e-300, 1e308, 2**64]),
    "label_set": st.sampled_from(["-2..2", "-1,1", "0..0", "2..-2", "1..100000000000", "", "1e400"]),
    "objective": st.sampled_from([None, "min-abs", "min-nonzero", "max"]),
    "no_zero": st.booleans(),
    "fixes": st.dictionaries(st.text(max_size=3) | st.sampled_from(["0", "11", "²", str(2**64)]), odd_int, max_size=3),
    "format": st.sampled_from(["json", "obj", "ply", "../x", ""]),
    "filters": st.lists(
        st.lists(odd_int | leaf | st.sampled_from(["components", "==", ">=", "in", "abs_sum"]), max_size=4), max_size=3
    ),
    "sort": st.sampled_from(["components", "abs_sum", "row", "", None]),
    "descending": st.booleans(),
    "offset": odd_int | st.integers(-5, 10**12),
    "limit": odd_int | st.integers(-5, 10**12),
}
body = st.one_of(
    st.fixed_dictionaries({"key": st.sampled_from(PLAUSIBLE[:5])}, optional=FIELDS),  # plausible shapes, odd values
    st.fixed_dictionaries({}, optional={name: anything for name in ["key", *FIELDS]}),  # anything in any field
    anything,  # not even an object
)
POSTS = ["scaffold", "design", "orbits", "clearance", "identify", "solve", "catalog", "export", "job/1/cancel"]


def answered_as_json(r):
    assert r.status_code < 500, r.text[:500]
    if r.headers["content-type"].startswith("application/json"):
        data = json.loads(r.text)  # strict JSON a page can read
        if r.status_code >= 400:
            assert set(data["error"]) == {"type", "message"} and data["error"]["message"]
    else:
        assert r.status_code == 200 and r.content


def fuzzed(n: int):
    """Hypothesis settings of a fuzz test of the server: ``n`` examples, no deadline, no health checks."""
    return hypothesis.settings(max_examples=n, deadline=None, suppress_health_check=list(hypothesis.HealthCheck))


JOB_OR_QUERY = {
    "job": st.text(min_size=1, max_size=30) | st.integers().map(str),
    "params": st.dictionaries(st.sampled_from(["name", "limit", "scaffold", "x"]), st.text(max_size=20), max_size=3),
}


def post_answers_as_json(client, path, payload):
    answered_as_json(
        client.post(f"/api/{path}", content=json.dumps(payload), headers={"Content-Type": "application/json"})
    )


def job_and_lookup_answer_as_json(client, job, params):
    answered_as_json(client.get("/api/job/" + urllib.parse.quote(job, safe="")))
    answered_as_json(client.get("/api/lookup", params=params))


# the default run sends 25 bodies to each POST and 50 job ids and queries; the slow run 80 and 150
@pytest.mark.parametrize("path", POSTS)
@fuzzed(25)
@hypothesis.given(payload=body)
def test_no_json_body_gets_a_5xx(client, path, payload):
    post_answers_as_json(client, path, payload)


@pytest.mark.slow
@pytest.mark.parametrize("path", POSTS)
@fuzzed(80)
@hypothesis.given(payload=body)
def test_no_json_body_of_many_gets_a_5xx(client, path, payload):
    post_answers_as_json(client, path, payload)


@fuzzed(50)
@hypothesis.given(**JOB_OR_QUERY)
def test_no_job_id_or_lookup_query_gets_a_5xx(client, job, params):
    job_and_lookup_answer_as_json(client, job, params)


@pytest.mark.slow
@fuzzed(150)
@hypothesis.given(**JOB_OR_QUERY)
def test_no_job_id_or_lookup_query_of_many_gets_a_5xx(client, job, params):
    job_and_lookup_answer_as_json(client, job, params)


def test_the_payloads_found_so_far(client):
    """Each once answered 500."""
    for path, payload in [
        ("design", {"key": "cube", "nulls": [10**30]}),
        ("clearance", {"key": "cube", "nulls": [-(2**64)]}),
        ("solve", {"key": "cube", "components": 1, "fixes": {"²": 1}}),
    ]:
        r = client.post(f"/api/{path}", json=payload)
        assert r.status_code in (400, 422) and r.json()["error"]["message"], r.text
    assert client.get("/api/job/²").status_code == 400
    stray = client.get("/api/job/0%2F")  # once a redirect with no body
    assert stray.status_code == 404 and stray.json()["error"]["message"], stray.text
    assert client.get("/api/lookup", params={"name": "3_1", "limit": "²"}).status_code == 400


class StubWorker:
    """A worker process and its pipe: reading the pipe (once armed) lets another thread cancel the job first (the race CI met)."""

    def __init__(self):
        self.job, self.armed, self.terminated, self.exitcode = None, False, False, None

    def is_alive(self):
        return not self.terminated

    def terminate(self):
        self.terminated, self.exitcode = True, -15

    kill = terminate

    def join(self, timeout=None):
        pass

    def poll(self):
        if self.armed:
            canceller = threading.Thread(target=self.job.cancel)
            canceller.start()
            canceller.join(timeout=0.5)  # the cancel stops the worker, then waits for this read to end
        return self.armed  # the stopped worker's pipe reads as ended

    def recv(self):
        if self.terminated:
            raise EOFError
        return ("progress", None)


def test_a_cancel_racing_a_poll_reads_as_cancelled_not_as_a_dead_worker():
    from lkspace.studio.jobs import Job

    worker = StubWorker()
    job = worker.job = Job(1, "clearance", worker, worker)
    first = job.poll().state
    worker.armed = True
    second = job.poll()
    time.sleep(0.1)
    assert (first, second.state, second.error, job.poll().state) == ("running", "cancelled", None, "cancelled")


def _half_a_message(sending):
    """A worker that dies while it sends: a message's header saying 1 MB, 10 bytes of it, then the end a moment later."""
    import os
    import struct

    os.write(sending.fileno(), struct.pack("!i", 1 << 20) + b"x" * 10)
    time.sleep(0.5)  # the server is reading by now
    os._exit(1)


def test_a_worker_that_dies_mid_message_is_read_as_stopped_not_waited_for():
    """The studio hung at Ctrl-C in CI: a read of a worker's unfinished message waited forever (the server held
    the pipe's other end too), and the shutdown waited for that read."""
    import multiprocessing

    from lkspace.studio.jobs import Job

    ctx = multiprocessing.get_context("fork")
    channel, sending = ctx.Pipe(duplex=False)
    process = ctx.Process(target=_half_a_message, args=(sending,))
    process.start()
    sending.close()  # as Jobs.start does: the worker holds the only sending end
    job = Job(1, "relax", process, channel)
    assert channel.poll(timeout=30)  # the header has come
    states = []
    reader = threading.Thread(target=lambda: states.append(job.poll()), daemon=True)
    reader.start()
    reader.join(timeout=30)
    assert not reader.is_alive(), "the read waits for a worker that has gone"
    assert (states[0].state, states[0].error) == ("error", "the worker stopped (exit code 1)")
