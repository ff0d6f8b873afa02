"""A catalog named by key only, sampled against an independent identification.

Rows are drawn at random from each status of a catalog that ``enumerate --identify`` or
``--identify-by-key`` wrote (named; split; not in the tables; table entries listed; other).
Each drawn design is identified again on the geometric path
(:func:`lkspace.knots.recognition.identify` with ``geometric=True``: the strands realized,
projected along their own direction and named in full by spherogram, regina and SnapPy,
no key, no shared name), and compared:

* a named row must get the same name and mirror flag, a split one a split name (``split: 0_1 + 3_1``);
* a row "not in the tables" must get no KnotInfo knot up to 12 crossings and no LinkInfo
  link up to 11 (a name past them, a sum, a split link or unknown are all consistent);
* a row listing table entries must get one of them, or a name outside the tables.

Usage: ``python experiments/check_atlas_sample.py CATALOG --per-status 40 --processes 2
[--out results/atlas/cube-2..2-sample.md]``.
"""

from __future__ import annotations

import argparse
import json
import multiprocessing
import os
import re
import time
from collections import Counter

import numpy as np

import lkspace
from lkspace import load
from lkspace.knots.key_names import NOT_IN_TABLES
from lkspace.knots.recognition import identify

GROUPS = ("named", "split", "not in the tables", "table entries listed", "other unknown")
"""The sample's strata (:func:`status_group`)."""

TIME_LIMIT = 120.0
"""Seconds per design of the reference."""


def status_group(status: str, name: str | None) -> str:
    """The sample's stratum of a row."""
    if name is not None:
        return "named"
    if status == "identified":
        return "split"
    if status == NOT_IN_TABLES.status:
        return "not in the tables"
    if status.startswith("unknown: its invariants match "):
        return "table entries listed"
    return "other unknown"


def in_small_tables(name: str | None) -> bool:
    """Whether ``name`` is a KnotInfo knot up to 12 crossings or a LinkInfo link up to 11 (the shipped keys' bounds)."""
    knot = re.fullmatch(r"(\d+)(?:[an])?_\d+", name or "")
    link = re.fullmatch(r"L(\d+)[an]\d+", name or "")
    return bool(knot and int(knot[1]) <= 12 or link and int(link[1]) <= 11)


def reference(job: tuple[str, list[int]]) -> tuple[str | None, bool | None, str, float]:
    scaffold, labels = job
    t = time.process_time()
    r = identify(load(scaffold), np.asarray(labels), time_limit=TIME_LIMIT, geometric=True)
    return r.name, r.mirror, r.status, time.process_time() - t


def verdict(row: dict, ref: tuple[str | None, bool | None, str, float]) -> str:
    """``agrees``, ``consistent`` (less said, nothing contradicted) or ``DISAGREES``."""
    name, mirror, status, _ = ref
    group = status_group(row["identify_status"], row["knot_name"])
    if group == "named":
        same = name == row["knot_name"] and (mirror == row["mirror"] or row["mirror"] is None or mirror is None)
        return "agrees" if same else "DISAGREES"
    if group == "split":
        return "agrees" if (name or "").startswith("split") and status == "identified" else "DISAGREES"
    if group == "not in the tables":
        return "consistent" if not in_small_tables(name) else "DISAGREES"
    if group == "table entries listed":
        listed = row["identify_status"].removeprefix("unknown: its invariants match ").split(" (named by key")[0]
        names = {n.removesuffix(" (mirror)") for n in listed.split(", ")}
        return "consistent" if name in names or not in_small_tables(name) else "DISAGREES"
    return "consistent"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("catalog")
    parser.add_argument("--per-status", type=int, default=40)
    parser.add_argument("--processes", type=int, default=2)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--out")
    args = parser.parse_args()
    cat = lkspace.read_catalog(args.catalog)
    scaffold = cat.scaffold.name
    frame = cat.frame
    frame = frame.astype({"knot_name": object, "mirror": object}).where(frame.notna(), None)
    groups = np.array([status_group(s, n) for s, n in zip(frame["identify_status"], frame["knot_name"], strict=True)])
    rng = np.random.default_rng(args.seed)
    picked = []
    for group in GROUPS:
        rows = np.flatnonzero(groups == group)
        picked += rng.choice(rows, size=min(args.per_status, len(rows)), replace=False).tolist()
    jobs = [(scaffold, [int(x) for x in cat.labels[i]]) for i in picked]
    t0 = time.monotonic()
    with multiprocessing.get_context("spawn").Pool(args.processes) as pool:
        refs = pool.map(reference, jobs, chunksize=1)
    wall = time.monotonic() - t0
    lines, tally = [], Counter()
    for i, job, ref in zip(picked, jobs, refs, strict=True):
        row = {k: frame[k].iloc[i] for k in ("knot_name", "mirror", "identify_status", "components")}
        row = {k: (None if v is None or (isinstance(v, float) and np.isnan(v)) else v) for k, v in row.items()}
        group = status_group(row["identify_status"], row["knot_name"])
        v = verdict(row, ref)
        tally[group, v] += 1
        ours = row["knot_name"] or row["identify_status"].removeprefix("unknown: ")[:60]
        lines.append(f"| `{','.join(map(str, job[1]))}` | {group} | {ours} | {ref[0] or ref[2][:50]} | {v} |")
    counts = Counter(groups.tolist())
    text = [
        f"# {os.path.basename(args.catalog)} sampled against the geometric path",
        "",
        f"Written by `experiments/check_atlas_sample.py` (lkspace {lkspace.__version__}): {len(jobs)} designs, "
        f"{args.per_status} per status at most (seed {args.seed}), identified again on the geometric path "
        f"({wall:.0f} s wall over {args.processes} processes, {TIME_LIMIT:g} s per design at most).",
        "",
        "| status | rows in the catalog | sampled | agrees | consistent | disagrees |",
        "|---|---|---|---|---|---|",
    ]
    for group in GROUPS:
        n = sum(v for (g, _), v in tally.items() if g == group)
        text.append(
            f"| {group} | {counts.get(group, 0):,} | {n} | {tally[group, 'agrees']} | {tally[group, 'consistent']} "
            f"| {tally[group, 'DISAGREES']} |"
        )
    text += ["", "| labels | status | by key | geometric path | verdict |", "|---|---|---|---|---|", *lines, ""]
    report = "\n".join(text)
    print(report)
    if args.out:
        with open(args.out, "w", encoding="utf-8") as fh:
            fh.write(report)
        with open(os.path.splitext(args.out)[0] + ".json", "w", encoding="utf-8") as fh:
            json.dump({"wall": wall, "counts": dict(counts), "tally": [[g, v, n] for (g, v), n in tally.items()]}, fh)
    return 1 if any(v == "DISAGREES" for _, v in tally) else 0


if __name__ == "__main__":
    raise SystemExit(main())
