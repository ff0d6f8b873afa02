"""Benchmark: two source trees side by side, the command line end to end, in interleaved rounds.

    mkdir /tmp/lk-before && git archive 596b7b9 | tar -x -C /tmp/lk-before
    python experiments/bench_before_after.py --before /tmp/lk-before --before-commit 596b7b9 --label "issue 36"

Each round runs every case once with the ``--before`` tree first on ``PYTHONPATH`` and once
with this checkout, in turn, so a change in the machine's load falls on both alike (after
one untimed warm-up of each, which also fills numba's cache).  Wall and CPU (user + system)
seconds; the median and best per case go to
``results/bench_before_after.json`` and ``.md`` under ``--label``, with both commits and the
load average before and after.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
from pathlib import Path

from benchkit import RESULTS, ROOT, load_average, provenance, summary, timed

CASES = {
    "trace tetrahedron": ["trace", "tetrahedron", "--twist", "1"],
    "enumerate oF -1..1 -o": ["enumerate", "honeycomb:oF", "--labels", "-1..1", "-o", "{tmp}/oF.parquet"],
    "enumerate cube -1..1 --identify -o": [
        "enumerate",
        "cube",
        "--labels",
        "-1..1",
        "--identify",
        "-o",
        "{tmp}/c1.parquet",
    ],
    "enumerate cube -2..2 --jobs 2 -o": [
        "enumerate",
        "cube",
        "--labels",
        "-2..2",
        "--jobs",
        "2",
        "-o",
        "{tmp}/c2.parquet",
    ],
    "solve cube --components 1": ["solve", "cube", "--components", "1", "--json"],
    "identify cube (trefoil)": ["identify", "cube", "--twist", "0,0,0,0,0,-1,0,-1,-1,-1,-1,-1"],
    "lookup 5_2": ["lookup", "5_2", "--json"],
    "export cube .stl": ["export", "cube", "--twist", "1", "-o", "{tmp}/cube.stl"],
    "verify catalog": ["verify", "{tmp}/c1.parquet"],
}
"""Case -> the command line after ``lkspace`` (``{tmp}``: a scratch folder)."""


def run(code: Path, argv: list[str], tmp: str) -> dict:
    """Run ``lkspace argv`` in a fresh process with ``code`` first on ``PYTHONPATH`` (:func:`benchkit.timed`)."""
    env = {**os.environ, "PYTHONPATH": str(code)}
    return timed([sys.executable, "-m", "lkspace", *(a.format(tmp=tmp) for a in argv)], env=env)


def main() -> None:
    """Time both trees in interleaved rounds and merge the figures into the results files."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", type=Path, required=True, help="source tree of the code before")
    parser.add_argument("--before-commit", required=True, help="the commit the --before tree holds")
    parser.add_argument("--label", default="latest")
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args()
    trees = {"before": args.before.resolve(), "after": ROOT}
    times: dict[str, dict[str, list[dict]]] = {t: {c: [] for c in CASES} for t in trees}
    load_before = load_average()
    with tempfile.TemporaryDirectory() as tmp:
        for round_ in range(args.rounds + 1):
            for case, argv in CASES.items():
                for tree, code in trees.items():
                    measured = run(code, argv, tmp)
                    if round_:  # the first round warms both up
                        times[tree][case].append(measured)
            print(f"round {round_} done", file=sys.stderr, flush=True)
    rows = {case: {tree: summary(times[tree][case]) for tree in trees} for case in CASES}
    path = RESULTS / "bench_before_after.json"
    results = json.loads(path.read_text()) if path.exists() else {}
    results[args.label] = {
        "before_commit": args.before_commit,
        **provenance(),
        "rounds": args.rounds,
        "load_before": load_before,
        "load_after": load_average(),
        "cases": rows,
    }
    path.write_text(json.dumps(results, indent=1) + "\n")
    lines = ["# The command line before and after a change, in interleaved rounds", ""]
    lines.append("Written by `experiments/bench_before_after.py`; seconds, median (best) of the rounds.")
    for label, run_ in results.items():
        lines += ["", f"## {label}", ""]
        lines.append(
            f"before {run_['before_commit']}, after {run_['commit']}, {run_['rounds']} rounds, "
            f"load {run_['load_before']} → {run_['load_after']}, {run_['machine']['cpu_count']} × {run_['machine']['cpu']}"
        )
        lines += ["", "| case | before wall | after wall | before CPU | after CPU |", "|---|---:|---:|---:|---:|"]
        for case, row in run_["cases"].items():
            b, a = row["before"], row["after"]
            lines.append(
                f"| {case} | {b['median_s']} ({b['best_s']}) | {a['median_s']} ({a['best_s']}) "
                f"| {b['cpu_median_s']} | {a['cpu_median_s']} |"
            )
    (RESULTS / "bench_before_after.md").write_text("\n".join(lines) + "\n")
    print((RESULTS / "bench_before_after.md").read_text())


if __name__ == "__main__":
    main()
