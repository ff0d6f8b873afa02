"""Worker pools that never wait for ever (issue 35): ``enumerate --identify --jobs 2`` killed with SIGTERM waited
for ever on a pool whose workers the signal had killed.

The installed program runs while its workers name designs in full (they have loaded SnapPy);
then it is signalled, or one of its workers is killed.  What is asserted is behaviour: the
exit status, one line on stderr, nothing at the final name, no lock left, no worker left.
:data:`~tests.test_interruptions.HANG` seconds only detect a hang.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pytest

from lkspace.runtime.pools import WorkerLost, worker_pool
from lkspace.runtime.schedulers import run_tasks
from tests.test_interruptions import HANG, lkspace_command, send

psutil = pytest.importorskip("psutil")
pytestmark = pytest.mark.skipif(sys.platform != "linux", reason="POSIX signals, /proc")

NAMING = ["enumerate", "tetrahedron", "--labels", "-3..3", "--identify", "--jobs", "2"]
"""About 1,200 keys named in full by 2 workers (with an empty key cache): a minute and more."""


def loaded_snappy(process: psutil.Process) -> bool:
    """Whether ``process`` has SnapPy's PARI library mapped (it names designs)."""
    try:
        with open(f"/proc/{process.pid}/maps") as fh:
            return "cypari" in fh.read()
    except OSError:
        return False


def naming_workers(proc: subprocess.Popen) -> list[psutil.Process]:
    """Wait until pool workers of ``proc`` (not their own naming children) name designs; return them."""
    deadline = time.monotonic() + HANG
    while proc.poll() is None and time.monotonic() < deadline:
        family = psutil.Process(proc.pid).children(recursive=True)
        workers = [p for p in family if loaded_snappy(p) and p.ppid() != proc.pid and not loaded_snappy(p.parent())]
        if workers:
            return workers
        time.sleep(0.1)
    raise AssertionError(f"no worker named designs within {HANG} s: {proc.communicate()[1]}")


def start_naming(tmp_path) -> tuple[subprocess.Popen, list[psutil.Process]]:
    """Start the run in a process group of its own, with an empty key cache; return it once its workers name."""
    env = {**os.environ, "LKSPACE_PROGRESS": "0", "LKSPACE_CACHE": str(tmp_path / "cache")}
    proc = subprocess.Popen(
        [*lkspace_command(), *NAMING, "-o", str(tmp_path / "out.parquet")],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
        start_new_session=True,
    )
    return proc, naming_workers(proc)


def ended(proc: subprocess.Popen, workers: list[psutil.Process]) -> str:
    """Wait for the run and its workers to end (a hang fails, and is killed); return its stderr."""
    try:
        _, err = proc.communicate(timeout=HANG)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.communicate()
    _, alive = psutil.wait_procs(workers, timeout=HANG)
    assert alive == [], f"workers left running: {alive}"
    return err


def left_behind(tmp_path) -> list[str]:
    """Files the run left beside its output (its key cache aside)."""
    return sorted(name for name in os.listdir(tmp_path) if name != "cache")


@pytest.mark.parametrize(
    "signum, group",
    [(signal.SIGTERM, False), (signal.SIGTERM, True), (signal.SIGINT, True)],
    ids=["kill", "kill-group", "ctrl-c"],
)
def test_identify_stops_on_a_signal_while_workers_name(tmp_path, signum, group):
    proc, workers = start_naming(tmp_path)
    send(proc, signum, group)
    err = ended(proc, workers)
    assert proc.returncode == 128 + signum, err
    assert err.strip().splitlines() == [
        f"lkspace: error: interrupted; nothing was written to {tmp_path / 'out.parquet'}"
        " (an old catalog there is unchanged)"
    ], err
    assert left_behind(tmp_path) == []  # no output, no temporaries, no lock


@pytest.mark.parametrize("signum", [signal.SIGKILL, signal.SIGTERM])
def test_a_naming_worker_killed_ends_the_run_with_one_line(tmp_path, signum):
    """A worker dies alone (the out-of-memory killer, ``kill`` of its pid): one line, exit 1, never a wait.

    Before pools noticed dead workers, the run waited for the lost task for ever.
    """
    proc, workers = start_naming(tmp_path)
    workers[0].send_signal(signum)
    err = ended(proc, workers)
    assert proc.returncode == 1, err
    assert err.strip().splitlines() == [
        "lkspace: error: a worker process ended without an answer (killed, or out of memory?)"
    ], err
    left = left_behind(tmp_path)  # the written, not yet identified build stays for --resume
    assert all(name.startswith(".out.parquet.lkspace-build") for name in left), left  # no output, no lock


@pytest.mark.timeout(HANG)
def test_a_worker_that_dies_is_reported_not_waited_for():
    """``os._exit`` in a worker: :class:`WorkerLost` at once, for results in order and as they finish."""
    with pytest.raises(WorkerLost), worker_pool(2) as pool:
        list(pool.ordered(os._exit, [3, 3]))
    with pytest.raises(WorkerLost):
        list(run_tasks(_exit_now, None, [3, 3, 3], "local", 2))


def _exit_now(shared: None, code: int) -> None:
    os._exit(code)


@pytest.mark.timeout(HANG)
def test_a_pool_gives_every_result():
    with worker_pool(2) as pool:
        assert list(pool.ordered(abs, [-3, 2, -1])) == [3, 2, 1]
        assert sorted(pool.unordered(abs, [-3, 2, -1])) == [1, 2, 3]


SNAPPY_THEN_CTRL_C = """
import os, signal, time
from lkspace.knots.tables import knot_modules
from lkspace.runtime.workers import deferred_signals, ignored_signals
knot_modules()  # imports SnapPy, whose PARI puts in its own SIGINT handlers
with ignored_signals(), deferred_signals():
    pass
try:
    os.kill(os.getpid(), signal.SIGINT)
    time.sleep(10)
    print("lost")
except KeyboardInterrupt:
    print("interrupted")
"""


def test_ctrl_c_still_interrupts_after_snappy_and_handlers_put_back():
    """PARI's Python-level SIGINT handler, put back by ``ignored_signals``, raised nothing: Ctrl-C was lost for good."""
    done = subprocess.run([sys.executable, "-c", SNAPPY_THEN_CTRL_C], capture_output=True, text=True, timeout=HANG)
    assert done.stdout.split() == ["interrupted"], done.stderr
