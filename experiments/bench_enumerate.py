"""Benchmark: listing and counting design spaces with tiny and with large residue classes.

For each case the full catalog is written to Parquet (``write_catalog``, one process
unless the case says otherwise) and the space is counted without listing
(``count_space``); each is timed as the best of ``--repeat`` runs after a warm-up (numba
compilation and the symmetry group outside the timing).  ``--code DIR`` benchmarks
another checkout of lkspace (``DIR/lkspace``), e.g. the code before the batched walk::

    git archive 167379a lkspace | tar -x -C /tmp/lkref
    python experiments/bench_enumerate.py --code /tmp/lkref --label before --repeat 1
    python experiments/bench_enumerate.py --label after --repeat 3

Beside these in-process figures (start-up excluded), each case is also run as users run
it: ``lkspace enumerate SCAFFOLD --labels L --symmetry S -o OUT --jobs J`` in a fresh
process (warm numba cache; best of ``--repeat`` after one untimed run), given as well as a
multiple of ``python -c "import numpy"`` timed in the same run (``--no-cli`` leaves it out).

Each run stores its numbers under its label in ``results/bench_enumerate.json`` (other
labels are kept), with the commit, lkspace version, machine and load average before and
after, and rewrites ``results/bench_enumerate.md`` from all labels.  The machine is shared
(2 cores, other jobs running): timings are the best of the runs.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import shutil
import sys
import tempfile
import time
from pathlib import Path

from benchkit import load_average, numpy_import, provenance, ratio, summary, timed

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RESULTS = os.path.join(ROOT, "results")
LKSPACE = os.path.join(os.path.dirname(sys.executable), "lkspace")

CASES = [  # name, scaffold, labels, symmetry, jobs, what the classes are like
    ("oF", "honeycomb:oF", "-1..1", "rotations", 1, "tiny: 1 assignment per class, periodic"),
    ("voronoi", "voronoi:cube-faces", "-1..1", "rotations", 1, "tiny, edges of degree 3 and 4"),
    ("hex2x2", "tiling:hexagonal@2x2", "-1..1", "rotations", 1, "small (2^odd edges), periodic"),
    ("octahedron", "octahedron", "-1..1", "isometries", 1, "small (2^odd edges)"),
    ("cube1", "cube", "-2..2", "rotations", 1, "large: up to 3^12 per class"),
    ("cube2", "cube", "-2..2", "rotations", 2, "large: up to 3^12 per class, 2 workers"),
    ("cI", "honeycomb:cI", "-1..1", "rotations", 1, "tiny: 1 assignment per class, periodic"),
]


def best(fn, repeat: int) -> tuple[float, float, object]:
    """Best wall time and best CPU time of this process (both in seconds) over ``repeat`` runs."""
    times, cpus, out = [], [], None
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        out = fn()
        times.append(time.perf_counter() - t0)
        cpus.append(time.process_time() - c0)
    return min(times), min(cpus), out


def run_case(case, repeat: int, skip_list: bool) -> dict:
    from lkspace import Execution, load, write_catalog
    from lkspace.design.counting import count_space
    from lkspace.design.space import make_space

    name, scaffold, labels, symmetry, jobs, kind = case
    space = make_space(load(scaffold), labels, symmetry)
    t_count, c_count, counted = best(lambda: count_space(make_space(load(scaffold), labels, symmetry)), repeat)
    out: dict = {
        "scaffold": scaffold,
        "labels": labels,
        "symmetry": symmetry,
        "classes": kind,
        "assignments": space.assignments,
        "designs": counted.designs,
        "count_seconds": round(t_count, 3),
        "count_cpu_seconds": round(c_count, 3),
        "count_assignments_per_cpu_second": round(space.assignments / c_count),
    }
    if not skip_list:
        tmp = tempfile.mkdtemp(prefix="lkspace-bench-")
        try:

            def listing():
                shutil.rmtree(os.path.join(tmp, "c"), ignore_errors=True)
                return write_catalog(
                    make_space(load(scaffold), labels, symmetry), os.path.join(tmp, "c"), execution=Execution(jobs=jobs)
                )

            t_list, c_list, written = best(listing, repeat)
        finally:
            shutil.rmtree(tmp)
        assert written.designs == counted.designs
        out.update(
            jobs=jobs,
            list_seconds=round(t_list, 3),
            list_assignments_per_second=round(space.assignments / t_list),
            list_assignments_per_second_per_core=round(space.assignments / t_list / jobs),
            list_cpu_seconds=round(c_list, 3) if jobs == 1 else None,
            list_assignments_per_cpu_second=round(space.assignments / c_list) if jobs == 1 else None,
            rows_per_second=round(written.designs / t_list),
        )
    return out


def run_cli(case, repeat: int, code: str, numpy: dict) -> dict:
    """The case as ``lkspace enumerate ... -o OUT`` in fresh processes: best wall and CPU s, ratio to import numpy."""
    name, scaffold, labels, symmetry, jobs, _ = case
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", "PYTHONDONTWRITEBYTECODE")}
    env["PYTHONPATH"] = code
    tmp = tempfile.mkdtemp(prefix="lkspace-bench-cli-")
    try:
        samples = []
        for i in range(repeat + 1):  # the first run warms the caches and is not kept
            out = os.path.join(tmp, f"{name}-{i}.parquet")
            cmd = [LKSPACE, "enumerate", scaffold, "--labels", labels, "--symmetry", symmetry, "-o", out]
            sample = timed([*cmd, "--jobs", str(jobs)], env)
            if i:
                samples.append(sample)
    finally:
        shutil.rmtree(tmp)
    figure = summary(samples)
    return {
        "cli_seconds": figure["best_s"],
        "cli_cpu_seconds": figure["cpu_best_s"],
        "cli_ratio_to_import_numpy": ratio(figure, numpy, "best_s"),
    }


def _pair(row: dict, what: str) -> str:
    wall, cpu = row.get(f"{what}_seconds"), row.get(f"{what}_cpu_seconds")
    if wall is None:
        return "-"
    return f"{wall} ({cpu})" if cpu is not None else str(wall)


def _cli(row: dict) -> str:
    if row.get("cli_seconds") is None:
        return "-"
    return f"{row['cli_seconds']} ({row['cli_ratio_to_import_numpy']}×)"


def markdown(data: dict) -> str:
    labels = [k for k in ("before", "after") if k in data] + [k for k in data if k not in ("before", "after")]
    lines = [
        "# Benchmark: listing and counting, tiny and large residue classes",
        "",
        "Catalog written to Parquet (`write_catalog`) and count without listing (`count_space`);",
        "best of the runs of each label; the 2 cores are shared with other jobs (load average below).",
        "`before`: the code before the batched walk (commit 167379a); `after`: this code.",
        "",
        "Times are wall seconds and, in brackets, CPU seconds of the process (one-process cases): the",
        "machine was heavily loaded (load average 8-16 on 2 cores), so CPU seconds are the fairer",
        "comparison; rates are assignments per CPU second where measured, else per wall second and core.",
        "",
        "`CLI s`: the same catalog written by `lkspace enumerate ... -o` in a fresh process (start-up,",
        "imports, numba's cache, symmetry search included), best wall s and, in brackets, as a multiple of",
        '`python -c "import numpy"` timed in the same run.',
        "",
        "| case | classes | assignments | designs | " + " | ".join(f"list s ({lb})" for lb in labels) + " | "
        "list assignments/s (" + labels[-1] + ") | " + " | ".join(f"count s ({lb})" for lb in labels) + " | "
        "CLI s (" + labels[-1] + ") |",
        "|---" * (6 + 2 * len(labels)) + "|",
    ]
    cases = {name: row for lb in labels for name, row in data[lb]["cases"].items()}  # every label's cases
    for name, row in cases.items():
        lst = [_pair(data[lb]["cases"].get(name, {}), "list") for lb in labels]
        cnt = [_pair(data[lb]["cases"].get(name, {}), "count") for lb in labels]
        last = data[labels[-1]]["cases"].get(name, {})
        rate = last.get("list_assignments_per_cpu_second") or last.get("list_assignments_per_second_per_core")
        rate = "-" if rate is None else f"{rate:,}"
        jobs = f", {row['jobs']} jobs" if row.get("jobs", 1) > 1 else ""
        lines.append(
            f"| {row['scaffold']} {row['labels']} {row['symmetry']}{jobs} | {row['classes']} | "
            f"{row['assignments']:,} | {row['designs']:,} | " + " | ".join(str(x) for x in lst) + f" | "
            f"{rate} | " + " | ".join(str(x) for x in cnt) + f" | {_cli(last)} |"
        )
    lines.append("")
    if {"before", "after"} <= set(data):
        b, a = data["before"]["cases"], data["after"]["cases"]
        for name in ("oF", "voronoi"):
            if name in a and name in b and a[name].get("list_cpu_seconds") and b[name].get("list_cpu_seconds"):
                lines.append(
                    f"- {a[name]['scaffold']} {a[name]['labels']}: listing {b[name]['list_cpu_seconds'] / a[name]['list_cpu_seconds']:,.0f}x "
                    f"and counting {b[name]['count_cpu_seconds'] / a[name]['count_cpu_seconds']:,.0f}x fewer CPU seconds."
                )
        lines.append(
            "- Large classes (cube -2..2) are walked as before, one class per compiled call: same speed "
            "within the noise of this machine (the Parquet writer takes most of the time)."
        )
        lines.append("")
    for lb in labels:
        m, d = data[lb]["machine"], data[lb]
        where = f"commit {d['commit']}, lkspace {d['lkspace']}, {m['cpus']} × {m.get('cpu')}; " if "commit" in d else ""
        numpy = f"; `import numpy` {d['import_numpy']['best_s']} s" if d.get("import_numpy") else ""
        before = f"{d['load_average_before']} → " if "load_average_before" in d else ""
        lines.append(
            f"- `{lb}`: {where}{d['repeat']} run(s) each; load average {before}{m['load_average_at_end']}{numpy}"
        )
    return "\n".join(lines) + "\n"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--code", default=ROOT, help="folder holding the lkspace package to benchmark")
    ap.add_argument("--label", default="after")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--only", nargs="*", help="case names")
    ap.add_argument("--count-only", nargs="*", default=[], help="cases timed for counting only")
    ap.add_argument("--no-cli", action="store_true", help="leave out the command line end to end")
    args = ap.parse_args()
    args.provenance = {**provenance(Path(args.code).resolve()), "load_average_before": load_average()}
    args.numpy = None if args.no_cli else numpy_import()
    sys.path.insert(0, os.path.abspath(args.code))
    from lkspace import load, write_catalog
    from lkspace.design.space import make_space

    warm = tempfile.mkdtemp()
    for sc in ("tetrahedron", "honeycomb:cP"):
        write_catalog(make_space(load(sc), "-1..1"), os.path.join(warm, sc.replace(":", "") + ".parquet"))
    shutil.rmtree(warm)
    cases: dict = {}
    for case in CASES:
        if args.only and case[0] not in args.only:
            continue
        cases[case[0]] = run_case(case, args.repeat, case[0] in args.count_only)
        if args.numpy is not None and case[0] not in args.count_only:
            cases[case[0]].update(run_cli(case, args.repeat, os.path.abspath(args.code), args.numpy))
        print(case[0], json.dumps(cases[case[0]]), flush=True)
        record(args, cases)  # after every case: a long run stopped midway keeps what it measured


def record(args: argparse.Namespace, cases: dict) -> None:
    """Merge ``cases`` under ``args.label`` into the JSON and rewrite the Markdown."""
    path = os.path.join(RESULTS, "bench_enumerate.json")
    data = {}
    if os.path.exists(path):
        with open(path) as fh:
            old = json.load(fh)
        data = {k: v for k, v in old.items() if isinstance(v, dict) and "cases" in v}
    previous = data.get(args.label, {}).get("cases", {})
    prov = args.provenance
    data[args.label] = {
        "code": os.path.abspath(args.code),
        "commit": prov["commit"],
        "dirty": prov["dirty"],
        "lkspace": prov["lkspace"],
        "date": prov["date"],
        "repeat": args.repeat,
        "import_numpy": args.numpy,
        "load_average_before": prov["load_average_before"],
        "cases": {**previous, **cases},
        "machine": {
            "cpus": os.cpu_count(),
            "cpu": prov["machine"]["cpu"],
            "python": platform.python_version(),
            "load_average_at_end": load_average(),
        },
    }
    os.makedirs(RESULTS, exist_ok=True)
    with open(path, "w") as fh:
        json.dump(data, fh, indent=1)
        fh.write("\n")
    with open(os.path.join(RESULTS, "bench_enumerate.md"), "w") as fh:
        fh.write(markdown(data))


if __name__ == "__main__":
    main()
