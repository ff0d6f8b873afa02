"""The studio's boundary records: every request's one ``from_json`` takes any JSON and answers a record or a
one-line error naming a field; answers write the keys the page has always read, in its order."""

import json

import numpy as np
import pytest

pytest.importorskip("starlette")

from lkspace.errors import LkspaceError
from lkspace.studio import requests as rq
from lkspace.studio.answers import Clearance, IdentifyAnswer, JobProgress, JobStarted, JobState, RelaxedCurves
from lkspace.studio.wire import fail

hypothesis = pytest.importorskip("hypothesis")
st = hypothesis.strategies

RECORDS = [
    rq.ScaffoldRequest,
    rq.DesignRequest,
    rq.RedrawRequest,
    rq.DiagramRequest,
    rq.ExportRequest,
    rq.DesignFileRequest,
    rq.SolveRequest,
    rq.JobRequest,
    rq.CatalogRequest,
    rq.LookupRequest,
    rq.ThumbnailsRequest,
]
FIELDS = ["key", "labels", "nulls", "block", "relax", "have", "view", "format", "components", "label_set"]
FIELDS += ["no_zero", "fixes", "objective", "count", "time_limit", "id", "filters", "sort", "descending"]
FIELDS += ["offset", "limit", "name", "scaffold", "designs", "names"]
leaf = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(-3, 40),
    st.sampled_from([10**30, -(2**64), "cube", "1", "²", "", "min-abs", "-2..2", "json", "=="]),
    st.floats(allow_nan=False),
    st.text(max_size=8),
)
anything = st.recursive(
    leaf, lambda kids: st.lists(kids, max_size=4) | st.dictionaries(st.text(max_size=4), kids, max_size=3), max_leaves=6
)


@pytest.mark.parametrize("record", RECORDS, ids=lambda r: r.__name__)
@hypothesis.settings(max_examples=50, deadline=None)
@hypothesis.given(body=st.fixed_dictionaries({}, optional=dict.fromkeys(FIELDS, anything)))  # every field, odd values
def test_from_json_answers_a_record_or_a_one_line_error_naming_a_field(record, body):
    try:
        parsed = record.from_json(body)
    except LkspaceError as exc:
        refused = exc
    else:
        refused = None
    if refused is not None:
        assert str(refused) and "\n" not in str(refused)
        assert fail(refused).status_code < 500
        return
    assert isinstance(parsed, record)
    with pytest.raises(AttributeError):  # frozen
        parsed.x = 1


def test_a_well_formed_body_reads_as_the_page_sends_it():
    redraw = rq.RedrawRequest.from_json(
        {"key": "cube", "labels": [1, "-9007199254740993"], "nulls": [0], "have": ["a"]}
    )
    assert redraw.design == rq.DesignRequest("cube", (1, -9007199254740993), (0,), None)
    assert redraw.have == frozenset({"a"}) and not redraw.relax
    solve = rq.SolveRequest.from_json({"key": "cube", "components": 1, "fixes": {"3": -2}, "objective": None})
    assert solve.options() == {
        "components": 1,
        "label_set": "-2..2",
        "no_zero": False,
        "fixes": {3: -2},
        "objective": None,
    }
    assert (solve.count, solve.time_limit) == (5, 60.0)
    assert rq.JobRequest.from_json({"id": "12"}) == rq.JobRequest(12)
    assert rq.LookupRequest.from_json({"name": "3_1", "limit": "3"}) == rq.LookupRequest("3_1", 3, None)
    with pytest.raises(LkspaceError, match="^relax: true or false$"):
        rq.RedrawRequest.from_json({"key": "cube", "relax": "yes"})
    with pytest.raises(LkspaceError, match="^labels: item 1: '1.5' is not an integer$"):
        rq.DesignRequest.from_json({"key": "cube", "labels": [1, 1.5]})


def test_answers_write_the_keys_the_page_reads_in_its_order():
    state = JobState(3, "identify", "running", 1.5, JobProgress("identifying cube", "", "jones"))
    assert list(state.to_json()) == ["id", "kind", "state", "elapsed", "progress", "result", "error"]
    assert JobState(3, "solve", "cancelled", 0.0).to_json()["progress"] == {}
    named = IdentifyAnswer("3_1", "trefoil", "identified", 1, [[0]], False, False, 3)
    assert list(named.to_json()) == [
        *("name", "common_name", "status", "components", "linking_matrix", "mirror", "split", "crossings"),
        "least_crossings",
    ]
    assert JobStarted(None, "periodic").to_json() == {"job": None, "message": "periodic"}
    assert JobStarted(4).to_json() == {"job": 4}
    far = Clearance(0.5, 0.1, 2, (0, 1))
    assert far.to_json() == {"min_distance": 0.5, "min_separation": 0.1, "ok": True, "edge": 2, "curves": [0, 1]}
    assert list(Clearance(0.01, 0.1, 2, (0, 1), "too close").to_json())[-1] == "message"
    curves = (np.arange(6.0).reshape(2, 3), np.ones((1, 3)))
    relaxed = RelaxedCurves(curves, 0.1, 0.3, None).to_json()
    assert relaxed["counts"] == [2, 1] and relaxed["closest"] == {} and json.dumps(relaxed)
