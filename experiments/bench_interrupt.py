"""Benchmark: how long every long-running command takes to stop on Ctrl-C or SIGTERM, on a loaded machine.

Each case starts ``python -m lkspace ...`` in a process group of its own, waits until it is
working (a build folder exists, a line was printed, or some seconds passed), sends the
signal (Ctrl-C as a terminal sends it, to the whole group; SIGTERM as ``kill PID`` does, to
the main process only) and measures the time until the main process has exited.  It records
the exit status, the number of stderr lines (the goal is one: no traceback from a worker or
the fork server), whether a traceback appeared, and whether anything is left at the final
output name.  Meanwhile ``--hogs`` processes spin on the CPU (default 2, one per core of
the reference machine), as on a shared machine.

The lkspace under test is the source folder ``--source`` (put first on ``PYTHONPATH``), so a
checkout of an older commit can be measured beside the working tree:

    git archive BASE | tar -x -C /tmp/base
    python experiments/bench_interrupt.py --source /tmp/base --label before
    python experiments/bench_interrupt.py --source . --label after

Results merge into ``results/bench_interrupt.json`` under ``--label``; a Markdown table of
all labels is written beside it (``results/bench_interrupt.md``).
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import signal
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass
from pathlib import Path

RESULTS = Path(__file__).resolve().parents[1] / "results"
BIG_KNOT = "2,2,2,2,2,1,2,2,1,2,1,2,1,2,2,1,2,1,2,1,2,2,1,1,2,1,1,2,2,2,1,2,2,1,2,2"
GOAL = 2.0
"""Seconds from the signal to the exit that the project asks for."""


@dataclass(frozen=True)
class Case:
    """One measurement: ``lkspace ARGS`` (``{out}`` is the output path), stopped by ``signal`` once ready."""

    name: str
    args: tuple[str, ...]
    signal: str = "SIGINT"
    ready: str = "seconds:6"
    """``seconds:S`` after start, ``build:S`` seconds after the catalog's build folder appeared, or ``line:TEXT``."""
    out: str = "x.parquet"


CASES = [
    Case(
        "enumerate --jobs 2, early",
        ("enumerate", "cube", "--labels", "-2..2", "-o", "{out}", "--jobs", "2"),
        ready="build:0",
    ),
    Case(
        "enumerate --jobs 2", ("enumerate", "cube", "--labels", "-2..2", "-o", "{out}", "--jobs", "2"), ready="build:2"
    ),
    Case(
        "enumerate --jobs 2",
        ("enumerate", "cube", "--labels", "-2..2", "-o", "{out}", "--jobs", "2"),
        "SIGTERM",
        "build:2",
    ),
    Case("enumerate (one process)", ("enumerate", "cube", "--labels", "-2..2", "-o", "{out}"), ready="build:2"),
    Case(
        "enumerate --scheduler dask",
        ("enumerate", "cube", "--labels", "-2..2", "-o", "{out}", "--jobs", "2", "--scheduler", "dask"),
        ready="build:4",
    ),
    Case(
        "enumerate --scheduler dask",
        ("enumerate", "cube", "--labels", "-2..2", "-o", "{out}", "--jobs", "2", "--scheduler", "dask"),
        "SIGTERM",
        "build:4",
    ),
    Case(
        "census (--count-only --components)",
        ("enumerate", "dodecahedron", "--labels", "0,1", "--count-only", "--components", "1"),
        ready="seconds:10",
    ),
    Case(
        "census --jobs 2",
        ("enumerate", "dodecahedron", "--labels", "0,1", "--count-only", "--components", "1", "--jobs", "2"),
        ready="seconds:10",
    ),
    Case(
        "enumerate --identify",
        ("enumerate", "cube", "--labels", "-1..1", "--identify", "-o", "{out}", "--jobs", "2"),
        ready="seconds:12",
    ),
    Case(
        "solve", ("solve", "honeycomb:cP@4x4x4", "-n", "3", "--count", "10000", "--time-limit", "60"), ready="seconds:8"
    ),
    Case(
        "solve --type", ("solve", "cube", "--type", "5_2", "--labels", "-2..2", "--processes", "2"), ready="seconds:10"
    ),
    Case(
        "atlas",
        ("atlas", "cube", "--labels", "-1..1", "-o", "{out}", "--processes", "2"),
        ready="seconds:10",
        out="atlas",
    ),
    Case("identify", ("identify", "truncated-octahedron", "--twist", BIG_KNOT), ready="seconds:8"),
    Case(
        "export --block",
        ("export", "honeycomb:cP", "--twist", "1", "--block", "10x10x10", "-o", "{out}"),
        ready="seconds:6",
        out="x.obj",
    ),
    Case("studio", ("studio", "--no-browser", "--port", "0"), ready="line:http://"),
]


def measure(case: Case, source: Path, folder: Path) -> dict[str, object]:
    """Run ``case`` once in ``folder``; return what happened after the signal."""
    out = folder / case.out
    args = [a.replace("{out}", str(out)) for a in case.args]
    env = {**os.environ, "LKSPACE_PROGRESS": "0", "PYTHONPATH": str(source)}
    proc = subprocess.Popen(
        [sys.executable, "-m", "lkspace", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
        cwd=folder,
        start_new_session=True,
    )
    lines: list[str] = []
    seen = threading.Event()
    kind, _, value = case.ready.partition(":")

    def read(stream) -> None:
        for line in stream:
            lines.append(line)
            if kind == "line" and value in line:
                seen.set()

    readers = [threading.Thread(target=read, args=(s,), daemon=True) for s in (proc.stdout, proc.stderr)]
    for r in readers:
        r.start()
    start = time.monotonic()
    if kind == "line":
        seen.wait(120)
    elif kind == "build":
        build = folder / f".{out.name}.lkspace-build"
        while not build.exists() and proc.poll() is None and time.monotonic() - start < 120:
            time.sleep(0.01)
        time.sleep(float(value))
    else:
        time.sleep(float(value))
    ran = time.monotonic() - start
    if proc.poll() is not None:
        return {"case": case.name, "signal": case.signal, "finished_before_signal": True, "returncode": proc.returncode}
    lines_before = len(lines)
    signum = getattr(signal, case.signal)
    sent = time.monotonic()
    if case.signal == "SIGINT":
        os.killpg(proc.pid, signum)
    else:
        proc.send_signal(signum)
    try:
        proc.wait(timeout=300)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()
    latency = time.monotonic() - sent
    time.sleep(0.5)  # what children still write arrives
    with_group_gone(proc.pid)
    err = "".join(lines[lines_before:])
    after = [line for line in err.splitlines() if line.strip() and not line.startswith("http")]
    return {
        "case": case.name,
        "signal": case.signal,
        "ran_s": round(ran, 2),
        "latency_s": round(latency, 2),
        "returncode": proc.returncode,
        "stderr_lines": len(after),
        "traceback": "Traceback" in err,
        "last_line": after[-1][:160] if after else "",
        "left_at_final_name": out.exists() and case.out.endswith(".parquet"),
    }


def with_group_gone(pgid: int) -> None:
    """Kill what is left of the process group (a worker the command failed to stop) and wait a moment."""
    try:
        os.killpg(pgid, signal.SIGKILL)
    except ProcessLookupError:
        return
    time.sleep(0.5)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--source", type=Path, required=True, help="folder holding the lkspace package to test")
    parser.add_argument("--label", required=True)
    parser.add_argument("--hogs", type=int, default=2, help="CPU-bound processes running meanwhile")
    parser.add_argument("--only", default="", help="run only cases whose name holds this text")
    parser.add_argument("--note", default="", help="a sentence on the conditions, shown in the table")
    opts = parser.parse_args()
    source = opts.source.resolve()
    hogs = [subprocess.Popen([sys.executable, "-c", "while 1: pass"]) for _ in range(opts.hogs)]
    rows = []
    try:
        for case in CASES:
            if opts.only not in case.name:
                continue
            with tempfile.TemporaryDirectory(prefix="bench-interrupt-") as tmp:
                row = measure(case, source, Path(tmp))
            print(json.dumps(row), flush=True)
            rows.append(row)
    finally:
        for hog in hogs:
            hog.kill()
            hog.wait()
    commit = subprocess.run(["git", "-C", str(source), "rev-parse", "--short", "HEAD"], capture_output=True, text=True)
    path = RESULTS / "bench_interrupt.json"
    data = json.loads(path.read_text()) if path.exists() else {}
    measured = {(r["case"], r["signal"]) for r in rows}
    kept = [r for r in data.get(opts.label, {}).get("rows", []) if (r["case"], r["signal"]) not in measured]
    rows = [*kept, *rows]  # with --only: the other cases as measured before
    data[opts.label] = {
        "date": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "source": commit.stdout.strip() or str(source),
        "hogs": opts.hogs,
        "cpus": os.cpu_count(),
        "rows": rows,
        "note": opts.note or data.get(opts.label, {}).get("note", ""),
    }
    path.write_text(json.dumps(data, indent=1) + "\n")
    write_table(data, path.with_suffix(".md"))


def write_table(data: dict[str, dict], path: Path) -> None:
    """One row per case and signal, one column group per label."""
    labels = list(data)
    keys = list(dict.fromkeys((r["case"], r["signal"]) for label in labels for r in data[label]["rows"]))
    head = "| case | signal | " + " | ".join(f"{label}: s, exit, stderr lines" for label in labels) + " |"
    lines = [
        "# Stopping on Ctrl-C and SIGTERM under load",
        "",
        "Written by `experiments/bench_interrupt.py`: seconds from the signal to the exit of the main",
        f"process (goal: under {GOAL:.0f} s), exit status (goal: 130 for Ctrl-C, 143 for SIGTERM) and lines on",
        "stderr after the signal (goal: one, no traceback), with CPU hogs spinning on every core; one run per case.",
        "Ctrl-C goes to the whole process group (as a terminal sends it), SIGTERM to the main process.",
        "",
        *[
            f"- {label}: {data[label]['source']}, {data[label]['hogs']} hogs on {data[label]['cpus']} CPUs, "
            f"{data[label]['date']}. {data[label].get('note', '')}"
            for label in labels
        ],
        "",
        head,
        "|" + "---|" * (2 + len(labels)),
    ]
    for case, sig in keys:
        cells = []
        for label in labels:
            row = next((r for r in data[label]["rows"] if (r["case"], r["signal"]) == (case, sig)), None)
            if row is None:
                cells.append("")
            elif row.get("finished_before_signal"):
                cells.append(f"finished first (exit {row['returncode']})")
            else:
                tb = ", traceback" if row["traceback"] else ""
                left = ", file left" if row["left_at_final_name"] else ""
                cells.append(f"{row['latency_s']:.2f}, {row['returncode']}, {row['stderr_lines']}{tb}{left}")
        lines.append(f"| {case} | {sig} | " + " | ".join(cells) + " |")
    path.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
