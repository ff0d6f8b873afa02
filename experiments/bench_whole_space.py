"""The cube's -2..2 space named whole, as users type it: ``enumerate --identify-by-key``, then ``atlas``.

Runs, each in a fresh process with an empty ``LKSPACE_CACHE`` (names from the shipped key
file alone, so the catalog is the same on every machine)::

    lkspace enumerate cube --labels -2..2 --identify-by-key --jobs 2 -o WORK/cube.parquet
    lkspace atlas WORK/cube.parquet -o results/atlas/cube-2..2

and records wall and CPU seconds, peak RSS and the machine's load beside the commit
(``results/bench_whole_space.md`` and ``.json``).  The CPU time and memory of every
process the command starts (the fork server's workers, a Dask cluster's) are sampled
with psutil twice a second, and the time each part is complete is read off the catalog's
parts.  Beside them, the kernels' rates on random designs of the space in this process:
keys (:func:`lkspace.knots.keyed.keys_of`) and names by key (``share_names``).  With
``--scheduler dask`` the parts run on a Dask LocalCluster of ``--jobs`` workers instead of
local processes; ``--shards N`` cuts the space into N parts.  ``--add`` then adds the
space to the shipped atlas index (``experiments/build_atlas.py --add-catalog``).

Run: ``python experiments/bench_whole_space.py [--labels -2..2] [--jobs 2] [--shards N]
[--scheduler dask] [--work /tmp/whole] [--add]`` (about half an hour on 2 cores).
"""

from __future__ import annotations

import argparse
import glob
import json
import os
import shutil
import subprocess
import sys
from typing import Any

from benchkit import RESULTS, ROOT, load_average, provenance, timed

import lkspace


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scaffold", default="cube")
    parser.add_argument("--labels", default="-2..2")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--scheduler", default="local")
    parser.add_argument("--shards", type=int, help="parts of the catalog (default: lkspace's plan)")
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
    record["shards"] = args.shards
    record["load_before"] = load_average()
    enumerate_cmd = [*lk, "enumerate", args.scaffold, "--labels", args.labels, "--identify-by-key"]
    enumerate_cmd += ["--jobs", str(args.jobs), "--scheduler", args.scheduler, "-o", catalog]
    enumerate_cmd += ["--shards", str(args.shards)] if args.shards else []
    record["kernels"] = kernel_rates(args.scaffold, args.labels)
    record["enumerate"] = timed_tree(enumerate_cmd, env, args.work, catalog)
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
    name += f"_{args.shards}parts" if args.shards else ""
    (RESULTS / f"{name}.json").write_text(json.dumps(record, indent=1) + "\n")
    (RESULTS / f"{name}.md").write_text(report(record))
    print(report(record))
    if args.add:
        seconds = str(round(record["enumerate"]["wall"], 1))
        build = [sys.executable, str(ROOT / "experiments" / "build_atlas.py"), "--add-catalog", catalog]
        os.execve(sys.executable, [*build, "--seconds", seconds], env)
    return 0


def timed_tree(cmd: list[str], env: dict[str, str], work: str, catalog: str) -> dict:
    """Run ``cmd``: its wall time, the CPU seconds and peak RSS of it and every process it starts, when each part was done.

    A part is done when it is last written (named, in the identify pass): the modification
    times of the parts of ``catalog``, from the start.
    """
    import time

    import psutil

    began = time.time()
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, env=env, cwd=work, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    root = psutil.Process(proc.pid)
    cpu: dict[int, float] = {}
    peak_rss = 0.0
    while proc.poll() is None:
        rss = 0.0
        for p in [root, *_children(root)]:
            try:
                times, memory = p.cpu_times(), p.memory_info()
            except psutil.Error:
                continue
            cpu[p.pid] = times.user + times.system
            rss += memory.rss
        peak_rss = max(peak_rss, rss)
        time.sleep(0.5)
    wall = time.perf_counter() - start
    err = proc.stderr.read() if proc.stderr else ""
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({proc.returncode}): {err[-2000:]}")
    parts = glob.glob(os.path.join(catalog, "part-*.parquet")) if os.path.isdir(catalog) else [catalog]
    done = sorted(os.path.getmtime(path) - began for path in parts)
    return {"wall": wall, "cpu_all": sum(cpu.values()), "rss_gb_all": peak_rss / 2**30, "parts_done_at": done}


def _children(root: Any) -> list[Any]:
    """Every process ``root`` started (and they started), as far as it can still be read."""
    import psutil

    try:
        return root.children(recursive=True)
    except psutil.Error:
        return []


def kernel_rates(scaffold_name: str, labels: str, n: int = 100_000) -> dict:
    """Designs per second of keying and of naming by key, on ``n`` random designs of the space, in this process."""
    import time

    import numpy as np

    from lkspace.knots.key_names import disk_cache, share_names
    from lkspace.knots.keyed import keys_of

    scaffold = lkspace.load(scaffold_name)
    low, high = (int(x) for x in labels.replace("..", " ").split())
    designs = np.random.default_rng(0).integers(low, high + 1, size=(n, scaffold.n_edges))
    keys_of(scaffold, designs[:100])  # kernels loaded
    began = time.perf_counter()
    found = keys_of(scaffold, designs, label_values=np.arange(low, high + 1))
    keyed = time.perf_counter() - began
    began = time.perf_counter()
    share_names(found, disk_cache(), lambda indices: iter(()), by_key=True)
    named = time.perf_counter() - began
    return {"designs": n, "keys_per_s": n / keyed, "names_by_key_per_s": n / named}


def report(r: dict) -> str:
    p = r["provenance"]
    e, a, k = r["enumerate"], r["atlas"], r["kernels"]
    shards = f" --shards {r['shards']}" if r.get("shards") else ""
    lines = [
        f"# {r['space']} named whole",
        "",
        f"Written by `experiments/bench_whole_space.py` at commit `{p['commit']}` (lkspace {p['lkspace']}, "
        f"{p['machine']['cpu_count']} cores, {p['machine']['cpu']}), {p['date']}; an empty name cache "
        "(the shipped key file alone); each command in a fresh process.",
        "",
        "| command | wall (min) | CPU of it and every process it started (min) | their peak RSS together (GB) |",
        "|---|---|---|---|",
        f"| `enumerate {r['space']} --identify-by-key --jobs {r['jobs']} --scheduler {r['scheduler']}{shards} -o` "
        f"| {e['wall'] / 60:.1f} | {e['cpu_all'] / 60:.1f} | {e['rss_gb_all']:.2f} |",
        f"| `atlas CATALOG -o` | {a['wall'] / 60:.1f} | {a['cpu'] / 60:.1f} | {a['rss_mb'] / 1024:.2f} |",
        "",
        f"Parts complete at (min): {', '.join(f'{t / 60:.1f}' for t in e['parts_done_at'])}.",
        "",
        f"In one process, on {k['designs']:,} random designs of the space: keys {k['keys_per_s']:,.0f} "
        f"designs/s (threads over the cores), names by key {k['names_by_key_per_s']:,.0f} designs/s.",
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
