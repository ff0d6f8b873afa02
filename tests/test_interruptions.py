"""Ctrl-C, SIGTERM and SIGKILL of the installed ``lkspace``: a prompt clean stop, nothing lost.

Each command runs as a real process (its workers too) and is stopped once it is known to
be working (a build folder, a progress line), or at seeded random moments after that.
Ctrl-C is sent as a terminal sends it, to the whole process group: the fork server and
the workers get it too, and must leave it to the main process.  Then ``--resume`` (in
this process, with another ``--jobs``) must give the same rows as an uninterrupted run:
none lost, none duplicated.

What is asserted is behaviour: the exit status, one line on stderr, no traceback (of the
main process, a worker or the fork server), nothing at the final name.  How long a stop
takes is measured under load by ``experiments/bench_interrupt.py``; here a generous
timeout only detects a hang.
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
HANG = 60
"""Seconds after a signal before a command counts as hung (a stop takes well under 2 s; the machine may be loaded)."""


def lkspace_command() -> list[str]:
    exe = shutil.which("lkspace")
    return [exe] if exe else [sys.executable, "-m", "lkspace"]


def sorted_keys(path) -> list[bytes]:
    table = pq.read_table(path, columns=["key"])  # what pandas and pyarrow see at the final name
    return sorted(table.column("key").to_pylist())


def launch(args, progress: bool = False) -> subprocess.Popen:
    """Start ``lkspace ARGS`` in a process group of its own (as a shell starts a job)."""
    env = {**os.environ, "LKSPACE_PROGRESS": "1" if progress else "0"}
    return subprocess.Popen(
        [*lkspace_command(), *args],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
        start_new_session=True,
    )


def send(proc: subprocess.Popen, signum: int, group: bool) -> None:
    """Send ``signum`` to the process group (a terminal's Ctrl-C) or to the main process only (``kill PID``)."""
    if group:
        os.killpg(proc.pid, signum)
    else:
        proc.send_signal(signum)


def wait_for_line(proc: subprocess.Popen, text: str) -> list[str]:
    """Read stderr until a line holding ``text``; return the lines read."""
    lines = []
    for line in proc.stderr:
        lines.append(line)
        if text in line:
            return lines
    raise AssertionError(f"the command ended before printing {text!r}: {''.join(lines)}")


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    out = tmp_path_factory.mktemp("ref") / "ref.parquet"
    assert main([*SPACE, "-o", str(out)]) == 0
    return sorted_keys(out)


def start(out):
    """Start the run and return once it is writing (its build folder exists), so that a slow
    start-up on a loaded machine does not turn a signal meant for the run into one for start-up."""
    proc = launch([*SPACE, "--jobs", "2", "-o", str(out)])
    build = out.parent / f".{out.name}.lkspace-build"
    deadline = time.monotonic() + HANG
    while not build.exists() and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.02)
    return proc


@pytest.mark.parametrize(
    "signum, group",
    [
        (signal.SIGINT, True),
        (signal.SIGTERM, False),
        pytest.param(signal.SIGTERM, True, marks=pytest.mark.slow),
        (signal.SIGKILL, False),
    ],
    ids=["ctrl-c", "kill", "kill-group", "kill-9"],
)
def test_stop_at_random_points_then_resume(tmp_path, capsys, reference, signum, group):
    rng = random.Random(int(signum) + 100 * group)
    out = tmp_path / "cube.parquet"
    for delay in sorted(rng.uniform(0.0, 3.0) for _ in range(2)):  # seconds into the writing
        shutil.rmtree(out, ignore_errors=True)
        proc = start(out)
        time.sleep(delay)
        send(proc, signum, group)
        _, err = proc.communicate(timeout=HANG)
        if out.exists():  # finished before the signal: complete (or else absent)
            assert sorted_keys(out) == reference
            continue
        if signum != signal.SIGKILL:
            assert proc.returncode == 128 + signum, err
            lines = err.strip().splitlines()  # one line: nothing from a worker or the fork server
            assert len(lines) == 1 and lines[0].startswith("lkspace: error: interrupted"), err
        assert main([*SPACE, "-o", str(out), "--resume"]) == 0, capsys.readouterr().err
        keys = sorted_keys(out)
        assert len(keys) == len(set(keys)) == len(reference) and keys == reference  # none lost, none twice
        assert sorted(os.listdir(tmp_path)) == ["cube.parquet"]  # no temporaries, no lock


@pytest.mark.parametrize(
    "signum, code, word", [(signal.SIGINT, 130, "interrupted"), (signal.SIGTERM, 143, "terminated")]
)
def test_any_command_stops_on_a_signal(signum, code, word):
    """Not only enumerate: a solve that would run for a minute stops once it is solving, one line, 130 or 143."""
    argv = ["solve", "honeycomb:cP@4x4x4", "-n", "3", "--count", "10000", "--time-limit", "60"]
    proc = launch(argv, progress=True)
    wait_for_line(proc, "lkspace: solving honeycomb:cP@4x4x4")
    send(proc, signum, group=signum == signal.SIGINT)
    _, err = proc.communicate(timeout=HANG)
    assert proc.returncode == code, err  # not 0: the signal, not the time limit, ended the solve
    errors = [line for line in err.splitlines() if line.startswith("lkspace: error:")]
    assert errors == [f"lkspace: error: {word}"] and "Traceback" not in err, err


@pytest.mark.parametrize(
    "signum, code, word", [(signal.SIGINT, 130, "interrupted"), (signal.SIGTERM, 143, "terminated")]
)
def test_solve_type_on_a_users_mesh_stops_on_a_signal(tmp_path, signum, code, word):
    """``solve MESH --type NAME`` on a user's OBJ (issue 35: SIGTERM ignored for 14 min): stops once it searches."""
    from tests.test_solve_user_mesh import prism_obj

    mesh = prism_obj(tmp_path / "prism6.obj", 6)
    proc = launch(["solve", mesh, "--type", "13a_1", "--labels", "-2..2", "--time-limit", "600"], progress=True)
    wait_for_line(proc, "designs screened")
    send(proc, signum, group=signum == signal.SIGINT)
    _, err = proc.communicate(timeout=HANG)
    assert proc.returncode == code, err  # the signal ended it: the time limit is ten minutes away
    errors = [line for line in err.splitlines() if line.startswith("lkspace: error:")]
    assert errors == [f"lkspace: error: {word}"] and "Traceback" not in err, err


NAMEDTUPLE_KERNEL = """
import os, signal, threading
import numpy as np
import lkspace
from lkspace.knots.keyed import keys_of

scaffold = lkspace.load("cube")
labels = np.random.default_rng(0).integers(-2, 3, size=(5_000, scaffold.n_edges))
keys_of(scaffold, labels[:10])  # loaded: the signals below come while the kernel computes
for delay in (0.02, 0.05, 0.1):
    threading.Timer(delay, os.kill, (os.getpid(), signal.SIGINT)).start()
    try:
        keys_of(scaffold, labels)
    except KeyboardInterrupt:
        print("interrupted")
"""


def test_a_signal_during_a_kernel_returning_a_named_tuple_is_an_interrupt_not_a_crash():
    """Issue 35: Ctrl-C or SIGTERM during ``design_keys`` (atlas, solve --type) was a segmentation fault, exit 139:
    numba, boxing the KeyArrays it returns, calls Python to find the class, which raised, and then called NULL."""
    done = subprocess.run([sys.executable, "-c", NAMEDTUPLE_KERNEL], capture_output=True, text=True, timeout=HANG)
    assert done.returncode == 0, (done.returncode, done.stderr[-2000:])
    assert done.stdout.split() == ["interrupted"] * 3  # each raised once the kernel returned


@pytest.mark.slow  # the first progress line comes after the first shard: seconds, a minute under load
@pytest.mark.parametrize("jobs", ["1", "2"])
def test_census_stops_between_shards_and_within_one(jobs):
    """A census of minutes (the dodecahedron's 2^30 parity vectors by components) stops on Ctrl-C.

    The signal comes after the first shards are counted (the progress line), while later
    ones run in compiled calls: in this process (``--jobs 1``) or in workers.
    """
    argv = ["enumerate", "dodecahedron", "--labels", "0,1", "--count-only", "--components", "1", "--jobs", jobs]
    proc = launch(argv, progress=True)
    wait_for_line(proc, "lkspace: census:")
    send(proc, signal.SIGINT, group=True)
    _, err = proc.communicate(timeout=HANG)
    assert proc.returncode == 130, err
    errors = [line for line in err.splitlines() if line.strip() and not line.startswith("lkspace: census:")]
    assert errors == ["lkspace: error: interrupted"], err


def test_ctrl_c_after_a_cp_sat_search_is_still_ours():
    """CP-SAT left SIGINT at the default action after a search: the next Ctrl-C killed the program silently."""
    script = (
        "import os, signal, lkspace\n"
        "r = lkspace.solve('cube', 3, options=lkspace.SolveOptions(count=2, fast_path=False))\n"
        "assert r.method == 'cp-sat', r\n"
        "try:\n"
        "    os.kill(os.getpid(), signal.SIGINT)\n"
        "    __import__('time').sleep(5)\n"
        "except KeyboardInterrupt:\n"
        "    print('caught')\n"
    )
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=HANG)
    assert (proc.returncode, proc.stdout.strip()) == (0, "caught"), proc.stderr


def test_ctrl_c_while_the_command_line_imports_is_one_line_and_130():
    """Ctrl-C while click and the command line import (the program's first second): no traceback.

    The signal is sent from inside the import of click, so it lands there every time.
    """
    script = (
        "import os, signal, sys\n"
        "class Hook:\n"
        "    def find_spec(self, name, path, target=None):\n"
        "        if name == 'click':\n"
        "            os.kill(os.getpid(), signal.SIGINT)\n"
        "sys.meta_path.insert(0, Hook())\n"
        "sys.argv = ['lkspace', 'identify', 'cube', '--twist', '1', '--json']\n"
        "from lkspace.__main__ import main\n"
        "main()\n"
    )
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=HANG)
    assert (proc.returncode, proc.stderr) == (130, "lkspace: error: interrupted\n"), proc.stderr
    assert '"type": "Interrupted"' in proc.stdout


@pytest.mark.parametrize("delay", [0.3, 0.6, 1.0, 1.5])
def test_ctrl_c_in_the_first_second_of_the_installed_program(delay):
    """The real program at fixed moments of its start: exit 130 and one line, or (if the machine is so
    slow that the signal lands while Python itself still starts, before any lkspace code) Python's own
    start-up error; never a traceback through lkspace."""
    proc = subprocess.Popen(
        [*lkspace_command(), "identify", "cube", "--twist", "1"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    time.sleep(delay)
    send(proc, signal.SIGINT, group=True)
    _, err = proc.communicate(timeout=HANG)
    if "Traceback" in err:
        assert "lkspace" not in err.split("Traceback", 1)[1].replace("/bin/lkspace", ""), err
        assert "init_import_site" in err or "<frozen site>" in err, err
    else:
        # 0: the signal came after the answer; -SIGINT: it came in the interpreter's last instants,
        # when Python has put the default handlers back (the command had ended, and said nothing)
        assert proc.returncode in (130, 0, -signal.SIGINT), err
        assert proc.returncode != -signal.SIGINT or not err, err
        assert err.strip() in ("", "lkspace: error: interrupted"), err


def test_a_long_call_in_a_thread_lets_ctrl_c_through_at_once():
    """``workers.interruptible``: the interrupt goes on up while the call still runs (a KD-tree of millions
    of points held Ctrl-C back for seconds in ``export --block``)."""
    script = (
        "import os, signal, threading\n"
        "from lkspace.runtime.workers import interruptible\n"
        "release = threading.Event()\n"
        "threading.Timer(0.2, os.kill, (os.getpid(), signal.SIGINT)).start()\n"
        "try:\n"
        "    interruptible(lambda: release.wait(120))\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted while the call runs' if not release.is_set() else 'after the call')\n"
        "release.set()\n"
        "print(interruptible(lambda: 6 * 7))\n"
        "try:\n"
        "    interruptible(lambda: 1 / 0)\n"
        "except ZeroDivisionError:\n"
        "    print('raised here')\n"
    )
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=HANG)
    assert proc.stdout.split("\n") == ["interrupted while the call runs", "42", "raised here", ""], proc.stderr


def test_a_small_call_runs_in_place():
    import threading

    from lkspace.runtime.workers import QUICK_SIZE, interruptible

    def here() -> bool:
        return threading.current_thread() is threading.main_thread()

    assert interruptible(here, QUICK_SIZE - 1)
    assert not interruptible(here, QUICK_SIZE) and not interruptible(here)


REGINA_KEY = """
import os, signal, threading
import numpy as np
import lkspace
from lkspace.knots import from_labels, tables

real = tables.regina_module()
calls = []  # per Jones polynomial: whether it ran off the main thread, and when it returned

class Link:  # regina's link, sending Ctrl-C once its long C++ call (seconds) has begun
    @staticmethod
    def fromPD(pd):
        link = Link()
        link.real = real.Link.fromPD(pd)
        return link

    def simplify(self):
        self.real.simplify()

    def jones(self):
        calls.append(threading.current_thread() is not threading.main_thread())
        threading.Timer(0.05, os.kill, (os.getpid(), signal.SIGINT)).start()
        out = self.real.jones()
        calls.append("returned")
        return out

class Regina:
    Link = Link

tables.regina_module = lambda: Regina
try:
    from_labels.design_keys_of(lkspace.load("dodecahedron"), np.full(30, 3))
except KeyboardInterrupt:
    print("interrupted during the call" if calls == [True] else f"interrupted, calls {calls}")
"""


def test_ctrl_c_during_regina_s_jones_polynomial_goes_through_at_once():
    """``identify dodecahedron --twist 3`` held Ctrl-C back for up to 3 s: the key of a diagram too wide for
    the state sum (112 crossings) is regina's Jones polynomial, one C++ call; it now runs in a thread."""
    proc = subprocess.run([sys.executable, "-c", REGINA_KEY], capture_output=True, text=True, timeout=HANG)
    assert proc.stdout == "interrupted during the call\n", proc.stderr


REGINA_SHARE = """
import os, signal, sys, threading
import regina
from lkspace.knots import design_diagrams, tables

real = tables.regina_module()
calls = []  # per long call: whether it ran off the main thread, and when it returned

class Link:  # regina's link, sending Ctrl-C once its long C++ call (seconds, or minutes) has begun
    @staticmethod
    def fromPD(pd):
        link = Link()
        link.real = real.Link.fromPD(pd)
        return link

    def size(self):
        return self.real.size()

    def long(self, call):
        calls.append(threading.current_thread() is not threading.main_thread())
        threading.Timer(0.05, os.kill, (os.getpid(), signal.SIGINT)).start()
        out = call()
        calls.append("returned")
        return out

    def simplify(self):
        return self.long(self.real.simplify) if sys.argv[1] == "simplify" else self.real.simplify()

    def homfly(self):
        return self.long(self.real.homfly)

class Regina:
    Link = Link
    RandomEngine = real.RandomEngine

tables.regina_module = lambda: Regina
try:
    if sys.argv[1] == "homfly":  # the torus knot T(6, 7): 35 crossings, minutes of HOMFLY-PT
        design_diagrams.homfly_of_link(design_diagrams.simplified(real.ExampleLink.torus(6, 7).pdData(), Regina))
    else:  # T(3, 2000): 4,000 crossings, seconds of simplification
        design_diagrams.simplified(real.ExampleLink.torus(3, 2000).pdData(), Regina)
except KeyboardInterrupt:
    print("interrupted during the call" if calls == [True] else f"interrupted, calls {calls}")
"""


@pytest.mark.parametrize("call", ["homfly"])
def test_ctrl_c_during_regina_s_calls_sharing_a_key_goes_through_at_once(call):
    """Sharing names by key, regina took the HOMFLY-PT polynomial in the main thread: Ctrl-C waited for the
    C++ call (minutes for a simplified diagram of 35 crossings).  Its simplification holds the GIL, so a
    thread would not help there (``identify`` runs a wide diagram's in a child it can stop)."""
    pytest.importorskip("regina")
    proc = subprocess.run([sys.executable, "-c", REGINA_SHARE, call], capture_output=True, text=True, timeout=HANG)
    assert proc.stdout == "interrupted during the call\n", proc.stderr
