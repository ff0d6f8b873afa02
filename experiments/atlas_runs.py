"""Atlases of the built-in scaffolds for results/atlas/ (run: ``nice python experiments/atlas_runs.py``).

Each space is identified with :func:`lkspace.linktypes.atlas.atlas` (resumable cache under
``$ATLAS_CACHE``, default /tmp/lkspace-atlas-cache, never committed) and written to
``results/atlas/NAME/`` (README.md, atlas.parquet, a few PNGs).  Wall and CPU times go to
``results/atlas/runs.json``; ``results/atlas/runs.md`` gets the table "which knots and
links each scaffold makes", by crossing number, and the types of the 32 single-cycle
tetrahedral designs.
"""

from __future__ import annotations

import json
import os
import resource
import sys
import time

import numpy as np

from lkspace import load
from lkspace.linktypes.atlas import atlas, crossing_number, read_cache
from lkspace.linktypes.gallery import write_gallery
from lkspace.model.specs import parse_label_set

ROOT = os.path.join(os.path.dirname(__file__), "..", "results", "atlas")
CACHE = os.environ.get("ATLAS_CACHE", "/tmp/lkspace-atlas-cache")

SPACES = [  # (folder, scaffold, labels, pictures)
    ("tetrahedron", "tetrahedron", "-2..2", 5),
    ("figure-eight", "figure-eight", "-2..2", 2),
    ("whitehead", "whitehead", "-2..2", 2),
    ("dihedron-3", "dihedron:3", "-2..2", 0),
    ("dihedron-4", "dihedron:4", "-2..2", 0),
    ("dihedron-5", "dihedron:5", "-2..2", 0),
    ("dihedron-6", "dihedron:6", "-2..2", 0),
    ("book-2", "book:2", "-1..1", 0),
    ("book-3", "book:3", "-1..1", 0),
    ("octahedron", "octahedron", "-1..1", 4),
    ("cube", "cube", "-1..1", 4),
]


def cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_SELF)
    c = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime + c.ru_utime + c.ru_stime


def main(only: list[str]) -> None:
    runs_path = os.path.join(ROOT, "runs.json")
    runs = json.load(open(runs_path)) if os.path.exists(runs_path) else {}
    for folder, name, labels, pictures in SPACES:
        if only and folder not in only:
            continue
        scaffold = load(name)
        t0, c0 = time.monotonic(), cpu()
        data = atlas(scaffold, parse_label_set(labels), os.path.join(CACHE, folder))
        write_gallery(os.path.join(ROOT, folder), data, scaffold, pictures)
        before = runs.get(folder, {})
        identified = data.run.identified_now if data.run is not None else 0
        runs[folder] = {
            "scaffold": name,
            "labels": labels,
            "designs": data.designs,
            "types": len(data.types),
            "identified_now": identified,
            "wall_s": round(time.monotonic() - t0, 1),
            "cpu_s": round(cpu() - c0, 1),
        }
        if identified == 0 and before.get("identified_now"):  # all from the cache: keep the real cost
            runs[folder].update({k: before[k] for k in ("identified_now", "wall_s", "cpu_s")})
        latest = json.load(open(runs_path)) if os.path.exists(runs_path) else {}  # another runner may have written
        runs = {**latest, folder: runs[folder]}
        with open(runs_path, "w") as fh:
            json.dump(runs, fh, indent=1)
        print(folder, runs[folder], flush=True)
    summary(runs)


def summary(runs: dict) -> None:
    import pandas as pd

    lines = [
        "# Atlases: which knots and links each scaffold makes",
        "",
        "Made by `experiments/atlas_runs.py` (`lkspace atlas`); one folder per space with its",
        "README.md (every type, designs, assignments, simplest design), atlas.parquet and pictures.",
        "Designs are counted up to rotation; a name stands for both mirror images.",
        "",
        "## Types by crossing number (non-split, named)",
        "",
        "| space | labels | designs | 0 | 2 | 3 | 4 | 5 | 6 | 7 | 8 | 9+ |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for folder, run in runs.items():
        frame = pd.read_parquet(os.path.join(ROOT, folder, "atlas.parquet"))
        named = frame[~frame["name"].str.startswith(("unknown", "split"))]
        cells = []
        for lo, hi in [(0, 0), (2, 2), (3, 3), (4, 4), (5, 5), (6, 6), (7, 7), (8, 8), (9, 999)]:
            pick = named[[lo <= crossing_number(n) <= hi for n in named["name"]]]
            cells.append(", ".join(sorted(pick["name"])) or "")
        row = f"| [{run['scaffold']}]({folder}/README.md) | {run['labels']} | {run['designs']:,} | " + " | ".join(cells)
        lines.append(row + " |")
    lines += [
        "",
        "## Cost",
        "",
        "One process, `nice`, on a machine of 2 cores shared by 5 engineers (load 5 to 14): wall times are",
        "mostly waiting; CPU times (this process and its children) are the cost.  *identified*: designs",
        "identified; the others of a space share the type of a design that differs only on edges of",
        "degree 1 (a lone strand's twist is a one-strand braid: it does not change the type).",
        "",
        "| space | designs | identified | wall s | CPU s |",
        "|---|---|---|---|---|",
    ]
    for run in runs.values():
        note = f" ({run['note']})" if run.get("note") else ""
        lines.append(
            f"| {run['scaffold']} {run['labels']}{note} | {run['designs']:,} | {run['identified_now']:,} | "
            f"{run['wall_s']} | {run['cpu_s']} |"
        )
    lines += cube_estimate(runs)
    lines += book_family()
    lines += single_cycle_table()
    with open(os.path.join(ROOT, "runs.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")


def cube_estimate(runs: dict) -> list[str]:
    """What the single-component designs of the cube with labels -2..2 would cost, from the -1..1 run."""
    from lkspace import count_designs

    run = runs.get("cube")
    if not run or not run.get("identified_now"):
        return []
    n = count_designs("cube", "-2..2").by_components[1]
    per = run["cpu_s"] / run["identified_now"]
    return [
        "",
        "## The cube's single-component designs with labels -2..2: not run",
        "",
        f"There are {n:,} of them (up to rotation).  The cube -1..1 atlas cost {per * 1000:.0f} ms of CPU per",
        f"design (realize, project, simplify, name), so they would take about {n * per / 3600:,.0f} CPU hours",
        "(the degree-1 sharing does not apply: every cube edge has degree 2).  `lkspace solve cube --type NAME`",
        "searches that space for one type at a time instead, simplest first, with the cheap filters.",
    ]


def book_family() -> list[str]:
    """book:K with twist t on its spine (the one edge of degree K) and 0 elsewhere, identified.

    Labels on the edges of degree 1 do not change the type (a one-strand braid), so the
    spine label is the whole design space of a book up to type.
    """
    from lkspace import identify

    lines = [
        "",
        "## book:K: the spine twist t (edges of degree 1 do not change the type)",
        "",
        "| K \\ t | " + " | ".join(str(t) for t in range(1, 7)) + " |",
        "|---|" + "---|" * 6,
    ]
    for k in range(2, 6):
        scaffold = load(f"book:{k}")
        spine = int(np.argmax(scaffold.edge_degrees))
        cells = []
        for t in range(1, 7):
            labels = np.zeros(scaffold.n_edges, np.int64)
            labels[spine] = t
            r = identify(scaffold, labels)
            name = r.details.get("chiral_name") or r.name
            if name is None and r.split:
                name = "split: " + " + ".join(sorted(r.details.get("pieces") or []))
            cells.append(str(name or f"unknown ({r.components})"))
        lines.append(f"| {k} | " + " | ".join(cells) + " |")
    return lines


def single_cycle_table() -> list[str]:
    """The 32 single-cycle designs of the tetrahedron with labels -1..1 and their types."""
    from lkspace.linktypes.candidates import OrderedWalk

    scaffold = load("tetrahedron")
    header = {"scaffold": "tetrahedron", "hash": scaffold.content_hash(), "labels": [-2, -1, 0, 1, 2],
              "no_zero": False, "seed": 0}  # fmt: skip
    cached = read_cache(os.path.join(CACHE, "tetrahedron", "cache.jsonl"), header)
    if not cached:
        return []
    rows = [(lab, cached[tuple(lab)]) for b in OrderedWalk(scaffold, np.arange(-1, 2), 1) for lab in b.labels.tolist()]
    lines = [
        "",
        f"## The {len(rows)} single-cycle tetrahedral designs (labels -1..1, up to rotation)",
        "",
        "| labels (edge order) | type | chirality |",
        "|---|---|---|",
    ]
    for lab, rec in rows:
        chir = {True: "mirror", False: "table", None: "-"}[rec.mirror]
        lines.append(f"| `{','.join(map(str, lab))}` | {rec.type} | {chir} |")
    return lines


if __name__ == "__main__":
    if sys.argv[1:] == ["--summary"]:
        summary(json.load(open(os.path.join(ROOT, "runs.json"))))
    else:
        main(sys.argv[1:])
