"""identify's time limit counts the worker's CPU time: a busy machine answers as an idle one, only later."""

from __future__ import annotations

import os
import time

import pytest

from lkspace.knots import budget
from lkspace.knots.budget import TimeLimitReached, run_in_time

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="the time limit needs os.fork")


def waits_then_answers(stage):
    """Work that gets no CPU for a while (as on a machine whose cores are busy), then answers."""
    stage("waiting for a core")
    time.sleep(1.0)
    return "answer"


def burns(stage):
    """Work that uses CPU without end."""
    stage("spinning")
    while True:
        pass


def test_time_without_cpu_does_not_count():
    """The wall-clock limit answered 'unknown' after 0.3 s of waiting; CPU time lets the work finish."""
    assert run_in_time(waits_then_answers, 0.3) == "answer"


def test_cpu_time_past_the_limit_stops_the_work():
    with pytest.raises(TimeLimitReached) as caught:
        run_in_time(burns, 0.3)
    assert caught.value.stage == "spinning"


def test_without_proc_the_kernel_limits_cpu(monkeypatch):
    """Where /proc cannot be read, the child's RLIMIT_CPU (whole seconds) ends it with SIGXCPU."""
    monkeypatch.setattr(budget, "cpu_seconds", lambda pid: None)
    with pytest.raises(TimeLimitReached) as caught:
        run_in_time(burns, 0.3)
    assert caught.value.stage == "spinning"
    assert run_in_time(waits_then_answers, 0.3) == "answer"


def test_cpu_seconds_reads_this_process():
    used = budget.cpu_seconds(os.getpid())
    if used is None:
        pytest.skip("no /proc here")
    assert abs(used - time.process_time()) < 0.5  # the same clock, in clock ticks


def test_the_key_of_a_wide_diagram_keeps_to_the_limit():
    """``identify icosahedron --twist 3 --time-limit 0.5`` used ~3 s of CPU first: regina's Jones polynomial
    keying its 116-crossing diagram ran outside the limit; now it runs under it, and past it the design is
    named without a key (here: time is up)."""
    import numpy as np

    import lkspace

    pytest.importorskip("regina")
    scaffold = lkspace.load("icosahedron")
    lkspace.identify(scaffold, np.full(scaffold.n_edges, 1), time_limit=0.2)  # loads what any design needs
    before = os.times()
    found = lkspace.identify(scaffold, np.full(scaffold.n_edges, 3), time_limit=0.2)
    after = os.times()
    used = sum(after[:4]) - sum(before[:4])  # this process and the children it waited for
    assert found.status.startswith("unknown: time limit 0.2 s")
    assert used < 1.0, used  # regina's Jones polynomial alone takes ~3 s of CPU


def test_sharing_a_key_keeps_to_the_limit(monkeypatch):
    """Sharing a known key may simplify the diagram and take its HOMFLY-PT polynomial (regina; minutes on a
    simplified diagram of 35 crossings), which ran outside ``--time-limit``: now a diagram past 30 crossings
    shares its key in a child stopped at the limit."""
    import numpy as np

    import lkspace
    from lkspace.knots import from_labels

    pytest.importorskip("regina")
    scaffold = lkspace.load("dodecahedron")
    labels = np.full(scaffold.n_edges, 2)  # a diagram of more than 30 crossings
    lkspace.identify(scaffold, labels, time_limit=5)  # loads what any design needs

    def slow_sharing(*args, **kwargs):
        end = time.monotonic() + 30
        while time.monotonic() < end:  # CPU without end, as a long C++ call uses it (bounded: no hang)
            pass
        return [None]

    monkeypatch.setattr(from_labels, "share_names", slow_sharing)
    found = lkspace.identify(scaffold, labels, time_limit=0.3)
    assert found.status == "unknown: time limit 0.3 s reached (during naming by key)"
