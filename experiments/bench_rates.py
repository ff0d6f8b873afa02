"""Designs per second of one space through every command that names a whole space, end to end.

Three commands meet each design of a space and name it by key: ``enumerate --identify``
(the catalog), ``atlas`` (the types and their simplest designs) and ``solve --type`` for
a type the space lacks (every design of the type's component count screened, the space
proved to hold none).  Each is timed as users run it, a fresh ``python -m lkspace``
process, warm (one untimed run first fills the caches), rounds interleaved between the
trees and the commands so that load drifts hit all alike.  The rate is the space's
designs over the median wall time.

Usage: ``python experiments/bench_rates.py [--runs 7] [--space cube:-1..1] [--before TREE]
[--out bench_rates]``; writes ``results/OUT.{json,md}``.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import sys
import tempfile
from pathlib import Path

from benchkit import RESULTS, ROOT, load_average, provenance, summary, timed

COMMANDS = {
    "enumerate --identify -o": ["enumerate", "{name}", "--labels", "{labels}", "--identify", "-o", "{out}"],
    "atlas": ["atlas", "{name}", "--labels", "{labels}"],
    "solve --type 10_1 (none: exhausted)": ["solve", "{name}", "--type", "10_1", "--labels", "{labels}"],
    "solve --type L10a1 (none: exhausted)": ["solve", "{name}", "--type", "L10a1", "--labels", "{labels}"],
}
"""The commands timed, by the label the tables show (``{out}``: a file in the run's folder)."""


def command(label: str, space: str, folder: str) -> list[str]:
    """The ``python -m lkspace`` command line of ``label`` on ``space`` (``scaffold:labels``)."""
    name, labels = space.split(":")
    out = os.path.join(folder, "x.parquet")
    args = [a.format(name=name, labels=labels, out=out) for a in COMMANDS[label]]
    return [sys.executable, "-m", "lkspace", *args]


def designs_of(space: str, env: dict[str, str], folder: str) -> int:
    """The number of designs of ``space`` (``enumerate --count-only --json``)."""
    import subprocess

    name, labels = space.split(":")
    cmd = [sys.executable, "-m", "lkspace", "enumerate", name, "--labels", labels, "--count-only", "--json"]
    found = subprocess.run(cmd, env=env, cwd=folder, capture_output=True, text=True, check=True)
    return int(json.loads(found.stdout)["designs"])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--space", default="cube:-1..1", help="scaffold:labels")
    parser.add_argument("--before", type=Path, help="the tree before the change")
    parser.add_argument("--out", default="bench_rates")
    args = parser.parse_args()
    trees = {"after": ROOT, **({"before": args.before.resolve()} if args.before else {})}
    folder = tempfile.mkdtemp(prefix="lkspace-rates-")  # cwd: `python -m` would import a checkout it starts in
    envs = {label: {**os.environ, "PYTHONPATH": str(tree)} for label, tree in trees.items()}
    designs = designs_of(args.space, envs["after"], folder)
    start_load = load_average()
    for env in envs.values():  # warm: name caches and compiled kernels in place
        for name in COMMANDS:
            timed(command(name, args.space, folder), env, cwd=folder)
    samples: dict[str, dict[str, list[dict]]] = {t: {c: [] for c in COMMANDS} for t in trees}
    for r in range(args.runs):
        for name in COMMANDS:
            for label, env in envs.items():
                samples[label][name].append(timed(command(name, args.space, folder), env, cwd=folder))
        print(f"round {r + 1}/{args.runs}, load {load_average()[0]}", flush=True)
    shutil.rmtree(folder)
    results = {
        label: {
            name: {**summary(runs), "designs_per_s": round(designs / summary(runs)["median_s"])}
            for name, runs in by_command.items()
        }
        for label, by_command in samples.items()
    }
    record = {
        "space": args.space,
        "designs": designs,
        "runs": args.runs,
        "load_start": start_load,
        "load_end": load_average(),
        "trees": {label: provenance(tree) for label, tree in trees.items()},
        "results": results,
    }
    (RESULTS / f"{args.out}.json").write_text(json.dumps(record, indent=1) + "\n")
    (RESULTS / f"{args.out}.md").write_text(markdown(record))
    print(markdown(record))


def markdown(record: dict) -> str:
    """The results as a Markdown page."""
    trees = list(record["results"])
    prov = record["trees"]["after"]
    lines = [
        f"# Designs per second through every command that names a whole space: {record['space']}",
        "",
        f"Written by `experiments/bench_rates.py`. lkspace {prov['lkspace']} at {prov['commit']}, {prov['date']}, "
        f"{prov['machine']['cpu_count']} × {prov['machine']['cpu']}; load average {record['load_start']} at the start, "
        f"{record['load_end']} at the end.  Fresh `python -m lkspace` processes, warm caches, "
        f"median of {record['runs']} interleaved rounds; rate = {record['designs']:,} designs / median wall.",
        "",
        "| command | " + " | ".join(f"{t}: median s (CPU s) | {t}: designs/s" for t in trees) + " |",
        "|---|" + "---:|---:|" * len(trees),
    ]
    for name in COMMANDS:
        cells = []
        for t in trees:
            r = record["results"][t][name]
            cells += [f"{r['median_s']} ({r['cpu_median_s']})", f"{r['designs_per_s']:,}"]
        lines.append(f"| `{name}` | " + " | ".join(cells) + " |")
    lines += ["", "| tree | commit | dirty |", "|---|---|---|"]
    lines += [f"| {t} | {record['trees'][t].get('commit')} | {record['trees'][t].get('dirty')} |" for t in trees]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    main()
