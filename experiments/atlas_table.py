"""The paper's question, "which knots and links each scaffold makes", answered from the shipped atlas.

Reads an atlas index (default ``lkspace/data/atlas.parquet``, built by
``experiments/build_atlas.py``) and writes ``results/atlas/README.md`` (per space: its
named types by crossing number, the first label sum |t| at which each appears, how many
designs realize it) and ``results/atlas/types_by_scaffold.png`` (spaces x types; marker
area: designs on a log scale, colour: first label sum).

Run: ``python experiments/atlas_table.py [--atlas FILE] [--out DIR]`` (seconds).
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from collections import defaultdict

from lkspace.linktypes.atlas import is_named
from lkspace.linktypes.lookup import SHIPPED, read_index
from lkspace.linktypes.records import IndexRow

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "results", "atlas")
BANDS = [(0, 0), (2, 2), (3, 3), (4, 4), (5, 5), (6, 6), (7, 7), (8, 8), (9, 10_000)]
"""Crossing-number columns of the overview (0: the unknot; links start at 2)."""


def named(row: IndexRow) -> bool:
    return is_named(row.type)


def type_order(row: IndexRow) -> tuple:
    return (row.crossing_number or 0, row.components or 0, row.type)


def spaces_of(rows: list[IndexRow], meta: dict) -> list[tuple[str, str]]:
    """The spaces in the order they were built."""
    listed = [(s["scaffold"], s["labels"]) for s in meta.get("spaces", [])]
    return listed or sorted({(r.scaffold, r.labels) for r in rows})


def markdown(rows: list[IndexRow], meta: dict, atlas: str) -> str:
    by_space: dict[tuple[str, str], list[IndexRow]] = defaultdict(list)
    for r in rows:
        by_space[r.scaffold, r.labels].append(r)
    info = {(s["scaffold"], s["labels"]): s for s in meta.get("spaces", [])}
    lines = [
        "# The atlas: which knots and links each scaffold makes",
        "",
        f"Made by `experiments/atlas_table.py` from `{os.path.relpath(atlas, os.path.join(HERE, '..'))}` "
        f"(built by `experiments/build_atlas.py`: lkspace {meta.get('lkspace_version')}, "
        f"commit {str(meta.get('commit'))[:10]}, {meta.get('date')}).  `lkspace lookup NAME` answers from the same file.",
        "Designs are counted up to rotation; a name stands for both mirror images.  *first Σ\\|t\\|*: the smallest",
        "label sum Σ\\|t\\| of a design of the type, i.e. the label sum at which the type first appears.",
        "",
        "![types by scaffold](types_by_scaffold.png)",
        "",
        "## Named types by crossing number",
        "",
        "Each cell: `type (first Σ|t|, designs)`; non-split types named by a table.  *build s*: wall seconds",
        "of the space's identification when it was built (`experiments/build_atlas.py`, on a shared 2-core machine).",
        "",
        "| space | labels | designs | complete | build s | " + " | ".join(band(lo, hi) for lo, hi in BANDS) + " |",
        "|---|---|---|---|---|" + "---|" * len(BANDS),
    ]
    for space in spaces_of(rows, meta):
        types = sorted((r for r in by_space[space] if named(r)), key=type_order)
        cells = []
        for lo, hi in BANDS:
            pick = [r for r in types if lo <= (r.crossing_number or 0) <= hi]
            cells.append(", ".join(f"{r.type} ({r.first_sum_abs}, {r.designs:,})" for r in pick))
        s = info.get(space, {})
        designs = f"{s['designs']:,}" if "designs" in s else ""
        done = "yes" if s.get("complete", True) else "no (simplest first)"
        took = f"{s['wall_time']:.1f}" if s.get("wall_time") is not None else ""
        lines.append(f"| {space[0]} | {space[1]} | {designs} | {done} | {took} | " + " | ".join(cells) + " |")
    lines += ["", "## Every type of every space", ""]
    for space in spaces_of(rows, meta):
        lines += [
            f"### {space[0]}, labels {space[1]}",
            "",
            "| type | common name | components | crossing number | first Σ\\|t\\| | designs | assignments | table / mirror / ? |",
            "|---|---|---|---|---|---|---|---|",
        ]
        for r in sorted(by_space[space], key=lambda r: (not named(r), *type_order(r))):
            chir = f"{r.chirality_table:,} / {r.chirality_mirror:,} / {r.chirality_undetermined:,}"
            lines.append(
                f"| {r.type} | {r.common_name or ''} | {r.components} | "
                f"{'' if r.crossing_number is None else r.crossing_number} | {r.first_sum_abs} | "
                f"{r.designs:,} | {r.assignments:,} | {chir} |"
            )
        lines.append("")
    lines += [
        "## Earlier atlases",
        "",
        "[runs.md](runs.md): the per-space atlases made by `experiments/atlas_runs.py` (pictures, costs).",
    ]
    return "\n".join(lines) + "\n"


def band(lo: int, hi: int) -> str:
    return str(lo) if lo == hi else f"{lo}+"


def plot(rows: list[IndexRow], meta: dict, path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    spaces = spaces_of(rows, meta)
    keep = [r for r in rows if named(r)]
    types = sorted({r.type: r for r in keep}.values(), key=type_order)
    column = {r.type: i for i, r in enumerate(types)}
    line = {s: i for i, s in enumerate(spaces)}
    xs = [column[r.type] for r in keep]
    ys = [line[r.scaffold, r.labels] for r in keep]
    top = max((r.designs for r in keep), default=1)
    sizes = [10 + 240 * math.log1p(r.designs) / math.log1p(top) for r in keep]
    fig, ax = plt.subplots(figsize=(min(4 + 0.22 * len(types), 60), 1.5 + 0.45 * len(spaces)))
    dots = ax.scatter(xs, ys, s=sizes, c=[r.first_sum_abs for r in keep], cmap="viridis", edgecolors="k", lw=0.3)
    ax.set_xticks(range(len(types)), [r.type for r in types], rotation=90, fontsize=7)
    ax.set_yticks(range(len(spaces)), [f"{s} {labels}" for s, labels in spaces], fontsize=8)
    ax.set_xlim(-0.7, len(types) - 0.3)
    ax.set_ylim(len(spaces) - 0.5, -0.5)
    ax.grid(alpha=0.25)
    ax.set_title(
        "Named knot and link types by scaffold (area: log of designs, colour: first label sum Σ|t|)", fontsize=9
    )
    fig.colorbar(dots, ax=ax, label="first Σ|t|", pad=0.01)
    fig.tight_layout()
    fig.savefig(path + ".tmp.png", dpi=110)
    plt.close(fig)
    os.replace(path + ".tmp.png", path)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--atlas", default=SHIPPED, help="the atlas index (default: the shipped one)")
    parser.add_argument("--out", default=OUT, help="folder for README.md and types_by_scaffold.png")
    args = parser.parse_args(argv)
    rows, meta = read_index(args.atlas)
    os.makedirs(args.out, exist_ok=True)
    readme = os.path.join(args.out, "README.md")
    with open(readme + ".tmp", "w", encoding="utf-8") as fh:
        fh.write(markdown(rows, meta, args.atlas))
    os.replace(readme + ".tmp", readme)
    plot(rows, meta, os.path.join(args.out, "types_by_scaffold.png"))
    print(f"wrote {readme} and types_by_scaffold.png ({len(rows)} rows)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
