"""Catalogs and counts on Dask: the same rows from every scheduler, a worker lost mid-run, fsspec URLs.

A real ``distributed.LocalCluster`` (2 worker processes, one thread each) serves the
``tcp://`` tests; ``--scheduler dask`` starts its own through the installed CLI.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import pandas as pd
import pytest

from lkspace import Execution, Selection, load, write_catalog
from lkspace.catalog.transaction import MANIFEST, load_manifest, save_manifest
from lkspace.design.census import census
from lkspace.design.counting import count_space
from lkspace.design.space import make_space
from lkspace.errors import UsageError
from lkspace.runtime.schedulers import import_distributed, resolve_scheduler

pytest.importorskip("dask")


@pytest.fixture(scope="module")
def cluster():
    distributed = import_distributed("tests")
    import dask

    settings = {"distributed.worker.multiprocessing-method": "fork", "distributed.worker.daemon": False}
    with dask.config.set(settings):
        with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as lc:
            yield lc.scheduler_address


def rows(path):
    df = pd.read_parquet(path)
    return df.sort_values("key").reset_index(drop=True)


def same(a, b):
    pd.testing.assert_frame_equal(rows(a), rows(b))


def test_resolve_scheduler(monkeypatch):
    monkeypatch.delenv("DASK_SCHEDULER_ADDRESS", raising=False)
    assert resolve_scheduler(None) == "local"
    monkeypatch.setenv("DASK_SCHEDULER_ADDRESS", "tcp://10.1.2.3:8786")
    assert resolve_scheduler(None) == "tcp://10.1.2.3:8786"
    assert resolve_scheduler("dask") == "dask"
    with pytest.raises(UsageError, match="^scheduler 'yarn'") as refused:
        resolve_scheduler("yarn")
    assert refused.value.parameter == "scheduler"


def test_same_rows_from_every_scheduler(tmp_path, cluster):
    space = make_space(load("honeycomb:hP"), "-2..2")  # periodic, degrees 3 and 4
    one = write_catalog(space, tmp_path / "one.parquet")
    pool = write_catalog(space, tmp_path / "pool", execution=Execution(shards=4, jobs=2))
    on_dask = write_catalog(space, tmp_path / "dask", execution=Execution(shards=4, jobs=2, scheduler=cluster))
    assert one.designs == pool.designs == on_dask.designs == count_space(space).designs
    assert on_dask.by_components == one.by_components
    same(tmp_path / "one.parquet", tmp_path / "pool")
    same(tmp_path / "one.parquet", tmp_path / "dask")
    manifest = load_manifest(str(tmp_path / "dask"))
    assert manifest is not None and manifest.complete and len(manifest.parts) == 4
    assert sorted(os.listdir(tmp_path / "dask")) == sorted([MANIFEST, *(p.file for p in manifest.parts.values())])


def test_resume_on_dask(tmp_path, cluster):
    space = make_space(load("cube"), "-1..1")
    first = write_catalog(space, tmp_path / "c", execution=Execution(shards=3))
    # turn the finished catalog back into an interrupted build that lacks part 1
    build = tmp_path / ".c.lkspace-build"
    shutil.move(tmp_path / "c", build)
    manifest = load_manifest(str(build))
    assert manifest is not None
    kept = {i: part for i, part in manifest.parts.items() if i != 1}
    os.remove(build / str(manifest.parts[1].file))
    save_manifest(str(build), replace(manifest, parts=kept, complete=False))
    again = write_catalog(space, tmp_path / "c", execution=Execution(shards=3, resume=True, scheduler=cluster))
    assert again.shards_resumed == 2 and again.designs == first.designs
    assert not build.exists()
    assert len(pd.read_parquet(tmp_path / "c")) == first.designs


def test_cli_local_cluster_survives_a_killed_worker(tmp_path):
    """The first part to start kills its own worker process (SIGKILL, injected by tests/faults.py); Dask runs it again elsewhere."""
    flag = tmp_path / "killed"
    out = tmp_path / "cube"
    cmd = [sys.executable, "-m", "tests.faults", str(flag), "enumerate", "cube", "--labels", "-1..1", "-o", str(out)]
    done = subprocess.run(
        [*cmd, "--shards", "4", "--scheduler", "dask", "--jobs", "2", "--json"],
        cwd=Path(__file__).parents[1],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    assert flag.exists()  # a worker really died
    assert json.loads(done.stdout)["designs"] == 22_815
    write_catalog(make_space(load("cube"), "-1..1"), tmp_path / "ref.parquet")
    same(tmp_path / "ref.parquet", out)
    manifest = load_manifest(str(out))
    assert manifest is not None
    assert sorted(os.listdir(out)) == sorted([MANIFEST, *(p.file for p in manifest.parts.values())])


def test_identify_pass_on_dask(tmp_path, cluster):
    pytest.importorskip("snappy")
    space = make_space(load("tetrahedron"), "-2,2")
    local = write_catalog(space, tmp_path / "a", selection=Selection(identify=True), execution=Execution(shards=2))
    on_dask = write_catalog(
        space, tmp_path / "b", selection=Selection(identify=True), execution=Execution(shards=2, scheduler=cluster)
    )
    assert local.identified == on_dask.identified and on_dask.identified.rows == 12
    assert on_dask.identified.named >= 6  # L12a2007, L12n2205, L12n2211 (HTLinkExteriors): decided in a main thread
    cols = ["key", "knot_name", "identify_error"]  # crossings: of a simplified diagram, may differ by process
    pd.testing.assert_frame_equal(rows(tmp_path / "a")[cols], rows(tmp_path / "b")[cols])


@pytest.mark.filterwarnings("ignore:The inplace keyword:DeprecationWarning")  # dask's own call into pandas
@pytest.mark.filterwarnings("ignore:The inplace keyword")
def test_memory_url_reads_back_with_pandas_and_dask(tmp_path):
    import_distributed("tests")
    import dask.dataframe as dd
    import fsspec
    import pyarrow.parquet as pq

    space = make_space(load("honeycomb:cF"), "-2..2")
    local = write_catalog(space, tmp_path / "cf.parquet")
    folder = write_catalog(space, "memory://lk/cf", execution=Execution(shards=3))
    single = write_catalog(space, "memory://lk/cf.parquet")
    assert folder.designs == single.designs == local.designs and folder.output == "memory://lk/cf"
    same(tmp_path / "cf.parquet", "memory://lk/cf")
    same(tmp_path / "cf.parquet", "memory://lk/cf.parquet")
    frame = dd.read_parquet("memory://lk/cf").compute(scheduler="sync")
    assert len(frame) == local.designs
    fs = fsspec.filesystem("memory")
    manifest = json.loads(fs.cat("/lk/cf/" + MANIFEST))
    assert manifest["complete"] and len(manifest["parts"]) == 3
    part = fs.open("/lk/cf/" + manifest["parts"]["0"]["file"])
    assert json.loads(pq.read_schema(part).metadata[b"lkspace"])["label_set"] == [-2, -1, 0, 1, 2]
    # resume keeps the parts that are there
    fs.rm("/lk/cf/" + manifest["parts"]["2"]["file"])
    again = write_catalog(space, "memory://lk/cf", execution=Execution(shards=3, resume=True))
    assert again.shards_resumed == 2
    same(tmp_path / "cf.parquet", "memory://lk/cf")
    with pytest.raises(UsageError, match="memory://"):
        write_catalog(space, "memory://lk/x", execution=Execution(shards=2, jobs=2))


def test_census_on_dask_equals_local(cluster):
    space = make_space(load("voronoi:cube-faces"), "-1..1")
    want = count_space(space).by_components
    assert census(space, cluster, 2, shard_choices=5000).by_components == want


@pytest.mark.filterwarnings("ignore::ResourceWarning")  # sockets distributed leaves to the collector
@pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning")
def test_worker_started_with_the_lkspace_entry_point(tmp_path):
    """``python -m lkspace.dask_worker`` joins a scheduler and runs tasks although SnapPy is installed."""
    import sys

    distributed = import_distributed("tests")
    with distributed.LocalCluster(n_workers=0, processes=False, protocol="tcp", dashboard_address=":0") as lc:
        cmd = [sys.executable, "-m", "lkspace.dask_worker", lc.scheduler_address, "--nworkers", "1", "--nthreads", "1"]
        worker = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            with distributed.Client(lc) as client:
                client.wait_for_workers(1, timeout=60)
            space = make_space(load("cube"), "-1..1")
            assert (
                census(space, lc.scheduler_address, 1, shard_choices=2000).by_components
                == count_space(space).by_components
            )
        finally:
            worker.terminate()
            worker.wait(timeout=30)


def test_missing_dask_is_one_clear_line(tmp_path):
    import sys

    code = (
        "import sys; sys.modules['dask'] = None; sys.modules['distributed'] = None\n"
        "from lkspace.cli import main\n"
        f"sys.exit(main(['enumerate', 'cube', '--labels', '-1..1', '--shards', '2', '-o', {str(tmp_path / 'c')!r},"
        " '--scheduler', 'dask']))"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 1, done.stderr
    assert (
        done.stderr.strip().splitlines()[-1].startswith("lkspace: error: --scheduler dask needs the optional package")
    )
    assert "lkspace[dask]" in done.stderr and "Traceback" not in done.stderr
    assert not (tmp_path / "c").exists()
