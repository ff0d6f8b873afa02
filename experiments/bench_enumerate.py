"""Benchmark: the full catalog of the cube with labels -2..2 under rotations.

244,140,625 assignments -> 10,194,250 designs, written to Parquet.  Also times a
straightforward per-assignment implementation (trace every assignment, test it for being
its orbit's smallest member by applying the whole group) on a random sample and
extrapolates it to the whole space.

Run from the repository root::

    python experiments/bench_enumerate.py [--jobs 2] [--sample 20000]

Writes ``results/bench_enumerate.json`` and ``results/bench_enumerate.md``.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import shutil
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

import lkspace  # noqa: E402
from lkspace.catalog.shards import write_catalog  # noqa: E402
from lkspace.design.counting import count_space
from lkspace.design.space import make_space  # noqa: E402
from lkspace.io.atomic import write_text  # noqa: E402

RESULTS = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "results")


def naive_rate(space, n_sample: int, seed: int = 0) -> dict:
    """Seconds per assignment of the per-assignment implementation, on a random sample."""
    sc = space.scaffold
    labels = space.label_set
    perms, signs = space.action
    inv = np.argsort(perms, axis=1)
    rng = np.random.default_rng(seed)
    sample = labels[rng.integers(0, len(labels), (n_sample, sc.n_edges))]
    lkspace.trace(sc, sample[0])  # compile outside the timing
    start = time.perf_counter()
    kept = 0
    for t in sample:
        images = signs[:, None] * t[inv]  # (n_g, n_edges): every image in edge order
        key = np.concatenate([images % 2, images], axis=1)
        own = np.concatenate([t % 2, t])
        smaller = False
        for row in key:  # lexicographic comparison with the assignment itself
            diff = np.flatnonzero(row != own)
            if len(diff) and row[diff[0]] < own[diff[0]]:
                smaller = True
                break
        components = lkspace.trace(sc, t).components
        kept += (not smaller) and components > 0
    seconds = time.perf_counter() - start
    return {
        "sample": n_sample,
        "seconds": seconds,
        "seconds_per_assignment": seconds / n_sample,
        "canonical_in_sample": kept,
    }


def peak_rss_mb() -> dict:
    own = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    kids = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    return {"main_mb": round(own, 1), "largest_child_mb": round(kids, 1)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--sample", type=int, default=20_000)
    ap.add_argument("--keep", help="keep the catalog at this path instead of a temporary folder")
    args = ap.parse_args()

    space = make_space("cube", "-2..2", "rotations")
    # warm up: numba compilation and the symmetry group, outside the timing
    write_catalog(make_space("tetrahedron", "-2..2"), os.path.join(tempfile.mkdtemp(), "warm.parquet"))
    t0 = time.perf_counter()
    totals = count_space(space)
    t_count = time.perf_counter() - t0

    out_dir = args.keep or tempfile.mkdtemp(prefix="lkspace-bench-")
    path = os.path.join(out_dir, "cube-2..2.parquet") if not args.keep else args.keep
    t0 = time.perf_counter()
    written = write_catalog(space, path, jobs=args.jobs)
    t_write = time.perf_counter() - t0
    memory = peak_rss_mb()
    size = (
        sum(os.path.getsize(os.path.join(path, f)) for f in os.listdir(path))
        if os.path.isdir(path)
        else os.path.getsize(path)
    )

    t0 = time.perf_counter()
    import pandas as pd

    df = pd.read_parquet(path, columns=["components", "orbit_size", "n_zero"])
    t_read = time.perf_counter() - t0
    assert len(df) == written.designs == 10_194_250
    assert int(df.orbit_size.sum()) == 244_140_625
    if not args.keep:
        shutil.rmtree(out_dir)

    naive = naive_rate(space, args.sample)
    naive_total = naive["seconds_per_assignment"] * space.assignments
    result = {
        "scaffold": "cube",
        "labels": "-2..2",
        "symmetry": "rotations",
        "assignments": space.assignments,
        "designs": written.designs,
        "by_components": written.by_components,
        "burnside_count_seconds": round(t_count, 3),
        "burnside_designs": totals.designs,
        "catalog_seconds": round(t_write, 2),
        "jobs": args.jobs,
        "shards": written.shards,
        "assignments_per_second": round(space.assignments / t_write),
        "designs_per_second": round(written.designs / t_write),
        "catalog_bytes": size,
        "read_back_seconds_3_columns": round(t_read, 2),
        "peak_memory": memory,
        "naive": {
            **naive,
            "extrapolated_seconds": round(naive_total),
            "extrapolated_hours": round(naive_total / 3600, 1),
        },
        "speedup_vs_naive": round(naive_total / t_write),
        "machine": {
            "cpus": os.cpu_count(),
            "python": platform.python_version(),
            "platform": platform.platform(),
            "load_average_at_end": list(os.getloadavg()),
        },
    }
    os.makedirs(RESULTS, exist_ok=True)
    write_text(os.path.join(RESULTS, "bench_enumerate.json"), json.dumps(result, indent=1) + "\n")
    md = f"""# Benchmark: cube, labels -2..2, rotations

| quantity | value |
|---|---|
| assignments | {space.assignments:,} |
| designs (rows written) | {written.designs:,} |
| Burnside count (no rows) | {t_count:.2f} s |
| full catalog to Parquet ({args.jobs} jobs, {written.shards} shards) | **{t_write:.1f} s** |
| assignments per second | {space.assignments / t_write:,.0f} |
| designs (rows) per second | {written.designs / t_write:,.0f} |
| catalog size | {size / 1e6:.0f} MB |
| peak RSS, main process / largest worker | {memory["main_mb"]:.0f} MB / {memory["largest_child_mb"]:.0f} MB |
| per-assignment implementation (sample {args.sample:,}) | {naive["seconds_per_assignment"] * 1e6:.1f} us per assignment |
| ... extrapolated to all assignments | {naive_total / 3600:.1f} h |
| speed-up | {naive_total / t_write:,.0f}x |

Load average at the end of the run: {", ".join(f"{x:.1f}" for x in os.getloadavg())} (other processes share the 2 cores).

Per-assignment implementation: for every assignment, build all group images, test whether
it is the smallest (same canonical rule as the catalog), and trace it with `lkspace.trace`.
"""
    write_text(os.path.join(RESULTS, "bench_enumerate.md"), md)
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
