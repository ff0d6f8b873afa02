"""``lkspace export --relax`` against ``--relax-fine`` on small knots: ropelength ratio to ideal, steps, seconds.

Each knot's design is the one ``results/ropelength/NAME.json`` keeps (written by
``experiments/relax_ropelength.py``); the command ``python -m lkspace export MESH --twist ...
--relax [--relax-fine] -o knot.obj --json`` runs in a fresh process (wall and CPU seconds, the
child's user + system time, which a loaded machine disturbs less), and the OBJ's
ropelength is measured by ``tests/ropelength.py`` against KnotInfo's ideal.  Writes
``results/bench_relax_fine.json`` and ``.md`` with the commit, machine and load average.

    nice python experiments/bench_relax_fine.py [--only 3_1,4_1,5_2,8_17,10_1]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(ROOT))

from benchkit import RESULTS, provenance  # noqa: E402

from tests.ropelength import read_obj_polylines, ropelength  # noqa: E402

KNOTS = "3_1,4_1,5_2,8_17,10_1"
MODES = {"--relax": ["--relax"], "--relax-fine": ["--relax-fine"]}


def measure(row: dict, flags: list[str]) -> dict:
    """Relax ``row``'s design with ``flags`` in a fresh process; its ratio to ideal, steps and seconds."""
    twist = ",".join(str(t) for t in row["labels"])
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "knot.obj")
        cmd = [sys.executable, "-m", "lkspace", "export", row["scaffold"], f"--twist={twist}", *flags, "-o", path]
        before, start = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
        summary = subprocess.run([*cmd, "--json"], capture_output=True, text=True, env=env, check=True)
        wall, after = time.perf_counter() - start, resource.getrusage(resource.RUSAGE_CHILDREN)
        measured = ropelength(read_obj_polylines(path), n_points=2000)["ropelength"]
    relaxation = json.loads(summary.stdout)["relaxation"]
    return {
        "ratio": measured / row["ideal"],
        "steps": relaxation["steps"],
        "converged": relaxation["converged"],
        "wall_s": round(wall, 2),
        "cpu_s": round(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime, 2),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", default=KNOTS, help=f"comma-separated knot names (default {KNOTS})")
    args = parser.parse_args()
    load = [os.getloadavg()[0]]
    rows = []
    for name in args.only.split(","):
        row = json.loads((RESULTS / "ropelength" / f"{name}.json").read_text())
        out = {"type": name, "scaffold": row["scaffold"], "labels": row["labels"], "ideal": row["ideal"]}
        for mode, flags in MODES.items():
            out[mode] = measure(row, flags)
            load.append(os.getloadavg()[0])
        rows.append(out)
        print(name, {m: out[m] for m in MODES}, flush=True)
    data = {"provenance": provenance(ROOT), "load_average_1min": load, "rows": rows}
    (RESULTS / "bench_relax_fine.json").write_text(json.dumps(data, indent=1) + "\n")
    prov = data["provenance"]
    lines = [
        "# `--relax` against `--relax-fine`",
        "",
        f"Commit `{prov['commit']}`{' (uncommitted changes)' if prov['dirty'] else ''}, "
        f"{prov['machine']['cpu_count']} CPUs ({prov['machine']['cpu']}), 1-minute load "
        f"{min(load):.1f}-{max(load):.1f} (shared machine: wall times are noisy, CPU times less); "
        f"`experiments/bench_relax_fine.py`, {prov['date'][:10]}.",
        "",
        "Each knot's design kept by `results/ropelength/NAME.json`, relaxed by `python -m lkspace export ... -o knot.obj` "
        "in a fresh process (CPU: user + system of the whole command, start-up included); ratio: ropelength of the OBJ "
        "(`tests/ropelength.py`) over KnotInfo's ideal.",
        "",
        "| knot | design | `--relax` ratio | steps | CPU s | wall s | `--relax-fine` ratio | steps | CPU s | wall s |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in rows:
        a, b = r["--relax"], r["--relax-fine"]
        design = f"`{r['scaffold']} --twist {','.join(str(t) for t in r['labels'])}`"
        lines.append(
            f"| {r['type']} | {design} | {a['ratio']:.3f} | {a['steps']:,} | {a['cpu_s']:.1f} | {a['wall_s']:.1f} | "
            f"{b['ratio']:.3f} | {b['steps']:,} | {b['cpu_s']:.1f} | {b['wall_s']:.1f} |"
        )
    (RESULTS / "bench_relax_fine.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
