"""Ctrl-C, SIGTERM and SIGKILL of the installed ``lkspace enumerate --jobs 2``: prompt stop, nothing lost.

The command runs as a real process (its workers too) and is stopped at seeded random
moments; then ``--resume`` (in this process, with another ``--jobs``) must give the
same rows as an uninterrupted run: none lost, none duplicated.
"""

from __future__ import annotations

import os
import random
import shutil
import signal
import subprocess
import sys
import time

import pyarrow.parquet as pq
import pytest

from lkspace.cli import main

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")

SPACE = ["enumerate", "cube", "--labels", "-1..2", "--shards", "4"]  # 703,760 designs, a few seconds


def lkspace_command() -> list[str]:
    exe = shutil.which("lkspace")
    return [exe] if exe else [sys.executable, "-m", "lkspace"]


def sorted_keys(path) -> list[bytes]:
    table = pq.read_table(path, columns=["key"])  # what pandas and pyarrow see at the final name
    return sorted(table.column("key").to_pylist())


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    out = tmp_path_factory.mktemp("ref") / "ref.parquet"
    assert main([*SPACE, "-o", str(out)]) == 0
    return sorted_keys(out)


def start(out):
    """Start the run and return once it is writing (its build folder exists), so that a slow
    start-up on a loaded machine does not turn a signal meant for the run into one for start-up."""
    env = {**os.environ, "LKSPACE_PROGRESS": "0"}
    proc = subprocess.Popen(
        [*lkspace_command(), *SPACE, "--jobs", "2", "-o", str(out)], stderr=subprocess.PIPE, text=True, env=env
    )
    build = out.parent / f".{out.name}.lkspace-build"
    deadline = time.monotonic() + 60
    while not build.exists() and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.02)
    return proc


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM, signal.SIGKILL])
def test_stop_at_random_points_then_resume(tmp_path, capsys, reference, signum):
    rng = random.Random(int(signum))
    out = tmp_path / "cube.parquet"
    for delay in sorted(rng.uniform(0.0, 3.0) for _ in range(2)):  # seconds into the writing
        shutil.rmtree(out, ignore_errors=True)
        proc = start(out)
        time.sleep(delay)
        sent = time.monotonic()
        proc.send_signal(signum)
        _, err = proc.communicate(timeout=30)
        waited = time.monotonic() - sent
        if out.exists():  # finished before the signal: complete (or else absent)
            assert sorted_keys(out) == reference
            continue
        if signum != signal.SIGKILL:
            assert waited < 2.0, f"stopped {waited:.2f} s after the signal"
            assert proc.returncode == 128 + signum, err
            assert err.strip().splitlines()[-1].startswith("lkspace: error: interrupted"), err
            assert "Traceback" not in err
        assert main([*SPACE, "-o", str(out), "--resume"]) == 0, capsys.readouterr().err
        keys = sorted_keys(out)
        assert len(keys) == len(set(keys)) == len(reference) and keys == reference  # none lost, none twice
        assert sorted(os.listdir(tmp_path)) == ["cube.parquet"]  # no temporaries, no lock


@pytest.mark.parametrize(
    "signum, code, word", [(signal.SIGINT, 130, "interrupted"), (signal.SIGTERM, 143, "terminated")]
)
def test_any_command_stops_on_a_signal(signum, code, word):
    """Not only enumerate: a long solve stops at once, one line, 130 for Ctrl-C and 143 for SIGTERM."""
    argv = [*lkspace_command(), "solve", "honeycomb:cP@4x4x4", "-n", "3", "--count", "10000", "--time-limit", "60"]
    proc = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    time.sleep(3)
    sent = time.monotonic()
    proc.send_signal(signum)
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == code and time.monotonic() - sent < 2, err  # the solve alone runs for a minute
    errors = [line for line in err.splitlines() if line.startswith("lkspace: error:")]
    assert errors == [f"lkspace: error: {word}"] and "Traceback" not in err
