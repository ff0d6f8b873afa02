"""The cube's -2..2 space named whole, as users type it: ``enumerate --identify-by-key``, then ``atlas``.

Runs, each in a fresh process with an empty ``LKSPACE_CACHE`` (names from the shipped key
file alone, so the catalog is the same on every machine)::

    lkspace enumerate cube --labels -2..2 --identify-by-key --jobs 2 -o WORK/cube.parquet
    lkspace atlas WORK/cube.parquet -o results/atlas/cube-2..2

and records wall and CPU seconds, peak RSS and the machine's load beside the commit
(``results/bench_whole_space.md`` and ``.json``).  With ``--scheduler dask`` the parts run
on a Dask LocalCluster of ``--jobs`` workers instead of local processes.  ``--add`` then
adds the space to the shipped atlas index (``experiments/build_atlas.py --add-catalog``).

Run: ``python experiments/bench_whole_space.py [--labels -2..2] [--jobs 2] [--work /tmp/whole]
[--add]`` (about half an hour on 2 cores).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import sys

from benchkit import RESULTS, ROOT, load_average, provenance, timed

import lkspace


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scaffold", default="cube")
    parser.add_argument("--labels", default="-2..2")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--scheduler", default="local")
    parser.add_argument("--work", default="/tmp/lkspace-whole-space")
    parser.add_argument("--add", action="store_true", help="add the space to the shipped atlas index")
    args = parser.parse_args()
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    env = {**os.environ, "LKSPACE_CACHE": os.path.join(args.work, "cache"), "PYTHONPATH": str(ROOT)}
    catalog = os.path.join(args.work, f"{args.scaffold.replace(':', '-')}.parquet")
    lk = [sys.executable, "-m", "lkspace"]
    space = f"{args.scaffold} {args.labels}"
    record: dict = {"provenance": provenance(), "space": space, "jobs": args.jobs, "scheduler": args.scheduler}
    record["load_before"] = load_average()
    enumerate_cmd = [*lk, "enumerate", args.scaffold, "--labels", args.labels, "--identify-by-key"]
    enumerate_cmd += ["--jobs", str(args.jobs), "--scheduler", args.scheduler, "-o", catalog]
    record["enumerate"] = timed(enumerate_cmd, env)
    record["load_after_enumerate"] = load_average()
    folder = RESULTS / "atlas" / f"{args.scaffold.replace(':', '-')}{args.labels}"
    shutil.rmtree(folder, ignore_errors=True)
    record["atlas"] = timed([*lk, "atlas", catalog, "-o", str(folder)], env)
    record["load_after"] = load_average()
    cat = lkspace.read_catalog(catalog)
    statuses = cat.frame["identify_status"].value_counts()
    record["rows"] = len(cat.frame)
    record["named"] = int(cat.frame["knot_name"].notna().sum())
    record["statuses"] = {str(k)[:80]: int(v) for k, v in statuses.head(12).items()}
    record["types"] = int(cat.frame["knot_name"].nunique())
    name = f"bench_whole_space_{args.scaffold.replace(':', '-')}{args.labels}_{args.scheduler}"
    (RESULTS / f"{name}.json").write_text(json.dumps(record, indent=1) + "\n")
    (RESULTS / f"{name}.md").write_text(report(record))
    print(report(record))
    if args.add:
        seconds = str(round(record["enumerate"]["wall"], 1))
        build = [sys.executable, str(ROOT / "experiments" / "build_atlas.py"), "--add-catalog", catalog]
        os.execve(sys.executable, [*build, "--seconds", seconds], env)
    return 0


def report(r: dict) -> str:
    p = r["provenance"]
    e, a = r["enumerate"], r["atlas"]
    lines = [
        f"# {r['space']} named whole",
        "",
        f"Written by `experiments/bench_whole_space.py` at commit `{p['commit']}` (lkspace {p['lkspace']}, "
        f"{p['machine']['cpu_count']} cores, {p['machine']['cpu']}), {p['date']}; an empty name cache "
        "(the shipped key file alone); each command in a fresh process.",
        "",
        "| command | wall (min) | CPU of the command's own process (min) | its peak RSS (GB) |",
        "|---|---|---|---|",
        f"| `enumerate {r['space']} --identify-by-key --jobs {r['jobs']} --scheduler {r['scheduler']} -o` "
        f"| {e['wall'] / 60:.1f} | {e['cpu'] / 60:.1f} | {e['rss_mb'] / 1024:.2f} |",
        f"| `atlas CATALOG -o` | {a['wall'] / 60:.1f} | {a['cpu'] / 60:.1f} | {a['rss_mb'] / 1024:.2f} |",
        "",
        "The worker processes that name the parts are started by a fork server, not by the command, so "
        "their CPU time and memory are not in the command's figures.",
        "",
        f"Load average (1, 5, 15 min): {r['load_before']} before, {r['load_after_enumerate']} after the "
        f"enumeration, {r['load_after']} at the end.",
        "",
        f"{r['rows']:,} designs; {r['named']:,} named ({r['types']:,} names).  Statuses:",
        "",
        "| status | designs |",
        "|---|---|",
        *(f"| {status} | {n:,} |" for status, n in r["statuses"].items()),
        "",
    ]
    return "\n".join(lines)


if __name__ == "__main__":
    raise SystemExit(main())
