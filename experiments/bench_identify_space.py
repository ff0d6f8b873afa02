"""Identifying whole design spaces as users run it: ``enumerate --identify`` and ``solve --type``, end to end.

Every figure is a fresh ``lkspace`` process (:func:`benchkit.timed`), beside the kernel's
own rate (designs keyed per second in one process, after a warm-up).  The names each
distinct key gets are kept on disk (``$LKSPACE_CACHE``); the runs are timed **cold** (an
empty name cache: every distinct key named in full, the first run on a machine) and
**warm** (the cache an earlier run left), each with ``--jobs 2`` and with ``--scheduler
dask`` (a LocalCluster of 2 workers).  In the same run, the geometric path (each design
realized, projected and named on its own, one process) is timed on a sample of the same
space: the ratios compare the two.

Usage: ``python experiments/bench_identify_space.py [--quick]``; writes
``results/bench_identify_space.{json,md}``.
"""

from __future__ import annotations

import argparse
import glob
import json
import os
import shutil
import sys
import tempfile
import time

import numpy as np
from benchkit import RESULTS, load_average, provenance, summary, timed

LKSPACE = [sys.executable, "-m", "lkspace"]
SPACES = [("cube", "-1..1", 22_815), ("tetrahedron", "-2..2", 1_475), ("octahedron", "-1..1", None)]
TARGETS = [
    ("octahedron", "L5a1", "-1..1"),
    ("octahedron", "5_2", "-1..1"),
    ("cube", "6_2", "-1..1"),
    ("cube", "3_1", "-1..1"),
    ("cube", "Borromean rings", "-1..1"),
    ("tetrahedron", "7_4", "-1..1"),
]


def cache_dir(warm_from: str | None) -> str:
    """A fresh ``$LKSPACE_CACHE`` with the knot tables' index (and, for warm runs, the names of ``warm_from``)."""
    path = tempfile.mkdtemp(prefix="lkspace-bench-")
    home = os.path.join(os.path.expanduser("~"), ".cache", "lkspace")
    for table in glob.glob(os.path.join(home, "knot-tables-*.pickle")):
        shutil.copy(table, path)
    if warm_from:
        for names in glob.glob(os.path.join(warm_from, "names-by-key-*.jsonl")):
            shutil.copy(names, path)
    return path


def enumerate_run(name: str, labels: str, cache: str, dask: bool) -> dict:
    out = tempfile.mkdtemp(prefix="lkspace-bench-out-")
    cmd = [*LKSPACE, "enumerate", name, "--labels", labels, "--identify", "--jobs", "2", "-o", f"{out}/c.parquet"]
    if dask:
        cmd += ["--scheduler", "dask"]
    try:
        return timed(cmd, env={**os.environ, "LKSPACE_CACHE": cache})
    finally:
        shutil.rmtree(out, ignore_errors=True)


def kernel_rate(name: str, labels: str) -> dict:
    """Designs keyed per second by :func:`lkspace.knots.keyed.keys_of`, in this process."""
    import lkspace
    from lkspace.knots.keyed import keys_of

    scaffold = lkspace.load(name)
    rows = np.vstack([np.stack(b["labels"].to_numpy()) for b in lkspace.designs(scaffold, labels)])
    keys_of(scaffold, rows[:10])  # compile or load the kernels
    start = time.perf_counter()
    keys_of(scaffold, rows)
    seconds = time.perf_counter() - start
    return {"designs": len(rows), "seconds": round(seconds, 3), "designs_per_s": round(len(rows) / seconds)}


GEOMETRIC = """
import sys, time, numpy as np, lkspace
from lkspace.knots.recognition import identify
s = lkspace.load(sys.argv[1])
rows = np.vstack([np.stack(b["labels"].to_numpy()) for b in lkspace.designs(s, sys.argv[2])])
rows = rows[np.random.default_rng(0).choice(len(rows), min(int(sys.argv[3]), len(rows)), replace=False)]
identify(s, rows[0])
t = time.perf_counter()
for r in rows:
    identify(s, r)
print(len(rows) / (time.perf_counter() - t))
"""


def geometric_rate(name: str, labels: str, sample: int) -> float:
    """Designs per second of the geometric path (each realized, projected, named: one process), on a sample."""
    import subprocess

    out = subprocess.run([sys.executable, "-c", GEOMETRIC, name, labels, str(sample)], capture_output=True, text=True)
    return round(float(out.stdout.split()[-1]), 1)


def measure(quick: bool) -> dict:
    runs = 1 if quick else 3
    data: dict = {"provenance": provenance(), "load_before": load_average(), "spaces": [], "targets": []}
    for name, labels, _ in SPACES[:1] if quick else SPACES:
        cold_cache = cache_dir(None)
        cold = enumerate_run(name, labels, cold_cache, dask=False)
        warm = summary([enumerate_run(name, labels, cache_dir(cold_cache), dask=False) for _ in range(runs)])
        dask = summary([enumerate_run(name, labels, cache_dir(cold_cache), dask=True) for _ in range(runs)])
        rate = kernel_rate(name, labels)
        n = rate["designs"]
        old = geometric_rate(name, labels, 60 if quick else 200)
        data["spaces"].append(
            {
                "space": f"{name} {labels}",
                "designs": n,
                "cold_s": round(cold["wall"], 2),
                "cold_designs_per_s": round(n / cold["wall"]),
                "warm": warm,
                "warm_designs_per_s": round(n / warm["median_s"]),
                "dask": dask,
                "dask_designs_per_s": round(n / dask["median_s"]),
                "kernel": rate,
                "geometric_designs_per_s": old,
                "warm_over_geometric": round(n / warm["median_s"] / old, 1),
                "cold_over_geometric": round(n / cold["wall"] / old, 1),
            }
        )
        shutil.rmtree(cold_cache, ignore_errors=True)
    for name, target, labels in TARGETS[:2] if quick else TARGETS:
        cache = cache_dir(None)
        cmd = [*LKSPACE, "solve", name, "--type", target, "--labels", labels, "--json"]
        cold = timed(cmd, env={**os.environ, "LKSPACE_CACHE": cache})
        warm = timed(cmd, env={**os.environ, "LKSPACE_CACHE": cache})
        data["targets"].append(
            {
                "query": f"solve {name} --type '{target}' --labels {labels}",
                "cold_s": round(cold["wall"], 2),
                "warm_s": round(warm["wall"], 2),
            }
        )
        shutil.rmtree(cache, ignore_errors=True)
    data["load_after"] = load_average()
    return data


def markdown(data: dict) -> str:
    p = data["provenance"]
    lines = [
        "# Identifying whole design spaces, end to end",
        "",
        f"lkspace {p['lkspace']} at {p['commit']}{' (dirty)' if p['dirty'] else ''}, {p['date']}; "
        f"{p['machine']['cpu_count']} CPUs ({p['machine']['cpu']}); load {data['load_before']} before, "
        f"{data['load_after']} after. `python experiments/bench_identify_space.py`",
        "",
        "Each figure is a fresh `lkspace` process: `enumerate NAME --labels SET --identify --jobs 2`. "
        "Cold: an empty name cache (every distinct key named in full); warm: the cache a cold run left; "
        "dask: warm, `--scheduler dask` (LocalCluster, 2 workers). Kernel: designs keyed per second in one process. "
        "Geometric: `identify` (realize, project, name) on a sample of the space, one process.",
        "",
        "| space | designs | cold (s) | cold designs/s | warm (s) | warm designs/s | dask (s) | dask designs/s "
        "| kernel designs/s | geometric designs/s | warm / geometric | cold / geometric |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for s in data["spaces"]:
        lines.append(
            f"| {s['space']} | {s['designs']:,} | {s['cold_s']} | {s['cold_designs_per_s']:,} | {s['warm']['median_s']} "
            f"| {s['warm_designs_per_s']:,} | {s['dask']['median_s']} | {s['dask_designs_per_s']:,} "
            f"| {s['kernel']['designs_per_s']:,} | {s['geometric_designs_per_s']} | {s['warm_over_geometric']}x "
            f"| {s['cold_over_geometric']}x |"
        )
    lines += ["", "## `solve --type`, end to end", "", "| query | cold (s) | warm (s) |", "|---|---|---|"]
    for t in data["targets"]:
        lines.append(f"| `{t['query']}` | {t['cold_s']} | {t['warm_s']} |")
    return "\n".join(lines) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="the cube and two targets, one run each")
    args = parser.parse_args()
    data = measure(args.quick)
    (RESULTS / "bench_identify_space.json").write_text(json.dumps(data, indent=1) + "\n")
    (RESULTS / "bench_identify_space.md").write_text(markdown(data))
    print(markdown(data))


if __name__ == "__main__":
    main()
