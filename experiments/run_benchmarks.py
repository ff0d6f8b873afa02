"""Rerun every benchmark with one command; record what ran, where and under what load.

    python experiments/run_benchmarks.py            # all of them (long: tens of minutes)
    python experiments/run_benchmarks.py --quick    # a few minutes: small cases of each
    python experiments/run_benchmarks.py --only bench_cli bench_enumerate

Each benchmark script under ``experiments/`` runs in its own process and writes its own
``results/bench_*.json`` / ``.md`` (labels ``latest`` where a script keeps labels); the
command line end to end (``bench_cli``) comes first, the in-process kernel rates after it.
Beside them this writes ``results/benchmarks.json`` and ``results/benchmarks.md``: per
script the exit status, seconds, load average before and after, and the time of
``python -c "import numpy"`` just before it (the machine's speed at that moment), with
the commit, lkspace version and machine of the run.  A script whose optional needs are
missing (Blender's ``bpy``, Chromium) is reported as skipped.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import subprocess
import sys
import tempfile
import time

from benchkit import RESULTS, ROOT, load_average, numpy_import, provenance

CATALOG = f"{tempfile.gettempdir()}/lkspace-bench-cube.parquet"
"""The cube -2..2 catalog bench_catalog_verify reads (written there on first use)."""

SCRIPTS = [  # script, arguments, arguments under --quick (None: left out), what it needs
    ("bench_cli", [], ["--quick"], None),
    ("bench_enumerate", ["--label", "latest"], ["--label", "latest", "--only", "oF", "cube1", "--repeat", "1"], None),
    ("bench_startup", ["--python", sys.executable, "--label", "latest"], None, None),
    ("bench_trace", [], ["--max-corners", "200000", "--out", f"{tempfile.gettempdir()}/bench_trace_quick.json"], None),
    ("bench_symmetry", ["--label", "latest"], ["--label", "latest", "--only-periodic"], None),
    ("bench_catalog_verify", ["--label", "latest", "--catalog", CATALOG], None, None),
    ("bench_export", ["--label", "latest"], ["--label", "latest", "--repeat", "1"], None),
    ("bench_geometry", [], None, None),
    ("bench_identify", [], ["--random", "1"], "spherogram"),
    ("bench_target", [], ["--repeats", "1"], "spherogram"),
    ("bench_solve", [], ["--quick"], "ortools"),
    ("bench_interrupt", ["--source", str(ROOT), "--label", "latest"], None, None),
    ("bench_studio", [], None, "playwright"),
    ("bench_blender", [], None, "bpy"),
]


def run_script(name: str, args: list[str]) -> dict:
    """Run ``experiments/NAME.py ARGS``; return its status, seconds, load averages and numpy reference."""
    record = {"args": args, "import_numpy_s": numpy_import(3)["median_s"], "load_average_before": load_average()}
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, str(ROOT / "experiments" / f"{name}.py"), *args], cwd=ROOT)
    record.update(
        status="ok" if proc.returncode == 0 else f"failed (exit {proc.returncode})",
        seconds=round(time.perf_counter() - start, 1),
        load_average_after=load_average(),
    )
    return record


def markdown(run: dict) -> str:
    """The table of one run of this script."""
    m = run["machine"]
    commit = f"{run['commit']}{' (dirty)' if run.get('dirty') else ''}"
    lines = [
        "# Benchmarks: the last run of `experiments/run_benchmarks.py`",
        "",
        f"{run['date']}, commit {commit}, lkspace {run['lkspace']}, Python {run['python']}, "
        f"{m['cpu_count']} × {m['cpu']}{', quick' if run['quick'] else ''}.  Each script's figures are in "
        "its own `results/bench_*.md`; the command line end to end, with every figure as a multiple of "
        '`python -c "import numpy"`, is in [bench_cli.md](bench_cli.md).',
        "",
        "| script | status | seconds | `import numpy` s before | load average before → after |",
        "|---|---|---|---|---|",
    ]
    for name, r in run["scripts"].items():
        if "seconds" not in r:
            lines.append(f"| {name} | {r['status']} | | | |")
            continue
        load = f"{', '.join(map(str, r['load_average_before']))} → {', '.join(map(str, r['load_average_after']))}"
        lines.append(f"| {name} | {r['status']} | {r['seconds']} | {r['import_numpy_s']} | {load} |")
    return "\n".join(lines) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="small cases only (a few minutes)")
    parser.add_argument("--only", nargs="*", help="script names (default: all)")
    args = parser.parse_args()
    unknown = set(args.only or []) - {name for name, *_ in SCRIPTS}
    if unknown:
        parser.error(f"no such benchmark: {', '.join(sorted(unknown))}")
    run = {**provenance(), "quick": args.quick, "scripts": {}}
    for name, full, quick, needs in SCRIPTS:
        if args.only and name not in args.only:
            continue
        if needs is not None and importlib.util.find_spec(needs) is None:
            run["scripts"][name] = {"status": f"skipped (needs {needs})"}
        elif args.quick and quick is None:
            run["scripts"][name] = {"status": "skipped (--quick)"}
        else:
            print(f"== {name}", flush=True)
            run["scripts"][name] = run_script(name, quick if args.quick else full)
    (RESULTS / "benchmarks.json").write_text(json.dumps(run, indent=1) + "\n")
    (RESULTS / "benchmarks.md").write_text(markdown(run))
    print(markdown(run))


if __name__ == "__main__":
    main()
