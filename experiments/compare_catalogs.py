"""Compare catalogs row set by row set: the rows this code writes against reference catalogs.

The reference catalogs are written by another checkout of lkspace (for the batched walk of
issue 12: the code before it, ``git archive 167379a lkspace``), one per line of a cases
file ``NAME|ENUMERATE ARGS``::

    PYTHONPATH=/tmp/lkref python -m lkspace enumerate ARGS -o REF/NAME.parquet
    python experiments/compare_catalogs.py --cases REF/cases.txt --ref REF

Every row (all columns, lists included) must match; rows are compared as sets (sorted by
``key``, or ``residue_class`` for residue rows), and also in order.  Exit status 1 on any
difference.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time

import pandas as pd


def canonical(df: pd.DataFrame) -> pd.DataFrame:
    """Rows sorted by their key, every list column as a tuple (hashable, comparable)."""
    out = df.copy()
    for col in out.columns:
        if out[col].dtype == object:
            out[col] = [
                x if isinstance(x, bytes) else repr([list(y) if hasattr(y, "__len__") else y for y in x])
                for x in out[col]
            ]
    by = "key" if "key" in out.columns else "residue_class"
    return out.sort_values(by).reset_index(drop=True)


def compare(ref: str, new: str) -> str | None:
    a, b = pd.read_parquet(ref), pd.read_parquet(new)
    if list(a.columns) != list(b.columns):
        return f"columns differ: {list(a.columns)} vs {list(b.columns)}"
    if len(a) != len(b):
        return f"{len(a)} vs {len(b)} rows"
    ca, cb = canonical(a), canonical(b)
    for col in ca.columns:
        if not ca[col].equals(cb[col]):
            bad = (ca[col] != cb[col]).to_numpy().nonzero()[0][:3]
            return f"column {col} differs at sorted rows {bad.tolist()}: {ca[col].iloc[bad].tolist()} vs {cb[col].iloc[bad].tolist()}"
    same_order = all(canonical_order_equal(a[c], b[c]) for c in ("labels",) if c in a.columns)
    return None if same_order else "same rows, different order"


def canonical_order_equal(x: pd.Series, y: pd.Series) -> bool:
    return [list(v) for v in x] == [list(v) for v in y]


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
