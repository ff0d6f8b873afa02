"""Benchmark: writing tube meshes (PLY, STL, 3MF, OBJ) and building them.

One large design, ``icosahedron --twist 3`` realized with dense sampling and unsmoothed
(smoothing resamples the curves: about 4,000 points; unsmoothed about 100,000 curve
points, 1.2 million tube vertices), is written as PLY tubes, and when the writers
exist as STL and 3MF; the tube build alone is timed too.  Best of ``--repeat`` runs (the
machine is shared: numbers are noisy, the best run is the fairest).  Writes
``results/bench_export.json``; ``--label`` names the run (e.g. ``before``, ``after``)
and runs are merged into the file by label.

Run: ``python experiments/bench_export.py --label after``.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import tempfile
import time

import lkspace
from lkspace.formats.options import MeshOptions, PrintOptions
from lkspace.formats.registry import ENCODERS, export
from lkspace.geometry.realization import GeometryParams, realize


def best_of(fn, repeat):
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--label", default="after")
    parser.add_argument("--repeat", type=int, default=3)
    here = os.path.dirname(os.path.abspath(__file__))
    parser.add_argument("--out", default=os.path.join(here, "..", "results", "bench_export.json"))
    args = parser.parse_args()
    params = GeometryParams(samples_per_turn=500, edge_samples=600, corner_samples=200, smooth=False)
    real = realize(lkspace.load("icosahedron"), 3, params=params)
    points = sum(len(c) for c in real.curves)
    row: dict[str, object] = {
        "commit": subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True
        ).stdout.strip(),
        "design": "icosahedron --twist 3 (dense sampling)",
        "curve_points": points,
        "tube_vertices": points * 12,
    }
    from lkspace.formats import tubes

    row["tube_build_s"] = best_of(lambda: tubes.tube_meshes(real, None, 12), args.repeat)
    with tempfile.TemporaryDirectory() as tmp:
        for ext in (".ply", ".stl", ".3mf", ".obj"):
            if ext not in ENCODERS:
                continue
            path = os.path.join(tmp, "x" + ext)
            options = PrintOptions() if ext in (".stl", ".3mf") else MeshOptions(tubes=True)
            row[f"write{ext}_s"] = best_of(lambda p=path, o=options: export(real, p, options=o), args.repeat)
            row[f"size{ext}_bytes"] = os.path.getsize(path)
    row["python"] = platform.python_version()
    results = {}
    if os.path.exists(args.out):
        with open(args.out) as fh:
            results = json.load(fh)
    results[args.label] = row
    with open(args.out, "w") as fh:
        json.dump(results, fh, indent=1)
    print(json.dumps(row, indent=1))


if __name__ == "__main__":
    main()
