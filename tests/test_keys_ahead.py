"""The next chunk keyed while this one is named: the same names whatever the chunks, and a stop that holds."""

from __future__ import annotations

import signal
import subprocess
import threading

import numpy as np
import pytest

from lkspace import load
from lkspace.knots import batch
from lkspace.knots.batch import NamerOptions, iter_names
from lkspace.knots.key_names import disk_cache
from lkspace.knots.keyed import KeyingStopped, keys_of
from lkspace.knots.keys_ahead import KeysAhead
from tests.test_interruptions import HANG, launch, send, wait_for_line

pytest.importorskip("regina")


def names(scaffold, labels) -> list[dict]:
    """Every design's row, named by key only (nothing in full, the shipped keys), through the pipelined chunks."""
    options = NamerOptions(by_key=True)
    return [row for chunk in iter_names(scaffold, labels, options, cache=disk_cache()) for row in chunk.rows()]


@pytest.mark.parametrize("name", ["tetrahedron", "cube"])
def test_designs_are_named_alike_whatever_the_chunks(monkeypatch, tmp_path, name):
    monkeypatch.setenv("LKSPACE_CACHE", str(tmp_path))
    scaffold = load(name)
    labels = np.random.default_rng(3).integers(-2, 3, size=(700, scaffold.n_edges))
    labels[5] = 99  # refused before keying: too many crossings
    whole = names(scaffold, labels)
    monkeypatch.setattr(batch, "BATCH", 37)
    chunked = names(scaffold, labels)
    assert len(whole) == len(chunked) == len(labels)
    assert chunked == whole
    assert whole[5]["error"] is not None
    assert sum(row["knot_name"] is not None for row in whole) > 100  # the comparison covers names


def test_a_set_stop_ends_keying_between_calls():
    cube = load("cube")
    stop = threading.Event()
    stop.set()
    with pytest.raises(KeyingStopped):
        keys_of(cube, np.zeros((10, cube.n_edges), np.int64), stop=stop)


def test_leaving_the_block_stops_the_keying_ahead():
    """An error while a chunk is named stops the next chunk's keying: the error goes on, no thread is left."""
    cube = load("cube")
    labels = np.random.default_rng(0).integers(-2, 3, size=(400_000, cube.n_edges))  # seconds of keying
    ahead = KeysAhead(cube, 0, None)
    with pytest.raises(ValueError, match="while naming"), ahead:
        ahead.submit(labels)
        raise ValueError("while naming")
    assert not [t for t in threading.enumerate() if t.name.startswith("lkspace-keys")]
    keyed = [f for f in ahead.futures if not f.cancelled() and f.exception() is None]
    assert len(ahead.futures) > 700 and len(keyed) <= 2  # stopped within the unit under way, not keyed to the end


@pytest.mark.parametrize("signum, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_signal_while_chunks_are_keyed_ahead_stops_the_run(tmp_path, signum, code):
    out = tmp_path / "cube.parquet"
    proc = launch(["enumerate", "cube", "--labels", "-2..2", "--identify-by-key", "-o", str(out)], progress=True)
    wait_for_line(proc, "identifying")
    send(proc, signum, group=signum == signal.SIGINT)
    try:
        _, err = proc.communicate(timeout=HANG)
    except subprocess.TimeoutExpired:
        proc.kill()
        raise
    assert proc.returncode == code, err
    errors = [line for line in err.splitlines() if line.startswith("lkspace: error:")]
    assert len(errors) == 1, err
    assert "Traceback" not in err
    assert not out.exists()


@pytest.mark.parametrize("wait", [False, True])
def test_the_caller_and_the_thread_share_a_chunk_and_join_it_in_order(monkeypatch, wait):
    """Units keyed by the caller (from the back) and by the thread (from the front) join to keys_of's keys exactly."""
    from lkspace.knots import keys_ahead

    gate = threading.Event()  # the thread waits in its first unit until the caller keys one (or, waiting, at once)
    real = keys_ahead.key_part

    def gated(tmpl, unit):
        if threading.current_thread().name.startswith("lkspace-keys"):
            assert gate.wait(HANG)
        else:
            gate.set()
        return real(tmpl, unit)

    monkeypatch.setattr(keys_ahead, "UNIT", 7)
    monkeypatch.setattr(keys_ahead, "key_part", gated)
    cube = load("cube")
    labels = np.random.default_rng(1).integers(-2, 3, size=(300, cube.n_edges))
    whole = keys_of(cube, labels)
    with KeysAhead(cube, 0, None) as ahead:
        ahead.submit(labels)
        if wait:
            gate.set()
            ahead.futures[-1].result()  # the thread keyed every unit
        found = ahead.result()
    cancelled = [f.cancelled() for f in ahead.futures]
    assert cancelled[-1] is not wait and not cancelled[0]  # the caller keyed the last unit itself unless it waited
    for name in ("keys", "crossings", "components", "keyed", "link_offsets", "link_values", "free", "jones_at"):
        assert np.array_equal(getattr(found, name), getattr(whole, name)), name
