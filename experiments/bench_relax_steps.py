"""Benchmark: relaxation steps per second of two source trees, interleaved, on small and large designs.

Each round runs, in a fresh process per tree, ``STEPS`` iterations of the growing rope flow
(``lkspace.geometry.flow.rope_flow`` with relax's growth, the convergence rule out of reach
at that length) on each design's default curves, and records the CPU time of the flow
alone (its process's, which other jobs on the shared machine disturb far less than the
wall time; both are kept).  Trees alternate within a round so load hits both alike.
Writes ``results/bench_relax_steps.{json,md}`` with the commits, machine and load average.

Run: ``python experiments/bench_relax_steps.py BEFORE_TREE AFTER_TREE [--rounds 3]``.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from benchkit import RESULTS, provenance  # noqa: E402

DESIGNS = [
    ("trefoil", "dihedron:3", "1"),
    ("6_2", "figure-eight", "-2,-2,-1,-1,0"),
    ("dodecahedron", "dodecahedron", "1"),
    ("icosahedron", "icosahedron", "1"),
    ("truncated-octahedron", "truncated-octahedron", "1"),
]
"""(name, mesh, twist): two small knots and the three large 6-component designs of issue 34."""

STEPS = 300
"""Flow iterations timed per design (below the convergence window: every run does them all)."""

CHILD = """
import json, sys, time
import lkspace
from lkspace.geometry.flow import FlowOptions, rope_flow, rope_thickness
mesh, twist, steps = sys.argv[1], sys.argv[2], int(sys.argv[3])
labels = [int(x) for x in twist.split(",")]
real = lkspace.realize(mesh, labels[0] if len(labels) == 1 else labels)
start = 2 * rope_thickness(real.curves)
t0, c0 = time.perf_counter(), time.process_time()
out = rope_flow(real.curves, FlowOptions(diameter=start, grow=0.004, iterations=steps))
wall, cpu = time.perf_counter() - t0, time.process_time() - c0
print(json.dumps({"wall": wall, "cpu": cpu, "points": sum(len(c) for c in out.curves)}))
"""


def run(tree: Path, mesh: str, twist: str) -> dict:
    env = {**os.environ, "PYTHONPATH": str(tree)}
    proc = subprocess.run(
        [sys.executable, "-c", CHILD, mesh, twist, str(STEPS)], env=env, capture_output=True, text=True, check=True
    )
    return json.loads(proc.stdout.splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("before", type=Path)
    parser.add_argument("after", type=Path)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    trees = {"before": args.before.resolve(), "after": args.after.resolve()}
    times: dict[str, dict[str, list[float]]] = {k: {d[0]: [] for d in DESIGNS} for k in trees}
    walls: dict[str, dict[str, list[float]]] = {k: {d[0]: [] for d in DESIGNS} for k in trees}
    load = [os.getloadavg()[0]]
    for _ in range(args.rounds):
        for name, mesh, twist in DESIGNS:
            for which, tree in trees.items():
                got = run(tree, mesh, twist)
                times[which][name].append(got["cpu"])
                walls[which][name].append(got["wall"])
        load.append(os.getloadavg()[0])
    rows = []
    for name, _, _ in DESIGNS:
        b, a = (statistics.median(times[k][name]) for k in ("before", "after"))
        rows.append({"design": name, "steps": STEPS, "before_steps_per_s": STEPS / b, "after_steps_per_s": STEPS / a})
    data = {
        "before": provenance(trees["before"]),
        "after": provenance(trees["after"]),
        "rounds": args.rounds,
        "load_average_1min": load,
        "rows": rows,
        "cpu_seconds": times,
        "wall_seconds": walls,
    }
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / "bench_relax_steps.json").write_text(json.dumps(data, indent=1) + "\n")
    lines = [
        "# Relaxation steps per second, before and after",
        "",
        f"Before: `{data['before']['commit']}`; after: `{data['after']['commit']}`"
        f"{' (uncommitted changes)' if data['after']['dirty'] else ''}; {data['after']['machine']['cpu_count']} CPUs "
        f"({data['after']['machine']['cpu']}), 1-minute load {min(load):.1f}-{max(load):.1f}; median of "
        f"{args.rounds} interleaved rounds of {STEPS} flow steps, per CPU second of the flow "
        "(`experiments/bench_relax_steps.py`; wall times in the JSON).",
        "",
        "| design | steps/s before | steps/s after | speed-up |",
        "|---|---:|---:|---:|",
    ]
    for r in rows:
        speed = r["after_steps_per_s"] / r["before_steps_per_s"]
        lines.append(f"| {r['design']} | {r['before_steps_per_s']:.0f} | {r['after_steps_per_s']:.0f} | {speed:.2f}x |")
    (RESULTS / "bench_relax_steps.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
