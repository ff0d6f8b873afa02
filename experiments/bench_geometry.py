"""Benchmark: ropelength of the exported curves, construction vs smoothed default vs relaxed.

For each design (the five knots and links of issue 21),
three OBJ files are written with the installed ``lkspace export``: the construction
polylines (``GeometryParams(smooth=False)``, what lkspace drew before the smoothing; written
through the Python API because the CLI always smooths), the default export, and
``--relax``.  Ropelength (length / tube radius) is measured on each OBJ by
``tests/ropelength.py`` (independent of lkspace's geometry code) and compared with the
least known value (ropelength literature).  Relax time is the wall time of the
``lkspace export --relax`` call minus that of the default call (the machine is shared:
noisy).  Writes ``results/bench_geometry.json`` and ``results/bench_geometry.md`` with the
commit, version and load average.

Run: ``python experiments/bench_geometry.py``.
"""

from __future__ import annotations

import json
import os
import platform
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..")
sys.path.insert(0, ROOT)

from tests.ropelength import read_obj_polylines, ropelength  # noqa: E402

DESIGNS = [
    ("trefoil", "dihedron:3", "1", 32.74),
    ("figure-eight", "figure-eight", "0,-1,-1,-1,-1", 42.09),
    ("5_1", "dihedron:5", "1", 47.20),
    ("Hopf", "dihedron:4", "0,0,-1,-1", 25.13),
    ("Borromean", "tetrahedron", "1", 58.01),
]
"""(name, mesh, twist, least known ropelength) of the five designs of issue 21 (ropelength literature)."""


def export(mesh: str, twist: str | None, path: str, *extra: str) -> float:
    """Run ``lkspace export``; return its wall time in seconds."""
    args = ["lkspace", "export", mesh, *([f"--twist={twist}"] if twist else []), "-o", path, *extra]
    t0 = time.perf_counter()
    subprocess.run(args, check=True, capture_output=True)
    return time.perf_counter() - t0


def construction(mesh: str, twist: str | None, path: str) -> None:
    """Write the unsmoothed construction polylines of the design as OBJ."""
    import lkspace

    labels = None if twist is None else [int(x) for x in twist.split(",")]
    if labels is not None and len(labels) == 1:
        labels = labels[0]
    real = lkspace.realize(mesh, labels, params=lkspace.GeometryParams(smooth=False))
    lkspace.export(real, path)


def main() -> None:
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for name, mesh, twist, least in DESIGNS:
            paths = {k: os.path.join(folder, f"{k}.obj") for k in ("construction", "default", "relaxed")}
            construction(mesh, twist, paths["construction"])
            t_default = export(mesh, twist, paths["default"])
            t_relaxed = export(mesh, twist, paths["relaxed"], "--relax")
            row = {"design": name, "mesh": mesh, "twist": twist, "least": least}
            for key, path in paths.items():
                row[key] = round(ropelength(read_obj_polylines(path))["ropelength"], 2)
            row["relax_seconds"] = round(max(t_relaxed - t_default, 0.0), 2)
            rows.append(row)
            print(row, flush=True)
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout
    import lkspace

    meta = {
        "commit": commit.strip(),
        "version": lkspace.__version__,
        "machine": f"{platform.machine()}, {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}",
        "python": platform.python_version(),
    }
    results = os.path.join(ROOT, "results")
    with open(os.path.join(results, "bench_geometry.json"), "w") as handle:
        json.dump({"meta": meta, "rows": rows}, handle, indent=1)
    lines = [
        "# Ropelength of exported curves: construction, smoothed default, relaxed",
        "",
        "Made by `python experiments/bench_geometry.py`: ropelength = length / tube radius (the smaller of",
        "the least curvature radius and half the least doubly critical distance), measured on the exported",
        "OBJ by `tests/ropelength.py`; *least* is the smallest value known (ropelength literature).",
        f"Commit {meta['commit']}, lkspace {meta['version']}, {meta['machine']}.",
        "",
        "| design | least | construction | default | relaxed | relaxed / least | relax time (s) |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['design']} (`{r['mesh']}`{' --twist ' + r['twist'] if r['twist'] else ''}) | {r['least']} | "
            f"{r['construction']} ({r['construction'] / r['least']:.1f}x) | {r['default']} ({r['default'] / r['least']:.1f}x) | "
            f"{r['relaxed']} | {r['relaxed'] / r['least']:.2f} | {r['relax_seconds']} |"
        )
    with open(os.path.join(results, "bench_geometry.md"), "w") as handle:
        handle.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
