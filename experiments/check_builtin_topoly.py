"""Name the simplest built-in design of every knot of ``results/builtin/coverage.json`` independently.

topoly's HOMFLY-PT of the curve lkspace realizes for the design (not lkspace's own
diagram naming, which the search used) must give the knot's name.  Writes
``results/builtin/check_topoly.md``.

    nice python experiments/check_builtin_topoly.py
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "results", "builtin")


def check(row: dict) -> tuple[str, str, str, float]:
    import topoly

    import lkspace

    t0 = time.perf_counter()
    d = row["simplest"]
    curves = lkspace.realize(lkspace.load(d["scaffold"]).with_labels(np.array(d["labels"]))).curves
    got = topoly.homfly(np.asarray(curves[0]).tolist(), closure=0, max_cross=200) if len(curves) == 1 else "?"
    return row["name"], d["scaffold"], str(got), time.perf_counter() - t0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.parse_args()
    with open(os.path.join(OUT, "coverage.json")) as fh:
        rows = [r for r in json.load(fh)["types"] if not r["name"].startswith("L") and r["simplest"]]
    load = os.getloadavg()
    t0 = time.perf_counter()
    results = [check(r) for r in rows]  # one at a time: topoly makes its own processes
    wall = time.perf_counter() - t0
    exact = [r for r in results if r[2] == r[0]]
    among = [r for r in results if r[2] != r[0] and r[0] in r[2].split("|")]
    other = [r for r in results if r[0] not in r[2].split("|")]
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, cwd=ROOT).stdout
    lines = [
        "# The simplest built-in designs of the knots, named by topoly",
        "",
        f"topoly's HOMFLY-PT on the realized curve gives the table name for {len(exact)} of {len(results)} knots, "
        f"lists it among the knots of equal HOMFLY-PT for {len(among)}, and names another knot for {len(other)}.",
        f"Commit {commit.strip()}, one process (topoly's own workers), load {[round(x, 2) for x in load]} before, "
        f"{wall:.0f} s wall.",
        "",
        "Knots of equal HOMFLY-PT that topoly names by one of them: 5_1 and 10_132, 8_8 and 10_129, 8_16 and 10_156.",
        "",
        "| knot | scaffold | topoly |",
        "|---|---|---|",
    ]
    lines += [f"| {n} | {s} | {g.replace('|', ' or ')} |" for n, s, g, _ in results if g != n]
    with open(os.path.join(OUT, "check_topoly.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print(lines[2])


if __name__ == "__main__":
    main()
