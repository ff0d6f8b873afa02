"""Benchmark: what checking a catalog on every read costs, on the 10-million-row cube catalog.

The catalog is ``lkspace enumerate cube --labels -2..2 -o cube.parquet --jobs 2`` (11 parts,
about 51 MB), written once into ``--catalog`` if missing.  Measured, as the median of
``--runs`` runs after one untimed warm-up (files in the page cache):

- in fresh subprocesses of the lkspace found on ``PYTHONPATH`` (give an older source tree
  there to measure "before"): ``lkspace export CATALOG --row 5000000 -o x.obj`` (wall time),
  and ``lkspace.read_catalog`` (wall time of a script that reads it);
- in this process, with the lkspace installed here: the structure checks alone
  (``open_catalog``: manifest and every part's footer), the SHA-256 of one part, of every
  part (``verify_all``), and ``verify_catalog``.

Results merge into ``results/bench_catalog_verify.json`` under ``--label``; a Markdown table
of all labels is written beside it.

Run:

    python experiments/bench_catalog_verify.py --label after --catalog /tmp/bench/cube.parquet
    cd /tmp && PYTHONPATH=/tmp/old-tree python REPO/experiments/bench_catalog_verify.py --label before \
        --catalog /tmp/bench/cube.parquet --subprocess-only
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

RESULTS = Path(__file__).resolve().parents[1] / "results"
ROW = 5_000_000
READ = "import sys, lkspace; print(len(lkspace.read_catalog(sys.argv[1])))"


def timed(action: Callable[[], object], runs: int) -> float:
    """Median seconds of ``action`` over ``runs`` runs after one warm-up."""
    action()
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        action()
        times.append(time.perf_counter() - t0)
    return round(statistics.median(times), 4)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--label", required=True)
    parser.add_argument("--catalog", required=True)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--subprocess-only", action="store_true", help="Only the subprocess figures (older trees).")
    args = parser.parse_args()
    catalog = args.catalog
    python = [sys.executable, "-m", "lkspace"]
    if not os.path.exists(catalog):
        cmd = [*python, "enumerate", "cube", "--labels", "-2..2", "-o", catalog, "--jobs", "2"]
        subprocess.run(cmd, check=True, capture_output=True)
    out = os.path.join(tempfile.mkdtemp(), "x.obj")
    export = [*python, "export", catalog, "--row", str(ROW), "-o", out]
    figures = {
        "export_row_cli_s": timed(lambda: subprocess.run(export, check=True, capture_output=True), args.runs),
        "read_catalog_script_s": timed(
            lambda: subprocess.run([sys.executable, "-c", READ, catalog], check=True, capture_output=True), args.runs
        ),
    }
    if not args.subprocess_only:
        from lkspace.catalog.verify import open_catalog, verify_catalog

        parts = open_catalog(catalog)
        figures.update(
            parts=len(parts.files),
            rows=parts.n_rows,
            megabytes=round(sum(os.path.getsize(f) for f in parts.files) / 1e6, 1),
            structure_checks_s=timed(lambda: open_catalog(catalog), args.runs),
            sha256_one_part_s=timed(lambda: parts.verify(parts.locate(ROW)[0]), args.runs),
            sha256_all_parts_s=timed(parts.verify_all, args.runs),
            verify_catalog_s=timed(lambda: verify_catalog(catalog), args.runs),
        )
    path = RESULTS / "bench_catalog_verify.json"
    data = json.loads(path.read_text()) if path.exists() else {}
    data[args.label] = figures
    path.write_text(json.dumps(data, indent=1) + "\n")
    keys = sorted({k for v in data.values() for k in v})
    lines = [
        "# Checking catalogs on read: cost on the cube catalog (`enumerate cube --labels -2..2`)",
        "",
        "Written by `experiments/bench_catalog_verify.py`; medians of warm runs (files in the page cache)",
        "on a shared, loaded 2-core machine.  `before*`: the tree before the checks (commit 816fe93, run with",
        "PYTHONPATH set to it, from outside the repository), measured before and after `after` to show the",
        "machine's noise; `after`: with the checks.  Catalog written by the `after` code (page checksums).",
        "",
        "| figure | " + " | ".join(data) + " |",
        "|---|" + "---|" * len(data),
        *(f"| {k} | " + " | ".join(str(v.get(k, "")) for v in data.values()) + " |" for k in keys),
        "",
    ]
    path.with_suffix(".md").write_text("\n".join(lines))
    print(json.dumps(data[args.label]))


if __name__ == "__main__":
    main()
