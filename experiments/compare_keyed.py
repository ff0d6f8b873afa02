"""Keyed identification against the geometric path on whole design spaces, row by row.

Every design of a space (one per rotation orbit) is identified twice: by
:func:`lkspace.knots.batch.identify_batch` (diagrams from labels, names shared by
invariant key) and by :func:`lkspace.knots.recognition.identify` (each design realized,
projected and named on its own: the reference).  Names, mirror flags, split pieces,
components and linking matrices are compared; the result goes to
``results/compare_keyed.md``.

The reference (hours of CPU) is kept in ``build/compare_keyed/`` with the time it took, so
a rerun after a change to the keyed path compares again in seconds.

Usage: ``python experiments/compare_keyed.py [tetrahedron:-2..2 cube:-1..1 ...] [--processes 2]``
"""

from __future__ import annotations

import argparse
import json
import multiprocessing
import os
import time

import numpy as np
import pandas as pd

import lkspace
from lkspace import load
from lkspace.knots.batch import NamerOptions, identify_batch
from lkspace.knots.recognition import identify

DEFAULT = ["tetrahedron:-2..2", "cube:-1..1", "octahedron:-1..1"]


def _reference(args: tuple[str, list[int]]) -> tuple:
    name, labels = args
    r = identify(load(name), np.asarray(labels), time_limit=120, geometric=True)
    return (r.name, r.mirror, r.status.split(":")[0], r.components, r.linking_matrix)


def compare(space: str, processes: int) -> dict:
    name, _, label_set = space.partition(":")
    scaffold = load(name)
    labels = np.vstack([np.stack(b["labels"].to_numpy()) for b in lkspace.designs(scaffold, label_set)])
    t0 = time.monotonic()
    fast = identify_batch(scaffold, labels, NamerOptions(processes), progress=False)
    t_fast = time.monotonic() - t0
    saved = f"build/compare_keyed/{name}_{label_set}.json"  # the reference and its time, kept for reruns
    if os.path.exists(saved):
        with open(saved, encoding="utf-8") as fh:
            kept = json.load(fh)
        ref, t_ref = [tuple(r) for r in kept["rows"]], kept["seconds"]
    else:
        t0 = time.monotonic()
        with multiprocessing.get_context("spawn").Pool(processes) as pool:
            ref = pool.map(_reference, [(name, row.tolist()) for row in labels], chunksize=16)
        t_ref = time.monotonic() - t0
        os.makedirs(os.path.dirname(saved), exist_ok=True)
        with open(saved, "w", encoding="utf-8") as fh:
            json.dump({"seconds": t_ref, "rows": ref}, fh)
    differ = []
    for i, row in enumerate(fast.itertuples()):
        name, mirror = (None if pd.isna(v) else v for v in (row.knot_name, row.mirror))
        got = (name, mirror, str(row.status).split(":")[0], row.components, json.loads(row.linking_matrix))
        want = tuple(ref[i])
        if got != want:
            differ.append(
                {"labels": labels[i].tolist(), "keyed": [str(v) for v in got], "geometric": [str(v) for v in want]}
            )
    return {
        "space": space,
        "designs": len(labels),
        "differ": len(differ),
        "examples": differ[:10],
        "keyed_s": round(t_fast, 2),
        "geometric_s": round(t_ref, 1),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("spaces", nargs="*", default=DEFAULT)
    parser.add_argument("--processes", type=int, default=2)
    parser.add_argument("--output", default="results/compare_keyed.md")
    args = parser.parse_args()
    results = [compare(space, args.processes) for space in args.spaces]
    lines = [
        "# Keyed identification against the geometric path, row by row",
        "",
        f"lkspace {lkspace.__version__}; `python experiments/compare_keyed.py {' '.join(args.spaces)}`",
        "",
        "| space | designs | rows that differ | keyed (s) | geometric (s, 2 processes) |",
        "|---|---|---|---|---|",
    ]
    for r in results:
        lines.append(f"| {r['space']} | {r['designs']:,} | {r['differ']} | {r['keyed_s']} | {r['geometric_s']} |")
    for r in results:
        for ex in r["examples"]:
            lines.append(f"\n- {r['space']} {ex['labels']}: keyed {ex['keyed']}, geometric {ex['geometric']}")
    with open(args.output, "w", encoding="utf-8") as fh:
        fh.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
