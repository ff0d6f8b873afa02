"""Peak memory and wall time of ``lkspace atlas CATALOG`` on a big catalog, before and after a change.

Each tree (``--tree``, default this one; ``--before TREE`` adds the tree before the
change) runs ``/usr/bin/time -v python -m lkspace atlas CATALOG --json`` in a fresh
process with ``PYTHONPATH`` set to it, one at a time, trees alternating run by run so load
drifts hit both alike.  Peak RSS is ``time``'s "Maximum resident set size"; the load
average is read before each run.  The atlases the trees print must be equal (else it
stops): the change is about memory, not the answer.

The catalog: the cube's -2..2 space named by key (10,194,250 rows in 11 parts), written once by
``python -m lkspace enumerate cube --labels -2..2 --identify-by-key --jobs 2 -o /tmp/cube22.parquet``.

Usage: ``nice -n 10 python experiments/bench_atlas_memory.py /tmp/cube22.parquet --before /tmp/atlasmem_snap
[--runs 1]``; writes ``results/bench_atlas_memory.{json,md}``.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import pyarrow.parquet as pq
from benchkit import RESULTS, ROOT, load_average, provenance


def run(tree: Path, catalog: str) -> tuple[dict, dict]:
    """One ``atlas CATALOG --json`` with ``tree``'s lkspace: ``({wall_s, cpu_s, peak_rss_mb, load}, its atlas)``."""
    env = {**os.environ, "PYTHONPATH": str(tree)}
    cmd = ["/usr/bin/time", "-v", sys.executable, "-m", "lkspace", "atlas", catalog, "--json"]
    load = load_average()
    # from a temporary folder: `python -m` puts the working directory first on sys.path
    proc = subprocess.run(cmd, env=env, cwd=tempfile.gettempdir(), capture_output=True, text=True)
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} with {tree} failed: {proc.stderr[-2000:]}")

    def field(name: str) -> str:
        return re.search(rf"^\s*{re.escape(name)}: (.+)$", proc.stderr, re.M)[1]  # type: ignore[index]

    clock = field("Elapsed (wall clock) time (h:mm:ss or m:ss)").split(":")
    wall = sum(float(x) * 60**i for i, x in enumerate(reversed(clock)))
    figures = {
        "wall_s": round(wall, 2),
        "cpu_s": round(float(field("User time (seconds)")) + float(field("System time (seconds)")), 2),
        "peak_rss_mb": round(int(field("Maximum resident set size (kbytes)")) / 1024, 1),
        "load": load,
    }
    return figures, json.loads(proc.stdout)


def markdown(result: dict) -> str:
    """The results as a Markdown page."""
    cat = result["catalog"]
    lines = [
        "# `lkspace atlas CATALOG`: peak memory and wall time",
        "",
        "Made by `experiments/bench_atlas_memory.py` (fresh process per run, `/usr/bin/time -v`; trees run one",
        "at a time, alternating).  Command: `" + result["command"] + "`.",
        f"Catalog: {cat['rows']:,} rows in {cat['parts']} parts ({cat['bytes'] / 1e6:,.0f} MB),",
        f"{result['types']:,} types.  The trees' atlases (`--json`) are equal: {result['atlases_equal']}.",
        "",
        "| tree | commit | run | wall s | CPU s | peak RSS MB | load (1, 5, 15 min) before the run |",
        "|---|---|---|---|---|---|---|",
    ]
    for name, tree in result["trees"].items():
        p = tree["provenance"]
        commit = p["commit"] + (" (dirty)" if p["dirty"] else "")
        for i, r in enumerate(tree["runs"], 1):
            load = ", ".join(str(x) for x in r["load"])
            lines.append(f"| {name} | {commit} | {i} | {r['wall_s']} | {r['cpu_s']} | {r['peak_rss_mb']:,} | {load} |")
    machine = next(iter(result["trees"].values()))["provenance"]["machine"]
    lines += ["", f"Machine: {machine['cpu_count']} CPUs ({machine['cpu']}), shared with other jobs.", ""]
    return "\n".join(lines)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("catalog")
    parser.add_argument("--tree", type=Path, default=ROOT)
    parser.add_argument("--before", type=Path)
    parser.add_argument("--runs", type=int, default=1)
    parser.add_argument("--out", default="bench_atlas_memory")
    args = parser.parse_args()
    trees = {"before": args.before, "after": args.tree} if args.before else {"after": args.tree}
    samples: dict[str, list[dict]] = {name: [] for name in trees}
    atlases = {}
    for _ in range(args.runs):
        for name, tree in trees.items():
            figures, atlases[name] = run(tree, args.catalog)
            samples[name].append(figures)
            print(name, figures, flush=True)
    same = len({json.dumps(a, sort_keys=True) for a in atlases.values()}) == 1
    if not same:
        raise SystemExit("the trees' atlases differ")
    rows = pq.ParquetDataset(args.catalog).files if os.path.isdir(args.catalog) else [args.catalog]
    result = {
        "command": f"python -m lkspace atlas {args.catalog} --json",
        "catalog": {
            "path": args.catalog,
            "parts": len(rows),
            "rows": sum(pq.read_metadata(f).num_rows for f in rows),
            "bytes": sum(os.path.getsize(f) for f in rows),
        },
        "types": len(atlases["after"]["types"]),
        "atlases_equal": same,
        "trees": {name: {"provenance": provenance(tree), "runs": samples[name]} for name, tree in trees.items()},
    }
    (RESULTS / f"{args.out}.json").write_text(json.dumps(result, indent=2) + "\n")
    (RESULTS / f"{args.out}.md").write_text(markdown(result))
    print(json.dumps({k: v for k, v in result.items() if k != "trees"}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
