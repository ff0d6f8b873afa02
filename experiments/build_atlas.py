"""Build the atlas index lkspace ships (``lkspace/data/atlas.parquet``): every built-in finite scaffold it can afford.

Each space is identified with :func:`lkspace.linktypes.atlas.atlas` into its own folder
``WORK/<scaffold>_<labels>/`` (the resumable ``cache.jsonl``, and ``atlas.json`` once the
space is done); then every space of the run is merged into one Parquet file
(:func:`lkspace.linktypes.lookup.write_index`).  A rerun reuses the finished spaces and
resumes the others, so it is cheap; ``--merge-only`` just merges.  A partial space is
reused as it is; delete its ``atlas.json`` to give it more time (the cache keeps what was
identified).

Labels: -2..2 where the space has at most ``--max-designs`` designs (up to rotation),
else -1..1 where that fits; else the space gets ``--partial-seconds S`` (default 300; 0:
left out) with -1..1, its simplest designs first (``complete`` false), or with -1,1 where
-1..1 has too many residue classes to walk in order (the dodecahedron, the icosahedron).  A space past the
atlas's own guard (:data:`~lkspace.linktypes.atlas.MAX_DESIGNS`, meant for interactive
runs) but within ``--max-designs`` is walked whole under a time budget too long to end it.

Run: ``nice python experiments/build_atlas.py --processes 2`` (every space; hours with
per-design geometric identification), ``--quick`` (a few small spaces, about two minutes),
``--spaces dihedron:3=-1..1,book:2=-1..1`` (exactly these).

A space too big to walk one design at a time is added from a catalog that ``lkspace
enumerate --identify`` (or ``--identify-by-key``) wrote: ``--add-catalog PATH --seconds S``
sums it (:func:`~lkspace.linktypes.atlas_catalog.atlas_of_catalog`) into the index, in place of
that scaffold and label set's rows, keeping every other space but the search's rows of the
types it reaches on that scaffold (``S``: the wall seconds the catalog took, recorded as
the space's build time).
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import json
import os
import subprocess
import sys
import time

import lkspace
from lkspace.errors import TooLargeError
from lkspace.io.atomic import write_text
from lkspace.linktypes.atlas import MAX_DESIGNS, AtlasOptions, atlas
from lkspace.linktypes.atlas_catalog import atlas_of_catalog
from lkspace.linktypes.lookup import SHIPPED, index_rows, read_index, write_index
from lkspace.linktypes.records import AtlasResult
from lkspace.model.specs import parse_label_set

HERE = os.path.dirname(os.path.abspath(__file__))
WORK = os.path.join(HERE, "..", "build", "atlas")

SCAFFOLDS = [
    "tetrahedron", "cube", "octahedron", "dodecahedron", "icosahedron", "truncated-octahedron",
    "dihedron:3", "dihedron:4", "dihedron:5", "dihedron:6", "dihedron:7", "dihedron:8",
    "book:2", "book:3", "book:4", "book:5",
    "kaleidocycle:4", "kaleidocycle:6", "cube-net", "cube-lid", "cubes:piano", "cubes:vertex",
    "figure-eight", "whitehead",
]  # fmt: skip
"""Every built-in finite scaffold family (``lkspace scaffold --help``), the small members of the numbered ones."""

PARTIAL_TIME_LIMIT = 10.0
"""Seconds per design in a space built simplest first for a while (past it: an unknown type)."""

QUICK = [
    ("tetrahedron", "-2..2"),
    ("dihedron:3", "-2..2"),
    ("dihedron:4", "-2..2"),
    ("dihedron:5", "-2..2"),
    ("book:2", "-1..1"),
    ("book:3", "-1..1"),
    ("figure-eight", "-1..1"),
    ("whitehead", "-1..1"),
]
"""Small spaces that identify in about 100 s with 2 processes, one design at a time: the atlas committed
before the fast path."""


UNBOUNDED = 1e9
"""Seconds given to a space bigger than ``MAX_DESIGNS`` that is meant to be built whole (about 30 years)."""


FALLBACK = "-1,1"
"""Labels of a partial space whose -1..1 has too many residue classes to walk simplest first: odd labels
make one residue class on every edge of degree 2."""


def slug(scaffold: str, labels: str) -> str:
    """``dihedron:3``, ``-2..2`` -> ``dihedron-3_-2..2``: the space's work folder."""
    return f"{scaffold.replace(':', '-')}_{labels}"


def plan(max_designs: int, partial: float) -> list[tuple[str, str, float | None]]:
    """``(scaffold, labels, stop_after)`` of every space the budget affords, in :data:`SCAFFOLDS` order."""
    spaces = []
    for name in SCAFFOLDS:
        scaffold = lkspace.load(name)
        for labels in ("-2..2", "-1..1"):
            n = lkspace.count_designs(scaffold, parse_label_set(labels)).designs
            if n <= max_designs:
                spaces.append((name, labels, None if n <= MAX_DESIGNS else UNBOUNDED))
                break
        else:
            if partial > 0:
                spaces.append((name, "-1..1", partial))
            else:
                print(f"{name}: more than {max_designs:,} designs with labels -1..1: left out", flush=True)
    return spaces


def build_space(work: str, name: str, labels: str, stop_after: float | None, processes: int) -> AtlasResult | str:
    """Identify one space (or reuse its finished result); return the atlas result, or why it cannot be walked."""
    folder = os.path.join(work, slug(name, labels))
    done = os.path.join(folder, "atlas.json")
    if os.path.exists(done):
        with open(done, encoding="utf-8") as fh:
            data = AtlasResult.from_json(json.load(fh), done)
        if data.complete or stop_after not in (None, UNBOUNDED):
            print(f"{name} {labels}: reused ({data.designs:,} designs, {len(data.types)} types)", flush=True)
            return data
    t0 = time.monotonic()
    try:
        # a partial space names its simplest designs: 10 s each, so that the deadline holds
        limit = PARTIAL_TIME_LIMIT if stop_after else 60.0
        options = AtlasOptions(processes=processes, stop_after=stop_after, time_limit=limit)
        data = atlas(lkspace.load(name), parse_label_set(labels), folder, options)
    except TooLargeError as exc:  # too many residue classes to walk in order, even simplest first
        print(f"{name} {labels}: left out: {exc}", flush=True)
        return str(exc)
    data = dataclasses.replace(data, labels=labels)
    write_text(done, json.dumps(data.to_json()))
    identified = data.run.identified_now if data.run is not None else 0
    print(
        f"{name} {labels}: {data.designs:,} designs, {len(data.types)} types, "
        f"{identified:,} identified now, {time.monotonic() - t0:.1f} s",
        flush=True,
    )
    return data


def commit() -> str | None:
    """The git commit of this source tree, if it is one."""
    try:
        out = subprocess.run(["git", "-C", HERE, "rev-parse", "HEAD"], capture_output=True, text=True, check=True)
    except (OSError, subprocess.CalledProcessError):
        return None
    return out.stdout.strip() or None


def merge(results: list[AtlasResult], output: str, left_out: list[dict] | None = None) -> None:
    """Write the index of ``results`` (atlas results, each with its ``labels`` text) to ``output``.

    ``left_out``: ``{scaffold, labels, reason}`` of the spaces planned but not walked, kept in the metadata.
    """
    rows = [row for data in results for row in index_rows(data, data.labels or "")]
    spaces = [
        {
            "scaffold": d.scaffold,
            "labels": d.labels,
            "designs": d.designs,
            "assignments": d.assignments,
            "types": len(d.types),
            "complete": d.complete,
            "identified": None if d.run is None else d.run.identified_now,
            "wall_time": None if d.run is None else d.run.wall_time,
        }
        for d in results
    ]
    meta = {
        "lkspace_version": lkspace.__version__,
        "commit": commit(),
        "date": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "spaces": spaces,
        "left_out": left_out or [],
    }
    write_index(output, rows, meta)
    print(f"wrote {output}: {len(rows)} rows, {len(spaces)} spaces, {os.path.getsize(output):,} bytes", flush=True)


def labels_text(values: tuple[int, ...] | list[int]) -> str:
    """A label set as typed: ``-2..2`` for a run of integers, else ``-1,1``."""
    values = sorted(values)
    if len(values) > 2 and values == list(range(values[0], values[-1] + 1)):
        return f"{values[0]}..{values[-1]}"
    return ",".join(str(v) for v in values)


def add_catalog(path: str, seconds: float | None, output: str) -> None:
    """Sum the identified catalog at ``path`` into the index ``output``, in place of its space's rows."""
    data = atlas_of_catalog(path)
    labels = labels_text(list(data.label_set or ()))
    rows, meta = read_index(output)
    added = index_rows(data, labels)
    walked = {(r.type, r.scaffold) for r in added}  # the search keeps only pairs no walked space reaches
    rows = [r for r in rows if (r.scaffold, r.labels) != (data.scaffold, labels)]
    rows = [r for r in rows if r.labels != "search" or (r.type, r.scaffold) not in walked] + added
    space = {
        "scaffold": data.scaffold,
        "labels": labels,
        "designs": data.designs,
        "assignments": data.assignments,
        "types": len(data.types),
        "complete": True,
        "identified": data.designs,
        "wall_time": seconds,
        "from_catalog": os.path.basename(path),
    }
    searched = {r.scaffold for r in rows if r.labels == "search"}
    spaces = [
        s
        for s in meta.get("spaces", [])
        if (s["scaffold"], s["labels"]) != (data.scaffold, labels)
        and (s["labels"] != "search" or s["scaffold"] in searched)
    ]
    meta = {k: v for k, v in meta.items() if k != "format"}
    meta.update(spaces=[*spaces, space], commit=commit(), lkspace_version=lkspace.__version__)
    meta["date"] = datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")
    write_index(output, rows, meta)
    print(f"{data.scaffold} {labels}: {data.designs:,} designs, {len(data.types)} types added to {output}", flush=True)


def parse_spaces(text: str) -> list[tuple[str, str, float | None]]:
    """``"dihedron:3=-1..1,book:2=-2..2"`` -> the spaces."""
    out = []
    for part in text.split(","):
        name, _, labels = part.partition("=")
        parse_label_set(labels or "-2..2")
        out.append((name.strip(), labels.strip() or "-2..2", None))
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="only the small spaces of QUICK")
    parser.add_argument("--spaces", help="exactly these spaces: SCAFFOLD=LABELS,... (labels as in --labels)")
    parser.add_argument("--max-designs", type=int, default=MAX_DESIGNS, help="most designs of a space built whole")
    parser.add_argument(
        "--partial-seconds", type=float, default=300, help="seconds for a space past the budget (0: leave it out)"
    )
    parser.add_argument("--processes", type=int, default=1, help="worker processes identifying")
    parser.add_argument("--work", default=WORK, help="folder of the per-space results (resumable)")
    parser.add_argument("-o", "--output", default=SHIPPED, help="the index written (default: the shipped one)")
    parser.add_argument("--merge-only", action="store_true", help="merge the finished spaces of the plan, build none")
    parser.add_argument("--plan", action="store_true", help="print the spaces the budget affords, build nothing")
    parser.add_argument("--add-catalog", metavar="PATH", help="add the space of this identified catalog, build none")
    parser.add_argument("--seconds", type=float, help="with --add-catalog: the wall seconds the catalog took")
    args = parser.parse_args(argv)
    if args.add_catalog:
        add_catalog(args.add_catalog, args.seconds, args.output)
        return 0
    if args.spaces:
        spaces = parse_spaces(args.spaces)
    elif args.quick:
        spaces = [(name, labels, None) for name, labels in QUICK]
    else:
        spaces = plan(args.max_designs, args.partial_seconds)
    if args.plan:
        for name, labels, stop_after in spaces:
            partial = stop_after is not None and stop_after != UNBOUNDED
            print(f"{name} {labels}" + (f" (simplest first, {stop_after:g} s)" if partial else ""))
        return 0
    results, left_out = [], []
    for name, labels, stop_after in spaces:
        done = os.path.join(args.work, slug(name, labels), "atlas.json")
        if args.merge_only:
            if os.path.exists(done):
                with open(done, encoding="utf-8") as fh:
                    results.append(AtlasResult.from_json(json.load(fh), done))
            continue
        data = build_space(args.work, name, labels, stop_after, args.processes)
        if isinstance(data, str) and stop_after not in (None, UNBOUNDED):  # too many residue classes: odd labels
            labels = FALLBACK
            data = build_space(args.work, name, labels, stop_after, args.processes)
        if isinstance(data, str):
            left_out.append({"scaffold": name, "labels": labels, "reason": data})
        else:
            results.append(data)
    merge(results, args.output, left_out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
