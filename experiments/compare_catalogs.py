"""Compare catalogs row set by row set: the rows this code writes against reference catalogs.

The reference catalogs are written by another checkout of lkspace (for the batched walk of
issue 12: the code before it, ``git archive 167379a lkspace``), one per line of a cases
file ``NAME|ENUMERATE ARGS``::

    PYTHONPATH=/tmp/lkref python -m lkspace enumerate ARGS -o REF/NAME.parquet
    python experiments/compare_catalogs.py --cases REF/cases.txt --ref REF

Every row (all columns, lists included) must match; rows are compared as sets (sorted by
``key``, or ``residue_class`` for residue rows) and then their order.  Exit status 1 on any
difference.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time

import pyarrow.parquet as pq


def compare(ref: str, new: str) -> str | None:
    """``None`` when the two catalogs hold the same rows (every column), else what differs."""
    a, b = pq.read_table(ref), pq.read_table(new)
    a, b = a.replace_schema_metadata(None), b.replace_schema_metadata(None)
    if a.schema != b.schema:
        return f"schemas differ: {a.schema} vs {b.schema}"
    if a.num_rows != b.num_rows:
        return f"{a.num_rows} vs {b.num_rows} rows"
    by = "key" if "key" in a.column_names else "residue_class"
    sa, sb = a.sort_by(by).combine_chunks(), b.sort_by(by).combine_chunks()
    for name in a.column_names:
        if not sa.column(name).equals(sb.column(name)):
            return f"column {name} differs"
    return None if a.column(by).equals(b.column(by)) else "same rows, different order"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", required=True)
    ap.add_argument("--ref", required=True)
    ap.add_argument("--extra", default="", help="extra enumerate arguments for the new run, e.g. '--jobs 2'")
    args = ap.parse_args()
    failures = 0
    with tempfile.TemporaryDirectory() as tmp:
        for line in open(args.cases):
            if not line.strip():
                continue
            name, cli = line.strip().split("|")
            ref = os.path.join(args.ref, name + ".parquet")
            if not os.path.exists(ref):
                print(f"{name}: no reference catalog, skipped")
                continue
            out = os.path.join(tmp, name + ".parquet")
            start = time.perf_counter()
            cmd = [sys.executable, "-m", "lkspace", "enumerate", *cli.split(), *args.extra.split(), "-o", out, "--json"]
            subprocess.run(cmd, check=True, capture_output=True)
            seconds = time.perf_counter() - start
            verdict = compare(ref, out)
            failures += verdict is not None
            print(f"{name}: {'same rows' if verdict is None else 'DIFFERENT: ' + verdict} ({seconds:.1f} s)")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
