"""Catalogs are transactions: complete or absent, old kept until the new is whole, one writer, checked resume."""

from __future__ import annotations

import json
import os
import socket
import subprocess
import sys

import pandas as pd
import pytest

import lkspace
import lkspace.catalog.jobs as jobs
from lkspace.catalog.transaction import CatalogInterrupted
from lkspace.cli import main

from .cli_calls import run

CUBE = ["enumerate", "cube", "--labels", "-1..1", "--shards", "3"]


def interrupt_part(monkeypatch, n):
    """Make the part written ``n``-th (from 1) stop with Ctrl-C after its first batch."""
    real = jobs.space_batches
    calls = {"n": 0}

    def flaky(*args, **kwargs):
        calls["n"] += 1
        if calls["n"] == n:

            def broken():
                yield from list(real(*args, **kwargs))[:1]
                raise KeyboardInterrupt

            return broken()
        return real(*args, **kwargs)

    monkeypatch.setattr(jobs, "space_batches", flaky)  # every part's batches, in this process or a file of one
    return lambda: monkeypatch.setattr(jobs, "space_batches", real)


def rows(path):
    cat = lkspace.read_catalog(path)
    frame = cat.frame.assign(key=[bytes(r) for r in cat.labels.view("uint8")])
    return frame.sort_values("key").reset_index(drop=True)


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    path = tmp_path_factory.mktemp("ref") / "cube.parquet"
    assert main([*CUBE, "-o", str(path)]) == 0
    return rows(path)


def test_interrupted_run_leaves_nothing_and_resumes_with_other_jobs(tmp_path, capsys, monkeypatch, reference):
    out = tmp_path / "c.parquet"
    restore = interrupt_part(monkeypatch, 3)
    code, _, err = run(capsys, *CUBE, "-o", out, "--json")
    assert code == 130 and "2 of 3 parts are finished" in err and "--resume" in err
    assert len(err.strip().splitlines()) == 1 and not out.exists()
    restore()
    code, got, _ = run(capsys, *CUBE, "-o", out, "--resume", "--jobs", "2", "--json")
    assert code == 0 and json.loads(got)["shards_resumed"] == 2
    pd.testing.assert_frame_equal(rows(out), reference)
    assert sorted(os.listdir(tmp_path)) == ["c.parquet"]


def test_python_caller_is_cleaned_up_after_ctrl_c_and_told_how_to_resume(tmp_path, monkeypatch, reference):
    out = tmp_path / "c.parquet"
    restore = interrupt_part(monkeypatch, 2)
    with pytest.raises(CatalogInterrupted, match=r"^interrupted; 1 of 3 parts are finished in .*resume=True") as stop:
        lkspace.write_catalog("cube", out, "-1..1", execution=lkspace.Execution(shards=3))
    assert stop.value.resumable and stop.value.exit_code == 130 and "--" not in str(stop.value)
    assert sorted(os.listdir(tmp_path)) == [".c.parquet.lkspace-build"]  # the finished part, no temporaries, no lock
    assert len(os.listdir(tmp_path / ".c.parquet.lkspace-build")) == 2  # the manifest and the one finished part
    restore()
    again = lkspace.write_catalog("cube", out, "-1..1", execution=lkspace.Execution(shards=3, resume=True))
    assert again.shards_resumed == 1
    pd.testing.assert_frame_equal(rows(out), reference)


def test_rerun_keeps_the_old_catalog_until_the_new_is_complete(tmp_path, capsys, monkeypatch, reference):
    out = tmp_path / "c.parquet"
    assert run(capsys, *CUBE, "-o", out)[0] == 0
    restore = interrupt_part(monkeypatch, 1)
    code, _, err = run(capsys, "enumerate", "cube", "--labels", "-1,1", "-o", out)  # one file, stopped midway
    assert code == 130 and "old catalog there is unchanged" in err
    pd.testing.assert_frame_equal(rows(out), reference)  # the old catalog, whole
    restore()
    assert run(capsys, "enumerate", "cube", "--labels", "-1,1", "-o", out)[0] == 0
    assert out.is_file() and len(pd.read_parquet(out)) == len(lkspace.read_catalog(out)) == 218
    assert sorted(os.listdir(tmp_path)) == ["c.parquet"]


def test_corrupted_and_foreign_parts_are_redone(tmp_path, capsys, monkeypatch, reference):
    out = tmp_path / "c.parquet"
    restore = interrupt_part(monkeypatch, 3)
    assert run(capsys, *CUBE, "-o", out)[0] == 130
    restore()
    build = tmp_path / ".c.parquet.lkspace-build"
    first, second = sorted(build.glob("part-*.parquet"))
    data = bytearray(first.read_bytes())  # bytes overwritten in the middle: the footer stays intact
    data[len(data) // 2 : len(data) // 2 + 64] = b"\x07" * 64
    first.write_bytes(bytes(data))
    other = tmp_path / "octa.parquet"
    assert run(capsys, "enumerate", "octahedron", "--labels", "-1..1", "-o", other)[0] == 0
    second.write_bytes(other.read_bytes())  # a part of another scaffold under a finished part's name
    (build / "part-00002-ffffffff.parquet").write_bytes(other.read_bytes())  # and a stray one
    (build / ".part-00002-x.parquet.abc.parquet.tmp").write_bytes(b"partial")
    (tmp_path / "..c.parquet.lkspace-build.xyz.parquet.tmp").write_bytes(b"partial")
    code, got, _ = run(capsys, *CUBE, "-o", out, "--resume", "--json")
    assert code == 0 and json.loads(got)["shards_resumed"] == 0
    pd.testing.assert_frame_equal(rows(out), reference)  # row for row
    assert len(pd.read_parquet(out)) == len(reference)  # pandas sees no foreign rows either
    assert sorted(os.listdir(tmp_path)) == ["c.parquet", "octa.parquet"]


def test_resume_of_a_finished_catalog_checks_its_parts(tmp_path, capsys, reference):
    out = tmp_path / "c.parquet"
    assert run(capsys, *CUBE, "-o", out)[0] == 0
    part = sorted(out.glob("part-*.parquet"))[1]
    data = bytearray(part.read_bytes())
    data[100:120] = b"\x00" * 20
    part.write_bytes(bytes(data))
    code, got, _ = run(capsys, *CUBE, "-o", out, "--resume", "--json")
    assert code == 0 and json.loads(got)["shards_resumed"] == 2
    pd.testing.assert_frame_equal(rows(out), reference)


def test_lock_stops_a_second_writer_and_a_stale_lock_is_taken_over(tmp_path, capsys):
    out = tmp_path / "t.parquet"
    lock = tmp_path / ".t.parquet.lkspace-lock"
    with subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"]) as other:
        lock.write_text(json.dumps({"pid": other.pid, "host": socket.gethostname(), "started": "now"}))
        code, _, err = run(capsys, "enumerate", "tetrahedron", "-o", out)
        other.kill()
    assert code == 1 and f"pid {other.pid}" in err and "another lkspace run" in err and not out.exists()
    code, _, err = run(capsys, "enumerate", "tetrahedron", "-o", out)  # its pid is gone: a stale lock
    assert code == 0 and out.is_file() and not lock.exists()


@pytest.mark.parametrize(
    "record",
    [
        {"pid": 2**70, "host": socket.gethostname(), "started": "now"},  # os.kill: OverflowError
        "[" * 100_000,  # json.load: RecursionError
        {"pid": True, "host": socket.gethostname()},
    ],
    ids=["huge-pid", "deep", "bool-pid"],
)
def test_a_lock_file_that_is_no_lock_record_is_one_line(tmp_path, capsys, record):
    """A lock file holding a pid past a C long or JSON nested past the stack was an internal error."""
    lock = tmp_path / ".t.parquet.lkspace-lock"
    lock.write_text(record if isinstance(record, str) else json.dumps(record))
    code, _, err = run(capsys, "enumerate", "tetrahedron", "-o", tmp_path / "t.parquet")
    assert code == 1
    assert err.count("\n") == 1
    assert "another lkspace run is writing this catalog (a run that is starting)" in err
    assert sorted(os.listdir(tmp_path)) == [lock.name]


@pytest.mark.parametrize(
    "output, message",
    [
        ("", "empty"),
        ("t.csv", "ending in .parquet"),
        ("t.json", "ending in .parquet"),
        ("missing/t.parquet", "does not exist"),
        ("file.txt/t.parquet", "is not a folder"),
        ("dev.parquet", "symbolic link"),
    ],
)
def test_bad_outputs_are_one_line(tmp_path, capsys, output, message):
    (tmp_path / "file.txt").write_text("x")
    os.symlink("/dev/null", tmp_path / "dev.parquet")
    target = str(tmp_path / output) if output else ""
    code, _, err = run(capsys, "enumerate", "tetrahedron", "-o", target)
    assert code == 2 and message in err and len(err.strip().splitlines()) == 1
    assert os.path.islink(tmp_path / "dev.parquet") and sorted(os.listdir(tmp_path)) == ["dev.parquet", "file.txt"]


def test_read_only_folder_is_one_line(tmp_path, capsys):
    if os.geteuid() == 0:
        pytest.skip("root writes in read-only folders")
    tmp_path.chmod(0o555)
    try:
        code, _, err = run(capsys, "enumerate", "tetrahedron", "-o", tmp_path / "t.parquet")
    finally:
        tmp_path.chmod(0o755)
    assert code == 2 and "cannot write" in err


def test_a_symlink_is_refused_and_its_target_kept(tmp_path, capsys):
    assert run(capsys, "enumerate", "tetrahedron", "--labels", "-2,2", "-o", tmp_path / "real.parquet")[0] == 0
    os.symlink("real.parquet", tmp_path / "link.parquet")
    code, _, err = run(capsys, "enumerate", "tetrahedron", "--labels", "-1,1", "-o", tmp_path / "link.parquet")
    assert code == 2 and "symbolic link (to real.parquet)" in err
    assert os.path.islink(tmp_path / "link.parquet") and len(pd.read_parquet(tmp_path / "real.parquet")) == 12


@pytest.mark.parametrize(
    "args, message",
    [
        (["cube", "--labels", "-100..100"], "past what lkspace writes"),
        (["cube", "--labels", "-3..3"], "pass --yes"),
        (["cube", "--jobs", str(10**30)], "--jobs"),
        (["cube", "--shards", str(10**30)], "--shards"),
    ],
)
def test_bounds_before_work(tmp_path, capsys, args, message):
    code, _, err = run(capsys, "enumerate", *args, "-o", tmp_path / "x.parquet")
    assert code == 2 and message in err and len(err.strip().splitlines()) == 1
    assert os.listdir(tmp_path) == []


def test_spanning_tree_residue_class_past_int64_is_null(tmp_path, capsys):
    out = tmp_path / "x.parquet"
    args = ["tiling:square@8x8", "--mode", "spanning-trees", "--sample", "3", "--symmetry", "none", "-o", out]
    code, _, err = run(capsys, "enumerate", *args)
    assert code == 0, err
    df = pd.read_parquet(out)
    assert len(df) == 3 and df.residue_class.isna().all() and (df.components == 1).all()
