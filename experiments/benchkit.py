"""What every benchmark records beside its figures, and how a command is timed in a fresh process.

:func:`provenance` says what was measured and where: the commit and lkspace version of the
tree tested, the machine (CPU count and model) and the date.  :func:`timed` runs one
command in a fresh process and returns its wall time, its CPU time (user + system, which
other jobs on a shared machine disturb less) and its peak RSS.  :func:`numpy_import`
times ``python -c "import numpy"``, the reference figures are divided by: start-up and
end-to-end runs are given as ratios to it, measured in the same run, so a loaded machine
shows as a slow reference rather than as a slow lkspace.
"""

from __future__ import annotations

import datetime
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "results"
IMPORT_NUMPY = [sys.executable, "-c", "import numpy"]


def cpu_model() -> str | None:
    """The CPU's model name (``/proc/cpuinfo``), ``None`` where it cannot be read."""
    try:
        with open("/proc/cpuinfo") as info:
            names = [line.split(":", 1)[1].strip() for line in info if line.startswith("model name")]
    except OSError:
        return None
    return names[0] if names else None


def git(tree: Path, *args: str) -> str | None:
    """Output of ``git -C tree ARGS`` (stripped), ``None`` when it fails."""
    proc = subprocess.run(["git", "-C", str(tree), *args], capture_output=True, text=True)
    return proc.stdout.strip() if proc.returncode == 0 else None


def provenance(tree: Path = ROOT) -> dict:
    """Commit (and whether the tree differs from it), lkspace version, interpreter, machine and date."""
    code = "import lkspace, numpy, sys; print(lkspace.__version__, numpy.__version__, sys.version.split()[0])"
    env = {**os.environ, "PYTHONPATH": str(tree)}
    versions = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env).stdout.split()
    commit = git(tree, "rev-parse", "--short", "HEAD")
    return {
        "date": datetime.datetime.now().astimezone().isoformat(timespec="seconds"),
        "commit": commit,
        "dirty": None if commit is None else git(tree, "status", "--porcelain", "--untracked-files=no") != "",
        "tree": str(tree),
        "lkspace": versions[0] if versions else None,
        "numpy": versions[1] if len(versions) > 1 else None,
        "python": versions[2] if len(versions) > 2 else None,
        "interpreter": sys.executable,
        "machine": {"cpu_count": os.cpu_count(), "cpu": cpu_model()},
    }


def load_average() -> list[float]:
    """The 1, 5 and 15 minute load averages, rounded."""
    return [round(x, 2) for x in os.getloadavg()]


def timed(cmd: list[str], env: dict[str, str] | None = None, cwd: str | None = None) -> dict:
    """Run ``cmd`` in a fresh process: wall and CPU seconds, peak RSS (MB); raises if it fails.

    ``cwd`` defaults to the temporary folder, not this one: ``python -m`` puts the working
    directory first on ``sys.path``, so a run started in a checkout would import that checkout
    whatever ``PYTHONPATH`` names (a "before" tree timed as the working tree).
    """
    with tempfile.TemporaryFile() as err:
        start = time.perf_counter()
        proc = subprocess.Popen(cmd, env=env, cwd=cwd or tempfile.gettempdir(), stdout=subprocess.DEVNULL, stderr=err)
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - start
        if os.waitstatus_to_exitcode(status) != 0:
            err.seek(0)
            raise RuntimeError(f"{' '.join(cmd)} failed: {err.read().decode()[-2000:]}")
    return {"wall": wall, "cpu": usage.ru_utime + usage.ru_stime, "rss_mb": usage.ru_maxrss / 1024}


def summary(samples: list[dict]) -> dict:
    """Median and best wall and CPU seconds of ``samples`` (from :func:`timed`), every wall time, peak RSS."""
    walls = [s["wall"] for s in samples]
    cpus = [s["cpu"] for s in samples]
    return {
        "median_s": round(statistics.median(walls), 3),
        "best_s": round(min(walls), 3),
        "cpu_median_s": round(statistics.median(cpus), 3),
        "cpu_best_s": round(min(cpus), 3),
        "runs_s": [round(w, 3) for w in walls],
        "peak_rss_mb": round(max(s["rss_mb"] for s in samples), 1),
    }


def numpy_import(runs: int = 5) -> dict:
    """:func:`summary` of ``python -c "import numpy"`` (after one untimed run)."""
    timed(IMPORT_NUMPY)
    return summary([timed(IMPORT_NUMPY) for _ in range(runs)])


def ratio(figure: dict, reference: dict, key: str = "median_s") -> float:
    """``figure[key] / reference[key]``, rounded (the figure in units of the reference)."""
    return round(figure[key] / reference[key], 2)
