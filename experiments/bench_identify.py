"""Benchmark: realization and identification time versus crossing count.

Designs: the torus families ``dihedron:N`` (all labels 1: T(2, N)) and ``book:K`` with
twist t (T(K, t)), and random labels in -2..2 (seeded) on the Platonic solids.  For each
design it times :func:`lkspace.geometry.realize` (with the embedding check) and
:func:`lkspace.knots.recognition.identify_curves` (projection, PD code, simplification, table
lookup) separately, best of three, after a warm-up that loads the KnotInfo/LinkInfo
index.  Writes ``results/bench_identify.json``.  Target: under 1 s in total for diagrams
of up to 30 crossings.

Run: ``python experiments/bench_identify.py [--random 6]``.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time

import numpy as np

import lkspace
from lkspace.geometry.realization import realize
from lkspace.knots.recognition import identify_curves
from lkspace.knots.tables import tables


def designs(n_random: int, rng: np.random.Generator):
    for n in (3, 5, 8, 11, 15, 20, 25, 30, 35):
        yield f"dihedron:{n}", 1
    for k, t in ((3, 2), (3, 4), (3, 7), (4, 3), (4, 5), (4, 7), (5, 4), (5, 6), (6, 5), (7, 5)):
        yield f"book:{k}", t
    for name in ("tetrahedron", "cube", "octahedron", "icosahedron"):
        s = lkspace.load(name)
        for _ in range(n_random):
            yield name, rng.integers(-2, 3, s.n_edges)


def best_of(fn, repeat=3):
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--random", type=int, default=6, help="random designs per solid")
    parser.add_argument(
        "--out", default=os.path.join(os.path.dirname(__file__), "..", "results", "bench_identify.json")
    )
    args = parser.parse_args()
    t0 = time.perf_counter()
    tables()
    identify_curves(realize(lkspace.load("dihedron:3"), 1).curves)
    warmup = time.perf_counter() - t0
    rng = np.random.default_rng(0)
    rows = []
    for name, twists in designs(args.random, rng):
        s = lkspace.load(name)
        t_real, real = best_of(lambda s=s, twists=twists: realize(s, twists))
        t_id, found = best_of(lambda real=real: identify_curves(real.curves))
        res = found.to_json()
        row = {
            "scaffold": name,
            "twists": np.atleast_1d(twists).tolist(),
            "components": res["components"],
            "points": int(sum(len(c) for c in real.curves)),
            "projected_crossings": res["projected_crossings"],
            "crossings": res.get("crossings"),
            "name": res["name"],
            "realize_s": round(t_real, 4),
            "identify_s": round(t_id, 4),
            "total_s": round(t_real + t_id, 4),
        }
        rows.append(row)
        print(
            f"{name:14s} {str(row['twists'])[:24]:24s} comps {row['components']:2d}  crossings "
            f"{row['projected_crossings']:3d} -> {str(row['crossings']):>4s}  {str(row['name']):8s} "
            f"realize {t_real:6.3f} s  identify {t_id:6.3f} s"
        )
    upto30 = [r["total_s"] for r in rows if r["projected_crossings"] <= 30]
    summary = {
        "designs": len(rows),
        "warmup_s": round(warmup, 3),
        "max_total_s_up_to_30_crossings": max(upto30) if upto30 else None,
        "median_total_s_up_to_30_crossings": float(np.median(upto30)) if upto30 else None,
        "target_s": 1.0,
    }
    print(json.dumps(summary))
    from lkspace.io.atomic import write_text

    write_text(
        args.out,
        json.dumps(
            {
                "benchmark": "identify",
                "machine": {"cpus": os.cpu_count(), "python": platform.python_version()},
                "summary": summary,
                "rows": rows,
            },
            indent=1,
        )
        + "\n",
    )


if __name__ == "__main__":
    main()
