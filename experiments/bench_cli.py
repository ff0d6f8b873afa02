"""Benchmark: the command line as users run it, end to end, against the goals of issue 20.

Each case is one ``lkspace ...`` command (the console script beside the interpreter) in a
fresh process, with numba's compile cache and Python's bytecode cache warm (as a user has
them; ``PYTHONDONTWRITEBYTECODE`` is dropped): every case runs once untimed, then
``--runs`` rounds run every case once each, in turn (so a change in the machine's load
falls on all cases alike).  The reference cases ``python -c pass`` and
``python -c "import numpy"`` run in the same rounds; every figure is also given as a
ratio to ``import numpy`` (median over median, best over best), which is how the goals
are checked on a shared machine.  Wall and CPU (user + system) seconds are both kept.

``--code DIR`` measures another source tree (put first on ``PYTHONPATH``), e.g. the code
before a change::

    mkdir /tmp/lk-before && git archive 9116d21 | tar -x -C /tmp/lk-before
    python experiments/bench_cli.py --code /tmp/lk-before --commit 9116d21 --label before
    python experiments/bench_cli.py --label after

Results merge into ``results/bench_cli.json`` under ``--label`` (with commit, lkspace
version, machine, load average before and after); ``results/bench_cli.md`` shows every
label.  ``--quick``: 3 rounds and no cube case.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import sys
import tempfile
from pathlib import Path

from benchkit import RESULTS, ROOT, load_average, provenance, ratio, summary, timed

OUT = RESULTS / "bench_cli.json"
IDLE_IMPORT_NUMPY = 0.14
"""Seconds of ``python -c "import numpy"`` on this machine when idle (issue 20): a goal of G seconds
is read as G / 0.14 times the reference timed in the same run, which a loaded machine slows alike."""
LKSPACE = str(Path(sys.executable).with_name("lkspace"))

CASES = [  # key, command (OUT: a fresh output path per run), goal in seconds (median wall), in --quick
    ("python_pass", [sys.executable, "-c", "pass"], None, True),
    ("import_numpy", [sys.executable, "-c", "import numpy"], None, True),
    ("import_lkspace", [sys.executable, "-c", "import lkspace"], None, True),
    ("help", [LKSPACE, "--help"], 0.3, True),
    ("trace", [LKSPACE, "trace", "tetrahedron", "--twist", "1"], 0.35, True),
    ("oF_count", [LKSPACE, "enumerate", "honeycomb:oF", "--labels", "-1..1", "--count-only"], None, True),
    ("oF", [LKSPACE, "enumerate", "honeycomb:oF", "--labels", "-1..1", "-o", "OUT"], 1.5, True),
    ("cube2", [LKSPACE, "enumerate", "cube", "--labels", "-2..2", "-o", "OUT", "--jobs", "2"], 6.0, False),
]
TITLES = {
    "python_pass": "`python -c pass`",
    "import_numpy": '`python -c "import numpy"` (the reference)',
    "import_lkspace": '`python -c "import lkspace"`',
    "help": "`lkspace --help`",
    "trace": "`lkspace trace tetrahedron --twist 1`",
    "oF_count": "`lkspace enumerate honeycomb:oF --labels -1..1 --count-only`",
    "oF": "`lkspace enumerate honeycomb:oF --labels -1..1 -o x.parquet`",
    "cube2": "`lkspace enumerate cube --labels -2..2 -o c.parquet --jobs 2`",
}


def remove(path: str) -> None:
    """Remove the catalog (a file or a folder of parts) at ``path``, if any."""
    if os.path.isdir(path):
        shutil.rmtree(path)
    elif os.path.exists(path):
        os.remove(path)


def measure(code: Path, runs: int, quick: bool) -> dict:
    """Time every case (see the module docstring); return the figures with their provenance."""
    env = {**os.environ, "PYTHONPATH": str(code)}
    for name in ("NUMBA_CACHE_DIR", "PYTHONDONTWRITEBYTECODE"):  # the user's caches, warmed by the untimed round
        env.pop(name, None)
    cases = [(key, cmd, goal) for key, cmd, goal, in_quick in CASES if in_quick or not quick]
    samples: dict[str, list[dict]] = {key: [] for key, _, _ in cases}
    result = {**provenance(code), "runs": runs, "load_average_before": load_average()}
    with tempfile.TemporaryDirectory(prefix="bench_cli_") as tmp:
        for round_ in range(runs + 1):  # round 0: the warm-up, not kept
            for key, cmd, _ in cases:
                out = os.path.join(tmp, f"{key}-{round_}.parquet")
                sample = timed([out if arg == "OUT" else arg for arg in cmd], env, cwd=tmp)
                remove(out)
                if round_:
                    samples[key].append(sample)
    result["load_average_after"] = load_average()
    figures = result["figures"] = {key: summary(samples[key]) for key, _, _ in cases}
    numpy = figures["import_numpy"]
    for key, _, goal in cases:
        figures[key].update(ratio_median=ratio(figures[key], numpy), ratio_best=ratio(figures[key], numpy, "best_s"))
        if goal is not None:
            goal_ratio = round(goal / IDLE_IMPORT_NUMPY, 1)
            figures[key].update(
                goal_s=goal,
                goal_ratio=goal_ratio,
                goal_met_seconds=figures[key]["median_s"] <= goal,
                goal_met_ratio=figures[key]["ratio_median"] <= goal_ratio,
            )
    return result


def markdown(data: dict) -> str:
    """The table of every label: median wall s (× import numpy), goal, CPU s; then provenance."""
    labels = list(data)
    lines = [
        "# Benchmark: the command line end to end",
        "",
        "Fresh process per run, numba's and Python's caches warm; median wall seconds of the runs and, in",
        'brackets, the median as a multiple of `python -c "import numpy"` timed in the same rounds (best',
        "over best in the JSON).  A goal of G seconds is met in seconds (first mark) and, read as",
        f"G / {IDLE_IMPORT_NUMPY} s (`import numpy` here when idle) times the reference, in the ratio (second",
        "mark: what a loaded machine leaves comparable).  CPU = user + system seconds of the command's own",
        "process (median; workers started by a fork server are not counted).",
        "Written by `experiments/bench_cli.py` (`python experiments/run_benchmarks.py` runs it).",
        "",
        "| command | goal | " + " | ".join(f"{label} wall | {label} CPU" for label in labels) + " |",
        "|---|---|" + "---|---|" * len(labels),
    ]
    for key, _, goal, _ in CASES:
        cells = []
        for label in labels:
            f = data[label]["figures"].get(key)
            if f is None:
                cells += ["-", "-"]
                continue
            marks = [" ✓" if f.get(k) else " ✗" for k in ("goal_met_seconds", "goal_met_ratio") if k in f]
            seconds, times = (f"{f['median_s']:.2f} s", f"{f['ratio_median']:.1f}×")
            if marks:
                seconds, times = seconds + marks[0], times + marks[1]
            cells += [f"{seconds} ({times})", f"{f['cpu_median_s']:.2f} s"]
        goal_text = "" if goal is None else f"≤ {goal} s (≤ {goal / IDLE_IMPORT_NUMPY:.1f}×)"
        lines.append(f"| {TITLES[key]} | {goal_text} | " + " | ".join(cells) + " |")
    lines += [
        "",
        "| label | date | commit | lkspace | runs | CPUs | CPU model | load average before → after |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for label, r in data.items():
        commit = f"{r['commit']}{' (dirty)' if r.get('dirty') else ''}"
        load = f"{', '.join(map(str, r['load_average_before']))} → {', '.join(map(str, r['load_average_after']))}"
        m = r["machine"]
        lines.append(
            f"| {label} | {r['date']} | {commit} | {r['lkspace']} | {r['runs']} | {m['cpu_count']} | {m['cpu']} | {load} |"
        )
    return "\n".join(lines) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--code", type=Path, default=ROOT, help="source tree holding the lkspace package to time")
    parser.add_argument("--commit", help="commit of --code when it is no git work tree (e.g. a git archive)")
    parser.add_argument("--label", default="latest", help='key in the JSON, e.g. "before" or "after"')
    parser.add_argument("--runs", type=int, default=7, help="timed rounds (after one untimed)")
    parser.add_argument("--quick", action="store_true", help="3 rounds, no cube case")
    args = parser.parse_args()
    result = measure(args.code.resolve(), 3 if args.quick else args.runs, args.quick)
    if args.commit:
        result.update(commit=args.commit, dirty=False)
    data = json.loads(OUT.read_text()) if OUT.exists() else {}
    data[args.label] = result
    OUT.write_text(json.dumps(data, indent=1) + "\n")
    OUT.with_suffix(".md").write_text(markdown(data))
    print(markdown({args.label: result}))


if __name__ == "__main__":
    main()
