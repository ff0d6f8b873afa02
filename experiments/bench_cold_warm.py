"""A first ``--identify`` run on a fresh machine against later ones: cold and warm, in fresh processes.

Cold: ``$LKSPACE_CACHE`` and ``$NUMBA_CACHE_DIR`` empty folders (no names by key, no
tables index, no compiled kernels: what a new install meets; lkspace's shipped files,
``lkspace/data/*.xz`` and ``lkspace/compiled/shipped/``, are what make it cheap).
Warm: the folders the cold run left.  Runs alternate cold, warm, cold, warm..., and
between the trees, so that load drifts hit all alike; the ratio cold/warm is of medians.  Each tree (``--tree``,
default this one; ``--before /work/main`` adds the tree before the change) runs with
``PYTHONPATH`` set to it.

Beside them, the kernel rate: designs keyed per second in a warm process (``keys_of`` on the catalog's
designs, one thread and one per core where the tree threads).

Usage: ``python experiments/bench_cold_warm.py [--runs 3] [--space cube:-1..1 ...] [--before TREE
--before-runs 1 --before-space cube:-1..1]``;
writes ``results/bench_cold_warm.{json,md}`` (``--out NAME``: ``results/NAME.*``).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import sys
import tempfile
from pathlib import Path

import pyarrow.parquet as pq
from benchkit import RESULTS, ROOT, load_average, provenance, summary, timed

SPACES = ["cube:-1..1", "whitehead:-1..1"]


def one_run(tree: Path, space: str, samples: dict) -> None:
    """One cold and one warm ``enumerate SPACE --identify`` with ``tree``'s lkspace, added to ``samples``."""
    name, labels = space.split(":")
    folder = tempfile.mkdtemp(prefix="lkspace-cold-")
    cache, numba = os.path.join(folder, "cache"), os.path.join(folder, "numba")
    env = {**os.environ, "PYTHONPATH": str(tree), "LKSPACE_CACHE": cache, "NUMBA_CACHE_DIR": numba}
    out = os.path.join(folder, "x.parquet")
    cmd = [sys.executable, "-m", "lkspace", "enumerate", name, "--labels", labels, "--identify", "-o", out]
    # run in the temporary folder: `python -m` puts the working directory first on sys.path, and
    # started in a checkout it would import that checkout instead of `tree`
    samples["cold"].append({**timed(cmd, env, cwd=folder), "load": load_average()[0]})
    os.remove(out)
    samples["warm"].append({**timed(cmd, env, cwd=folder), "load": load_average()[0]})
    samples["designs"] = pq.read_metadata(out).num_rows
    if "kernel" not in samples:
        samples["kernel"] = key_rate(name, out, env, folder)
    shutil.rmtree(folder)
    cold, warm = samples["cold"][-1]["wall"], samples["warm"][-1]["wall"]
    print(f"{tree} {space}: cold {cold:.2f} s, warm {warm:.2f} s", flush=True)


def summed(samples: dict) -> dict:
    """Cold and warm :func:`benchkit.summary` of one tree and space, their ratio and rates."""
    c, w = summary(samples["cold"]), summary(samples["warm"])
    c["load_1min"] = [s["load"] for s in samples["cold"]]
    w["load_1min"] = [s["load"] for s in samples["warm"]]
    return {
        "cold": c,
        "warm": w,
        "ratio": round(c["median_s"] / w["median_s"], 2),
        "designs": samples["designs"],
        "warm_rate": round(samples["designs"] / w["median_s"]),
        "key_rate": samples["kernel"],
    }


KEY_RATE = """
import json, sys, time, numpy as np, pyarrow.parquet as pq, lkspace
import lkspace.knots.keyed as keyed
scaffold = lkspace.load(sys.argv[1])
flat = pq.read_table(sys.argv[2], columns=["labels"]).column("labels").combine_chunks().flatten()
labels = np.asarray(flat).astype(np.int64).reshape(-1, scaffold.n_edges)
keyed.keys_of(scaffold, labels[:100])
out = {}
for threads in ([1, keyed.key_threads()] if hasattr(keyed, "key_threads") else [1]):
    if hasattr(keyed, "key_threads"):
        keyed.key_threads = lambda n=threads: n
    start = time.perf_counter()
    keyed.keys_of(scaffold, labels)
    out[threads] = round(len(labels) / (time.perf_counter() - start))
print(json.dumps(out))
"""
"""Keys per second of :func:`lkspace.knots.keyed.keys_of` in a warm process, by thread count (the kernel rate)."""


def key_rate(scaffold: str, catalog: str, env: dict[str, str], cwd: str) -> dict[str, int]:
    """Designs keyed per second on the designs of ``catalog``, with one thread and with every core (where the tree threads)."""
    import subprocess

    found = subprocess.run(
        [sys.executable, "-c", KEY_RATE, scaffold, catalog], env=env, cwd=cwd, capture_output=True, text=True
    )
    return json.loads(found.stdout) if found.returncode == 0 else {}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--before", type=Path, help="the tree before the change (e.g. /work/main)")
    parser.add_argument("--before-runs", type=int, default=1, help="runs of the tree before (its cold runs are long)")
    parser.add_argument("--before-space", nargs="*", default=SPACES[:1], help="spaces timed before the change")
    parser.add_argument("--space", nargs="*", default=SPACES, help="scaffold:labels")
    parser.add_argument("--out", default="bench_cold_warm", help="results/OUT.json and results/OUT.md")
    args = parser.parse_args()
    trees = {"after": ROOT} if args.before is None else {"before": args.before, "after": ROOT}
    report: dict = {"provenance": provenance(), "load_start": load_average(), "spaces": {}}
    jobs: dict[tuple[str, str], dict] = {}  # (tree label, space) -> samples; runs alternate between trees
    for label, tree in trees.items():
        report[f"{label}_commit"] = provenance(tree)["commit"]
        for space in args.before_space if label == "before" else args.space:
            jobs[label, space] = {"cold": [], "warm": []}
    for i in range(max(args.runs, args.before_runs if args.before else 0)):
        for (label, space), samples in jobs.items():
            if i < (args.before_runs if label == "before" else args.runs):
                one_run(trees[label], space, samples)
    for (label, space), samples in jobs.items():
        report["spaces"].setdefault(space, {})[label] = summed(samples)
    report["load_end"] = load_average()
    (RESULTS / f"{args.out}.json").write_text(json.dumps(report, indent=1) + "\n")
    lines = [
        "# First run against later ones: `enumerate SPACE --identify`, cold (empty cache) and warm",
        "",
        f"Commit {report['provenance']['commit']}, lkspace {report['provenance']['lkspace']}, "
        f"{report['provenance']['machine']['cpu_count']} CPUs, {report['provenance']['date']}; "
        f"load average {report['load_start']} at the start, {report['load_end']} at the end.",
        "",
        "| space | tree | cold median (s) | warm median (s) | warm CPU (s) | warm designs/s | keys/s in-process "
        "(by threads) | cold / warm | load (1 min) during cold runs |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for space, by_tree in report["spaces"].items():
        for label, r in by_tree.items():
            lines.append(
                f"| {space} | {label} ({report[f'{label}_commit']}) | {r['cold']['median_s']} | "
                f"{r['warm']['median_s']} | {r['warm']['cpu_median_s']} | {r['warm_rate']:,} | "
                f"{', '.join(f'{n}: {v:,}' for n, v in r['key_rate'].items())} | {r['ratio']} "
                f"| {r['cold']['load_1min']} |"
            )
    (RESULTS / f"{args.out}.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
