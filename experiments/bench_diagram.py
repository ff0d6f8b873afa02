"""Benchmark: the candidate search of the planar diagram (``near_pairs``), before and after issue 33.

``near_pairs`` finds the pairs of projected segments whose circles meet, the candidates
for crossings.  It used one uniform grid whose cell was the longest segment, so one long
segment made the grid coarse and the search quadratic; it now puts each segment's box
into the cells of a grid at the typical segment size.  Cases:

- ``dense 47k``: a (3, 400) torus knot drawn with 47,000 segments of even length;
- ``dense 47k + one long``: the same with 12 points left out, so that one segment is four
  times as long as the others (the case of issue 33: the old grid's cells grew with it);
- ``realized``: the default curves of small designs (cube, dodecahedron), the everyday case
  (``project`` whole, whose candidate search is ``near_pairs``).

Each case is timed (best of a few runs) in a fresh process per tree: this tree, and with
``--before REV`` the tree at a git revision (``git archive``), so the two columns come
from one run on one machine load.  Both trees must give the same pairs; the pair counts
are printed beside the times.  Writes ``results/bench_diagram.json`` and ``.md``.

Run: ``python experiments/bench_diagram.py [--before REV]``.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from benchkit import RESULTS, ROOT, git, load_average, provenance  # noqa: E402


def torus_knot(n: int, long_gap: int = 0) -> np.ndarray:
    """A (3, 400) torus knot as ``n`` points; ``long_gap`` points removed leave one long segment."""
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = 2 + np.cos(400 * t)
    pts = np.column_stack([r * np.cos(3 * t), r * np.sin(3 * t), np.sin(400 * t)])
    return pts[long_gap:] if long_gap else pts


def segment_ends(curves: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Starts and ends ``(n, 3)`` of the closed polylines' segments."""
    return np.vstack(curves), np.vstack([np.roll(c, -1, axis=0) for c in curves])


def cases() -> dict[str, object]:
    """The inputs: segment ends for ``near_pairs`` or curves for ``project``."""
    import lkspace

    dense = torus_knot(47_000)
    gap = 12  # the closing segment is about 0.2 long, the others 0.05
    cube = lkspace.realize("cube", [1, 0, -1, 1, 1, 0, 2, 1, 0, 1, 1, 1])
    dodeca = lkspace.realize("dodecahedron", 1)
    return {
        "near_pairs: dense 47k": segment_ends([dense]),
        "near_pairs: dense 47k + one long": segment_ends([torus_knot(47_000 + gap, gap)]),
        "project: realized cube": [np.asarray(c) for c in cube.curves],
        "project: realized dodecahedron": [np.asarray(c) for c in dodeca.curves],
    }


def measure(repeats: int) -> dict:
    """Time every case in this process (lkspace from ``PYTHONPATH``); best of ``repeats``."""
    from lkspace.knots.diagram import near_pairs, project

    out = {}
    for name, data in cases().items():
        times = []
        for _ in range(repeats):
            t0 = time.perf_counter()
            if name.startswith("near_pairs"):
                p0, p1 = data
                result = near_pairs(p0, p1)
                count = len(result[0])
            else:
                count = project(data).n_crossings
            times.append(time.perf_counter() - t0)
        segments = len(data[0]) if name.startswith("near_pairs") else sum(len(c) for c in data)
        out[name] = {"best_s": round(min(times), 4), "segments": segments, "count": count}
        print(tree_label(), name, out[name], flush=True)
    return out


def tree_label() -> str:
    return os.environ.get("BENCH_TREE", "this")


def run_tree(tree: Path, label: str, repeats: int) -> dict:
    """Run :func:`measure` in a fresh process with ``tree`` on ``PYTHONPATH``."""
    env = {**os.environ, "PYTHONPATH": str(tree), "BENCH_TREE": label}
    proc = subprocess.run(
        [sys.executable, __file__, "--measure", "--repeats", str(repeats)],
        env=env,
        capture_output=True,
        text=True,
        check=True,
    )
    sys.stdout.write(proc.stdout.split("\n@@")[0])
    return json.loads(proc.stdout.split("\n@@")[1])


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--before", help="git revision to compare with")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--measure", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.measure:
        print("\n@@" + json.dumps(measure(args.repeats)))
        return
    load = load_average()
    trees = {"after": run_tree(ROOT, "after", args.repeats)}
    before_commit = None
    if args.before:
        before_commit = git(ROOT, "rev-parse", "--short", args.before)
        with tempfile.TemporaryDirectory() as folder:
            archive = Path(folder) / "tree.tar"
            subprocess.run(["git", "-C", str(ROOT), "archive", "-o", str(archive), args.before], check=True)
            with tarfile.open(archive) as tar:
                tar.extractall(folder, filter="data")
            trees["before"] = run_tree(Path(folder), "before", args.repeats)
    meta = {**provenance(), "before": before_commit, "load_before": load, "load_after": load_average()}
    for name, row in trees["after"].items():
        if "before" in trees and trees["before"][name]["count"] != row["count"]:
            raise SystemExit(f"{name}: the trees disagree ({trees['before'][name]['count']} vs {row['count']})")
    (RESULTS / "bench_diagram.json").write_text(json.dumps({"meta": meta, "trees": trees}, indent=1) + "\n")
    lines = [
        "# Diagram candidate search (issue 33)",
        "",
        f"Commit {meta['commit']} (dirty: {meta['dirty']}), before = {before_commit}; {meta['date']}; "
        f"{meta['machine']['cpu_count']} CPUs ({meta['machine']['cpu']}); load {load} -> {meta['load_after']}.",
        "Best of the runs, seconds, each tree in a fresh process; `count` is the number of pairs "
        "(`near_pairs`) or crossings (`project`), equal in both trees.",
        "",
        "| case | segments | count | before s | after s |",
        "|---|---:|---:|---:|---:|",
    ]
    for name, row in trees["after"].items():
        before = trees["before"][name]["best_s"] if "before" in trees else "-"
        lines.append(f"| {name} | {row['segments']} | {row['count']} | {before} | {row['best_s']} |")
    (RESULTS / "bench_diagram.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
