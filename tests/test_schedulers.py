"""Schedulers tell the truth: a named scheduler is contacted, where a run ran is said, no dashboard is served.

Through the installed CLI (``lkspace ...`` in a subprocess) and a real
``distributed.LocalCluster`` whose scheduler listens on ``tcp://``.
"""

from __future__ import annotations

import json
import os
import socket
import subprocess
import urllib.error
import urllib.request

import pytest

from lkspace.runtime.schedulers import NO_DASHBOARD, dask_client, import_distributed

pytest.importorskip("dask")


@pytest.fixture(scope="module")
def address():
    distributed = import_distributed("tests")
    import dask

    settings = {"distributed.worker.multiprocessing-method": "fork", "distributed.worker.daemon": False}
    with dask.config.set(settings):
        with distributed.LocalCluster(
            n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None, scheduler_kwargs=NO_DASHBOARD
        ) as lc:
            yield lc.scheduler_address


def closed_port() -> int:
    """A local TCP port nobody listens on (bound, then released)."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def lkspace(*args):
    return subprocess.run(["lkspace", *map(str, args)], capture_output=True, text=True)


def test_unreachable_scheduler_is_one_line_exit_2(tmp_path):
    where = f"tcp://127.0.0.1:{closed_port()}"
    for extra in ([], ["-o", tmp_path / "t.parquet"]):
        done = lkspace("enumerate", "tetrahedron", "--labels", "-1..1", "--scheduler", where, *extra)
        assert done.returncode == 2, done.stderr
        assert done.stdout == ""
        assert done.stderr.count("\n") == 1, done.stderr
        assert done.stderr.startswith(f"lkspace: error: --scheduler {where}: no Dask scheduler answers there")
    assert not (tmp_path / "t.parquet").exists()


def test_unreachable_scheduler_from_the_environment():
    where = f"tcp://127.0.0.1:{closed_port()}"
    done = subprocess.run(
        ["lkspace", "enumerate", "tetrahedron", "--labels", "-1..1", "--json"],
        capture_output=True,
        text=True,
        env={**os.environ, "DASK_SCHEDULER_ADDRESS": where},
    )
    assert done.returncode == 2
    assert json.loads(done.stdout)["error"]["message"].startswith(f"--scheduler {where}: no Dask scheduler")


def test_small_run_says_it_ran_here(address, tmp_path):
    done = lkspace("enumerate", "tetrahedron", "--labels", "-1..1", "--scheduler", address, "--json")
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    assert out["designs"] == 87 and out["ran_in"] == "this process"
    assert f"ran in this process: too small to split into parts, so --scheduler {address} answered" in done.stderr


def test_sharded_run_says_it_ran_on_dask(address, tmp_path):
    cat = tmp_path / "t"
    args = ("enumerate", "tetrahedron", "--labels", "-1..1", "--scheduler", address, "--shards", 2, "-o", cat)
    done = lkspace(*args, "--json")
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    assert out["designs"] == 87 and out["shards"] == 2 and out["ran_in"] == f"Dask at {address}"
    assert "ran in this process" not in done.stderr


def get(url: str) -> int:
    try:
        with urllib.request.urlopen(url, timeout=10) as answer:
            return int(answer.status)
    except urllib.error.HTTPError as exc:
        return int(exc.code)


def test_local_cluster_serves_no_dashboard():
    with dask_client("dask", 1) as client:
        info = client.scheduler_info()
        ports = [info["services"]["dashboard"]] + [w["services"]["dashboard"] for w in info["workers"].values()]
        assert 8787 not in ports  # the dashboard's usual port stays free
        for port in ports:
            for page in ("/status", "/health", "/metrics", "/info/main/workers.html"):
                assert get(f"http://127.0.0.1:{port}{page}") == 404, (port, page)
