"""Benchmark: start-up, cold/warm enumeration and catalog loading of an installed lkspace.

Every figure is the wall time of fresh subprocesses of the venv given by ``--python`` and the
``lkspace`` beside it, median of ``--runs`` after one untimed warm-up (warm caches: numba's and
.pyc files; PYTHONDONTWRITEBYTECODE is dropped): ``--help``, ``trace tetrahedron --twist 1
--json``, ``import lkspace`` (and ``python -c pass``), the README loop ``trace honeycomb:cP
--twist 0..4 --json`` (total), ``enumerate tetrahedron`` and ``enumerate cube --labels -2..2``
cold (a fresh empty ``NUMBA_CACHE_DIR`` per run) and warm (a cold run's cache reused), then
reading the cube catalog with ``pandas.read_parquet`` and ``lkspace.read_catalog`` (null when
absent), with peak RSS.  Results merge into the JSON under ``--label``; a Markdown table of all
labels next to the targets is written beside it (same name, ``.md``).

Run (any Python; the commit recorded is that of the repo holding the tested lkspace):

    python experiments/bench_startup.py --python /path/to/venv/bin/python --label after [--runs 5]
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

RESULTS = Path(__file__).resolve().parents[1] / "results"
INFO = (
    "import importlib.metadata as m, importlib.util, json, sys\n"
    "v = {p: m.version(p) for p in ('lkspace', 'numpy', 'numba', 'pandas', 'pyarrow', 'click')}\n"
    "print(json.dumps({'python': sys.version.split()[0], 'versions': v,"
    " 'origin': importlib.util.find_spec('lkspace').origin}))"
)
READ_PARQUET = "import sys, pandas; print(len(pandas.read_parquet(sys.argv[1])))"
READ_CATALOG = (
    "import sys, lkspace; c = lkspace.read_catalog(sys.argv[1]); print(len(c.frame), c.labels.shape, c.labels.dtype)"
)
# (key, figure, target, limit in s); read_* rows also show peak RSS
ROWS = [
    ("help", "`lkspace --help`", "≤ 0.3 s", 0.3),
    ("trace", "`trace tetrahedron --twist 1 --json`", "≤ 0.5 s", 0.5),
    ("import", "`python -c 'import lkspace'`", "≤ 0.3 s", 0.3),
    ("python_pass", "`python -c pass` (reference)", "", None),
    ("readme_loop", "README loop: 5 × `trace honeycomb:cP`", "", None),
    ("cold_tetrahedron", "cold `enumerate tetrahedron`", "≤ 4 s", 4.0),
    ("cold_cube", "cold `enumerate cube --labels -2..2`", "≤ 25 s", 25.0),
    ("warm_tetrahedron", "warm `enumerate tetrahedron`", "", None),
    ("warm_cube", "warm `enumerate cube --labels -2..2`", "", None),
    ("read_parquet_cube", "`pandas.read_parquet(cube)`", "", None),
    ("read_catalog_cube", "`lkspace.read_catalog(cube)`", "≤ 6 s", 6.0),
]


def run(cmd: list[str], env: dict | None = None) -> tuple[float, float, str]:
    """Wall seconds, peak RSS (MB) and stdout of one subprocess; raises if it fails."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        t0 = time.perf_counter()
        proc = subprocess.Popen([str(c) for c in cmd], env=env, stdout=out, stderr=err)
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - t0
        proc.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0), err.seek(0)
        if proc.returncode:
            raise RuntimeError(f"{' '.join(map(str, cmd))} exited {proc.returncode}: {err.read().decode()[-2000:]}")
        return wall, usage.ru_maxrss / 1024, out.read().decode().strip()


def summary(samples: list[tuple[float, float, str]], runs_each: int = 1) -> dict:
    """Median/min/max of wall times (summed over each group of ``runs_each`` commands) and peak RSS."""
    walls = [sum(s[0] for s in samples[i : i + runs_each]) for i in range(0, len(samples), runs_each)]
    return {
        "median_s": round(statistics.median(walls), 3),
        "min_s": round(min(walls), 3),
        "max_s": round(max(walls), 3),
        "runs_s": [round(w, 3) for w in walls],
        "peak_rss_mb": round(max(s[1] for s in samples), 1),
        "stdout": samples[-1][2][:200],
    }


def bench(cmds: list[list], runs: int, env: dict, warmup: bool = True) -> dict:
    """Run ``cmds`` one after another ``runs`` times (after one untimed round if ``warmup``)."""
    for cmd in cmds if warmup else []:
        run(cmd, env)
    return summary([run(cmd, env) for _ in range(runs) for cmd in cmds], len(cmds))


def git(repo: Path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run(["git", "-C", str(repo), *args], capture_output=True, text=True)


def measure(py: str, runs: int, cold: int) -> dict:
    lk = str(Path(py).parent / "lkspace")
    # warm caches as a user has them: default numba cache, and bytecode written on the warm-up run
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", "PYTHONDONTWRITEBYTECODE")}
    info = json.loads(run([py, "-c", INFO], env)[2])
    repo = Path(info.pop("origin")).parent
    head = git(repo, "rev-parse", "--short", "HEAD")
    cpu = [line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name")]
    res = {
        "date": datetime.datetime.now().astimezone().isoformat(timespec="seconds"),
        "commit": head.stdout.strip() if head.returncode == 0 else None,
        "dirty": git(repo, "diff", "--quiet", "HEAD").returncode == 1 if head.returncode == 0 else None,
        "repo": str(repo),
        "interpreter": py,
        **info,
        "runs": runs,
        "machine": {"nproc": os.cpu_count(), "cpu": cpu[0] if cpu else None, "loadavg_start": os.getloadavg()},
    }
    fig = res["figures"] = {}
    fig["help"] = bench([[lk, "--help"]], runs, env)
    fig["trace"] = bench([[lk, "trace", "tetrahedron", "--twist", "1", "--json"]], runs, env)
    fig["import"] = bench([[py, "-c", "import lkspace"]], runs, env)
    fig["python_pass"] = bench([[py, "-c", "pass"]], runs, env)
    loop = [[lk, "trace", "honeycomb:cP", "--twist", str(t), "--json"] for t in range(5)]
    fig["readme_loop"] = bench(loop, runs, env)
    with tempfile.TemporaryDirectory(prefix="bench_startup_") as tmp:
        T = Path(tmp)

        def enumerate_(name: str, out: str, cache: str) -> tuple[float, float, str]:
            labels = ["--labels", "-2..2"] if name == "cube" else []
            cmd = [lk, "enumerate", name, *labels, "-o", T / out, "--json"]
            return run(cmd, {**env, "NUMBA_CACHE_DIR": str(T / cache)})

        # cold: a fresh cache dir per run; warm: the cache of the first cold run reused
        fig["cold_tetrahedron"] = summary(
            [enumerate_("tetrahedron", f"tet-{i}.parquet", f"nb-tet-{i}") for i in range(cold)]
        )
        fig["cold_cube"] = summary([enumerate_("cube", "cube.parquet", "nb-cube")])
        fig["warm_tetrahedron"] = summary(
            [enumerate_("tetrahedron", f"tet-w{i}.parquet", "nb-tet-0") for i in range(runs)]
        )
        fig["warm_cube"] = summary([enumerate_("cube", f"cube-w{i}.parquet", "nb-cube") for i in range(runs)])
        cube = T / "cube.parquet"
        fig["read_parquet_cube"] = bench([[py, "-c", READ_PARQUET, cube]], runs, env)
        has = run([py, "-c", "import lkspace; print(hasattr(lkspace, 'read_catalog'))"], env)[2] == "True"
        fig["read_catalog_cube"] = bench([[py, "-c", READ_CATALOG, cube]], runs, env) if has else None
    res["machine"]["loadavg_end"] = os.getloadavg()
    return res


def markdown(data: dict) -> str:
    labels = list(data)
    lines = [
        "# Benchmark: start-up, enumeration and catalog loading",
        "",
        "Median wall time of fresh subprocesses (peak RSS where it matters); cold = empty numba cache.",
        "Written by `experiments/bench_startup.py`.",
        "",
        "| figure | target | " + " | ".join(labels) + " |",
        "|---|---|" + "---|" * len(labels),
    ]
    for key, name, target, limit in ROWS:
        cells = []
        for label in labels:
            f = data[label]["figures"].get(key)
            ok = "" if f is None or limit is None else (" ✓" if f["median_s"] <= limit else " ✗")
            cells.append("null" if f is None else f"{f['median_s']:.2f} s{ok}")
        lines.append(f"| {name} | {target} | " + " | ".join(cells) + " |")
        if key.startswith("read_"):
            cells = []
            for label in labels:
                f = data[label]["figures"].get(key)
                gb = None if f is None else f["peak_rss_mb"] / 1024
                ok = "" if gb is None or key != "read_catalog_cube" else (" ✓" if gb <= 1.5 else " ✗")
                cells.append("null" if gb is None else f"{gb:.2f} GB{ok}")
            target = "≤ 1.5 GB" if key == "read_catalog_cube" else ""
            lines.append(f"| {name} peak RSS | {target} | " + " | ".join(cells) + " |")
    lines += ["", "| label | date | commit | runs | nproc | CPU | load average (start → end) |", "|---" * 7 + "|"]
    for label, r in data.items():
        m = r["machine"]
        load = " → ".join(", ".join(f"{x:.2f}" for x in m[k]) for k in ("loadavg_start", "loadavg_end"))
        commit = f"{r['commit']}{' (dirty)' if r.get('dirty') else ''}"
        lines.append(f"| {label} | {r['date']} | {commit} | {r['runs']} | {m['nproc']} | {m['cpu']} | {load} |")
    return "\n".join(lines) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--python", required=True, help="interpreter of the venv to test")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--cold-runs", type=int, default=3, help="cold tetrahedron runs (cube: always 1)")
    parser.add_argument("--label", required=True, help='key in the JSON, e.g. "before" or "after"')
    parser.add_argument("--out", type=Path, default=RESULTS / "bench_startup.json")
    args = parser.parse_args()
    result = measure(os.path.abspath(args.python), args.runs, args.cold_runs)
    data = json.loads(args.out.read_text()) if args.out.exists() else {}
    data[args.label] = result
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(data, indent=1) + "\n")
    args.out.with_suffix(".md").write_text(markdown(data))
    print(markdown({args.label: result}))


if __name__ == "__main__":
    main()
