"""Benchmark: trace time versus corner count on subdivided cube-spheres.

Each face of the cube [-1, 1]^3 is split into n x n quads and projected onto the unit
sphere (6 n^2 quads, 24 n^2 corners).  Labels are random in -2..2 (seeded).  Reports the
time to build the scaffold's derived data once (edges, radial order, port model) and the
time of one ``trace`` call on it, and writes ``results/bench_trace.json``.

Run: ``python experiments/bench_trace.py [--max-corners 4000000]``.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time

import numpy as np

import lkspace
from lkspace.strands.ports import port_model


def cube_sphere(n: int) -> lkspace.Scaffold:
    """Cube-sphere with ``6 n^2`` quads (vertices shared along the cube's seams)."""
    grid = np.linspace(-1.0, 1.0, n + 1)
    points, faces = [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            u, v = np.meshgrid(grid, grid, indexing="ij")
            p = np.zeros((n + 1, n + 1, 3))
            p[..., axis] = sign
            p[..., (axis + 1) % 3] = u
            p[..., (axis + 2) % 3] = v
            base = sum(len(x) for x in points)
            points.append(p.reshape(-1, 3))
            idx = base + np.arange((n + 1) ** 2).reshape(n + 1, n + 1)
            q = np.stack([idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]], axis=-1).reshape(-1, 4)
            faces.append(q if sign > 0 else q[:, ::-1])
    points = np.concatenate(points)
    faces = np.concatenate(faces)
    keys = np.round(points * n * 4).astype(np.int64)
    unique, inverse = np.unique(keys, axis=0, return_inverse=True)
    merged = np.zeros((len(unique), 3))
    merged[inverse.reshape(-1)] = points
    merged /= np.linalg.norm(merged, axis=1, keepdims=True)
    faces = inverse.reshape(-1)[faces]
    starts = np.arange(0, 4 * len(faces) + 1, 4, dtype=np.int64)
    return lkspace.Scaffold(merged, starts, faces.reshape(-1), name=f"cube-sphere:{n}")


def measure(n: int, rng: np.random.Generator) -> dict:
    t0 = time.perf_counter()
    s = cube_sphere(n)
    t1 = time.perf_counter()
    s.radial
    port_model(s)
    t2 = time.perf_counter()
    twists = rng.integers(-2, 3, s.n_edges)
    best = float("inf")
    for _ in range(3):
        t3 = time.perf_counter()
        result = lkspace.trace(s, twists)
        result.holds_together
        best = min(best, time.perf_counter() - t3)
    return {
        "n": n,
        "faces": s.n_faces,
        "edges": s.n_edges,
        "corners": s.n_corners,
        "build_s": round(t1 - t0, 4),
        "prepare_s": round(t2 - t1, 4),
        "trace_s": round(best, 4),
        "corners_per_s": round(s.n_corners / best),
        "corners_per_s_with_prepare": round(s.n_corners / (best + t2 - t1)),
        "components": result.components,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max-corners", type=int, default=4_000_000)
    parser.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "..", "results", "bench_trace.json"))
    args = parser.parse_args()
    rng = np.random.default_rng(0)
    lkspace.trace(lkspace.load("cube"), 1)  # compile the numba kernel outside the timings
    rows = []
    n = 4
    while 24 * n * n <= args.max_corners:
        rows.append(measure(n, rng))
        print(json.dumps(rows[-1]))
        n *= 2
    report = {
        "benchmark": "trace",
        "machine": {"cpus": os.cpu_count(), "python": platform.python_version()},
        "target_corners_per_s": 1_000_000,
        "rows": rows,
    }
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, "w") as fh:
        json.dump(report, fh, indent=1)


if __name__ == "__main__":
    main()
