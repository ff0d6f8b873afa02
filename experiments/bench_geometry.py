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

``--timing [--before REV]`` measures instead how long ``lkspace.realize`` takes in a warm
process (issue 34: a cube design in 30 ms), the default and with ``embedding="later"``
(the studio's redraw), on designs of the cube, tetrahedron, dodecahedron, dihedra and
cP honeycomb, together with the default curves' ropelength (``tests/ropelength.py``) on
the small knots above; each tree (this one, and the tree at git revision ``REV`` from
``git archive``) in a fresh process, one after the other, so both columns share a
machine load.  Writes ``results/bench_realize.json`` and ``results/bench_realize.md``.
"""

from __future__ import annotations

import json
import math
import os
import platform
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..")
sys.path.insert(0, ROOT)

from tests.ropelength import most_turning, read_obj_polylines, ropelength  # noqa: E402

DESIGNS = [
    ("trefoil", "dihedron:3", "1", 32.74),
    ("figure-eight", "figure-eight", "0,-1,-1,-1,-1", 42.09),
    ("5_1", "dihedron:5", "1", 47.20),
    ("5_2", "figure-eight", "-2,-1,-1,-1,0", 49.47),
    ("Hopf", "dihedron:4", "0,0,-1,-1", 25.13),
    ("Hopf (lookup)", "dihedron:3", "-2,0,0", 25.13),
    ("Borromean", "tetrahedron", "1", 58.01),
]
"""(name, mesh, twist, least known ropelength): the five designs of issue 21 (ropelength literature),
5_2 and the Hopf link as ``lkspace lookup`` finds them."""


TIMED = [
    ("cube", [1, 0, -1, 1, 1, 0, 2, 1, 0, 1, 1, 1]),
    ("cube", 1),
    ("tetrahedron", 1),
    ("dodecahedron", 1),
    ("dihedron:3", 1),
    ("figure-eight", [0, -1, -1, -1, -1]),
    ("truncated-octahedron", 1),
    ("honeycomb:cP", 1),
    ("honeycomb:cP@2x2x2", 1),
]
"""(mesh, labels) of the designs :func:`timing` realizes."""


def timing(repeats: int = 9) -> dict:
    """Warm in-process ``realize`` times (median and best, wall and CPU ms) and the default curves' ropelength.

    ``lkspace`` must come first on ``sys.path`` (the caller puts the tree measured there:
    this module puts the repository's root on it for ``tests.ropelength``).
    """
    import statistics

    import lkspace

    rows = []
    for mesh, labels in TIMED:
        scaffold = lkspace.load(mesh)
        row: dict = {"design": f"{mesh} {labels}"}
        for mode in ("refuse", "later"):
            options = lkspace.RealizeOptions(embedding=mode)
            real = lkspace.realize(scaffold, labels, options=options)  # warm: compiled, cached
            walls, cpus = [], []
            for _ in range(repeats):
                w0, c0 = time.perf_counter(), time.process_time()
                lkspace.realize(scaffold, labels, options=options)
                walls.append(1e3 * (time.perf_counter() - w0))
                cpus.append(1e3 * (time.process_time() - c0))
            row[mode] = {
                "wall_median_ms": round(statistics.median(walls), 1),
                "wall_best_ms": round(min(walls), 1),
                "cpu_median_ms": round(statistics.median(cpus), 1),
            }
        row["points"] = int(sum(len(c) for c in real.curves))
        rows.append(row)
        print(row, flush=True)
    ropes = [default_shape(lkspace, *design) for design in DESIGNS]
    return {"rows": rows, "ropelength": ropes}


def default_shape(lkspace, name: str, mesh: str, twist: str, least: float) -> dict:
    """The default curves of a design against its construction, measured by ``tests/ropelength.py``.

    Ropelength and its ratio to the least known; the least curvature radius over the tube
    radius; the most any stretch of 2 pi insets turns (pi); the farthest a point lies from
    its strand's construction (insets: how far the smoothing drew it off its face).
    """
    from scipy.spatial import cKDTree

    labels = [int(x) for x in twist.split(",")]
    labels = labels[0] if len(labels) == 1 else labels
    real = lkspace.realize(mesh, labels)
    raw = lkspace.realize(mesh, labels, params=lkspace.GeometryParams(smooth=False))
    measured = ropelength([(c, True) for c in real.curves])
    inset = real.radius
    drift = max(float(cKDTree(b).query(a)[0].max()) for a, b in zip(real.curves, raw.curves, strict=True))
    return {
        "design": name,
        "least": least,
        "default": round(measured["ropelength"], 2),
        "ratio": round(measured["ropelength"] / least, 2),
        "bend_over_tube": round(measured["curvature_radius"] / real.tube_radius, 2),
        "turning_pi": round(max(most_turning(c, True, 2 * math.pi * inset) for c in real.curves) / math.pi, 2),
        "drift_insets": round(drift / inset, 2),
    }


def timing_tables(trees: dict[str, dict], meta: dict) -> str:
    """Markdown of :func:`timing` for each tree, side by side."""
    names = list(trees)
    lines = [
        "# `lkspace.realize` in a warm process (issue 34: a cube design in 30 ms)",
        "",
        "Made by `python experiments/bench_geometry.py --timing --before REV`; each tree in a fresh",
        "process, the design realized once before timing (numba kernels compiled and loaded), then",
        f"{meta['repeats']} timed runs: median wall ms (best; median CPU ms).  `refuse`: the default",
        "(embedding checked before the smoothing and measured after); `later`: `RealizeOptions(embedding=",
        '"later")`, the studio\'s redraw (the check before the smoothing only).',
        f"Commit {meta['commit']} (dirty: {meta['dirty']}), before = {meta['before']}; {meta['date']}; "
        f"{meta['machine']['cpu_count']} CPUs ({meta['machine']['cpu']}), shared; load {meta['load_start']} -> "
        f"{meta['load_end']}.",
        "",
        "| design | points | " + " | ".join(f"{t} refuse | {t} later" for t in names) + " |",
        "|---|---:|" + "---:|---:|" * len(names),
    ]

    def cell(m: dict) -> str:
        return f"{m['wall_median_ms']} ({m['wall_best_ms']}; {m['cpu_median_ms']})"

    for k, row in enumerate(trees[names[0]]["rows"]):
        cells = [f"{cell(trees[t]['rows'][k]['refuse'])} | {cell(trees[t]['rows'][k]['later'])}" for t in names]
        lines.append(f"| {row['design']} | {row['points']} | " + " | ".join(cells) + " |")
    lines += [
        "",
        "`python -m lkspace export cube --twist 1 -o c.obj` in a fresh process (imports, numba's on-disk cache",
        "warm), median of 5 (best), wall and CPU seconds: "
        + "; ".join(
            f"{t} {trees[t]['cold_export']['median_s']} s ({trees[t]['cold_export']['best_s']}), "
            f"CPU {trees[t]['cold_export']['cpu_median_s']} s"
            for t in names
        )
        + ".",
    ]
    lines += [
        "",
        "The default curves, measured by `tests/ropelength.py`: ropelength (length / rope radius) and its ratio",
        "to the least known; least curvature radius / tube radius; the most any stretch of 2π insets turns",
        "(× π: a curl of the inset's radius turns 2π); the farthest point from its strand's construction (insets):",
        "",
        "| design | least | "
        + " | ".join(f"{t} ropelength (ratio) | {t} bend / tube | {t} turning | {t} drift" for t in names)
        + " |",
        "|---|---:|" + "---:|---:|---:|---:|" * len(names),
    ]
    for k, rope in enumerate(trees[names[0]]["ropelength"]):
        cells = []
        for t in names:
            m = trees[t]["ropelength"][k]
            cells.append(
                f"{m['default']} ({m['ratio']}x) | {m['bend_over_tube']} | {m['turning_pi']} | {m['drift_insets']}"
            )
        lines.append(f"| {rope['design']} | {rope['least']} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def timing_main(before: str | None, repeats: int) -> None:
    """Run :func:`timing` in a fresh process per tree; write ``results/bench_realize.{json,md}``."""
    import tarfile

    sys.path.insert(0, HERE)
    from benchkit import git, load_average, provenance, summary, timed

    def run(tree: str) -> dict:
        env = {**os.environ, "PYTHONPATH": tree}
        code = (
            f"import sys, json; sys.path.insert(0, {HERE!r}); import bench_geometry as b; sys.path.insert(0, {tree!r}); "
            f"import lkspace; assert lkspace.__file__.startswith({tree!r}), lkspace.__file__; "
            f"print(json.dumps(b.timing({repeats})))"
        )
        out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
        return json.loads(out.stdout.strip().splitlines()[-1])

    def cold(tree: str) -> dict:
        """``python -m lkspace export cube --twist 1`` in fresh processes (caches warm: one untimed run first)."""
        env = {**os.environ, "PYTHONPATH": tree}
        with tempfile.TemporaryDirectory() as out:
            cmd = [sys.executable, "-m", "lkspace", "export", "cube", "--twist", "1", "-o", os.path.join(out, "c.obj")]
            timed(cmd, env)
            return summary([timed(cmd, env) for _ in range(5)])

    load_start = load_average()
    trees = {}
    if before:
        with tempfile.TemporaryDirectory() as folder:
            archive = os.path.join(folder, "tree.tar")
            subprocess.run(["git", "-C", ROOT, "archive", "-o", archive, before], check=True)
            with tarfile.open(archive) as tar:
                tar.extractall(folder, filter="data")
            trees["before"] = {**run(folder), "cold_export": cold(folder)}
    after = os.path.abspath(ROOT)
    trees["after"] = {**run(after), "cold_export": cold(after)}
    meta = {
        **provenance(),
        "before": git(ROOT, "rev-parse", "--short", before) if before else None,
        "repeats": repeats,
        "load_start": load_start,
        "load_end": load_average(),
    }
    results = os.path.join(ROOT, "results")
    with open(os.path.join(results, "bench_realize.json"), "w") as handle:
        json.dump({"meta": meta, "trees": trees}, handle, indent=1)
    text = timing_tables(trees, meta)
    with open(os.path.join(results, "bench_realize.md"), "w") as handle:
        handle.write(text)
    print(text)


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
    import argparse

    parser = argparse.ArgumentParser()
    parser.add_argument("--timing", action="store_true", help="time lkspace.realize in a warm process")
    parser.add_argument("--before", help="git revision to compare with (with --timing)")
    parser.add_argument("--repeats", type=int, default=9)
    args = parser.parse_args()
    if args.timing:
        timing_main(args.before, args.repeats)
    else:
        main()
