"""Benchmark (issue 33, deliverables 3 and 5): one design identified, and start-up, as users type them.

Every figure is the wall time (and CPU time) of a fresh ``python -m lkspace ...`` process
run with ``PYTHONPATH`` set to the source tree tested, median of ``--runs`` rounds after
one untimed warm-up per case (so the name cache under ``$LKSPACE_CACHE``, numba's cache and
the ``.pyc`` files are warm, as for a user's second command; ``PYTHONDONTWRITEBYTECODE`` is
dropped, as ``experiments/bench_startup.py`` does).  Trees are interleaved case
by case so that both see the same machine load; ``python -c "import numpy"`` is timed in
the same rounds and every figure is also given as a ratio to it.

Cases: ``identify`` of a trefoil, a 13-crossing knot and a 14-crossing link on the cube, a
split link and the 6-component unlink on the cube, and a dodecahedron design (default
path; the trefoil also ``--geometric``); ``--help`` (case ``help``); ``trace tetrahedron`` (also
``--json``); ``enumerate honeycomb:oF --labels -1..1 -o``, ``enumerate cube --labels -1..1 --identify -o``
and ``enumerate cube --labels -2..2 --jobs 2 -o``.

Run (a few minutes)::

    git archive COMMIT | tar -x -C /tmp/before_COMMIT
    python experiments/bench_fast_paths.py --before /tmp/before_COMMIT --runs 3 [--only CASE ...]

Writes ``results/bench_fast_paths.json`` and ``.md`` (commit of each tree, load average
before and after, versions).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from benchkit import RESULTS, ROOT, load_average, provenance, summary, timed  # noqa: E402

TREFOIL = "0,0,0,0,0,-1,0,-1,-1,-1,-1,-1"
CASES: dict[str, list[str]] = {
    "identify cube trefoil": ["identify", "cube", "--twist", TREFOIL],
    "identify cube trefoil --geometric": ["identify", "cube", "--twist", TREFOIL, "--geometric"],
    "identify cube 13n_1915": ["identify", "cube", "--twist", "-1,0,-1,2,-2,2,1,2,-2,-1,1,0"],
    "identify cube L14n38135": ["identify", "cube", "--twist", "-1,-1,2,1,-2,-1,-2,2,0,-1,1,2"],
    "identify cube split link": ["identify", "cube", "--twist", "1,1,1,1,0,0,0,0,0,0,0,0"],
    "identify cube unlink": ["identify", "cube", "--twist", "0"],
    "identify dodecahedron": ["identify", "dodecahedron", "--twist", ",".join(["1"] * 5 + ["0"] * 25)],
    "help": ["--help"],
    "trace tetrahedron": ["trace", "tetrahedron", "--twist", "1"],
    "trace tetrahedron --json": ["trace", "tetrahedron", "--twist", "1", "--json"],
    "enumerate oF -1..1 -o": ["enumerate", "honeycomb:oF", "--labels", "-1..1", "-o", "{out}"],
    "enumerate cube -1..1 --identify -o": ["enumerate", "cube", "--labels", "-1..1", "--identify", "-o", "{out}"],
    "enumerate cube -2..2 --jobs 2 -o": ["enumerate", "cube", "--labels", "-2..2", "--jobs", "2", "-o", "{out}"],
}
"""Case name -> arguments of ``python -m lkspace`` (``{out}``: a new output path per run)."""

GEOMETRIC_ONLY = ("--geometric",)


def run(tree: Path, args: list[str], scratch: str) -> dict:
    """Time ``python -m lkspace ARGS`` on ``tree`` in a fresh process."""
    out = tempfile.mkdtemp(dir=scratch)
    argv = [a.replace("{out}", os.path.join(out, "catalog.parquet")) for a in args]
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}  # .pyc files, as installed
    env["PYTHONPATH"] = str(tree)
    # cwd: python -m puts the working folder first on sys.path, before PYTHONPATH
    return timed([sys.executable, "-m", "lkspace", *argv], env=env, cwd=out)


def applies(tree: Path, args: list[str]) -> bool:
    """Whether the tree knows every option of the case (an old tree has no ``--geometric``)."""
    help_text = (tree / "lkspace" / "cli" / "identify.py").read_text()
    return all(opt in help_text for opt in args if opt in GEOMETRIC_ONLY)


def rewrite(path: Path) -> None:
    """Write the Markdown of an earlier run's JSON again (``--rewrite``), CPU ratios added from its samples."""
    data = json.loads(path.read_text())
    ref = data["numpy_import"]["cpu_median_s"]
    for per in data["figures"].values():
        for f in per.values():
            f.setdefault("cpu_ratio_to_numpy", round(f["cpu_median_s"] / ref, 2))
    path.write_text(json.dumps(data, indent=1) + "\n")
    path.with_suffix(".md").write_text(markdown(data))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", type=Path, help="source tree to compare with (e.g. main)")
    parser.add_argument("--after", type=Path, default=ROOT, help="source tree tested (default: this one)")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--only", nargs="*", help="case names to run (default: all)")
    parser.add_argument("--out", type=Path, default=RESULTS / "bench_fast_paths.json")
    parser.add_argument("--rewrite", action="store_true", help="only rewrite the Markdown of --out's JSON")
    args = parser.parse_args()
    if args.rewrite:
        rewrite(args.out)
        return
    trees = {"after": args.after.resolve()} | ({"before": args.before.resolve()} if args.before else {})
    cases = {k: v for k, v in CASES.items() if not args.only or k in args.only}
    load_start = load_average()
    samples: dict[str, dict[str, list[dict]]] = {label: {} for label in trees}
    numpy_runs = []
    with tempfile.TemporaryDirectory() as scratch:
        for tree in trees.values():  # warm-up: caches, numba, .pyc
            for case in cases.values():
                if applies(tree, case):
                    run(tree, case, scratch)
        for _ in range(args.runs):
            numpy_runs.append(timed([sys.executable, "-c", "import numpy"]))
            for name, case in cases.items():
                for label, tree in trees.items():
                    if applies(tree, case):
                        samples[label].setdefault(name, []).append(run(tree, case, scratch))
    reference = summary(numpy_runs)
    figures = {
        label: {
            name: {
                **summary(s),
                "ratio_to_numpy": round(statistics.median(x["wall"] for x in s) / reference["median_s"], 2),
                "cpu_ratio_to_numpy": round(statistics.median(x["cpu"] for x in s) / reference["cpu_median_s"], 2),
            }
            for name, s in per.items()
        }
        for label, per in samples.items()
    }
    data = {
        "runs": args.runs,
        "load_average": {"start": load_start, "end": load_average()},
        "trees": {label: provenance(tree) for label, tree in trees.items()},
        "numpy_import": reference,
        "figures": figures,
    }
    args.out.write_text(json.dumps(data, indent=1) + "\n")
    args.out.with_suffix(".md").write_text(markdown(data))
    print(markdown(data))


def markdown(data: dict) -> str:
    """The figures as a Markdown table: wall median (CPU median) and ratio to ``import numpy``, per tree."""
    labels = list(data["figures"])
    lines = [
        "# One design identified, and start-up (issue 33)",
        "",
        "Written by `experiments/bench_fast_paths.py`: fresh `python -m lkspace` processes, warm caches,",
        f"median of {data['runs']} interleaved rounds; seconds wall (CPU), and × `import numpy` wall (CPU) "
        f"({data['numpy_import']['median_s']} s wall, {data['numpy_import']['cpu_median_s']} s CPU, in the same rounds).",
        "",
        "| case | " + " | ".join(labels) + " |",
        "|---|" + "---:|" * len(labels),
    ]
    for name in CASES:
        cells = []
        for label in labels:
            f = data["figures"][label].get(name)
            cells.append(
                "n/a"
                if f is None
                else f"{f['median_s']} ({f['cpu_median_s']}) = {f['ratio_to_numpy']}× ({f.get('cpu_ratio_to_numpy')}×)"
            )
        if any(c != "n/a" for c in cells):
            lines.append(f"| {name} | " + " | ".join(cells) + " |")
    lines += ["", "| tree | path | commit | dirty | lkspace | python | CPU |", "|---|---|---|---|---|---|---|"]
    for label, p in data["trees"].items():  # a tree exported with git archive has no commit: its path names it
        lines.append(
            f"| {label} | {p['tree']} | {p['commit']} | {p['dirty']} | {p['lkspace']} | {p['python']} | "
            f"{p['machine']['cpu_count']} × {p['machine']['cpu']} |"
        )
    load = data["load_average"]
    lines += ["", f"Load average (1, 5, 15 min): {load['start']} at the start, {load['end']} at the end.", ""]
    return "\n".join(lines)


if __name__ == "__main__":
    main()
