"""The paper's question, "which knots and links each scaffold makes", answered from the shipped atlas.

Reads an atlas index (default ``lkspace/data/atlas.parquet``, built by
``experiments/build_atlas.py``) and writes ``results/atlas/README.md`` (per space: its
named types by crossing number, the first label sum |t| at which each appears, how many
designs realize it) and ``results/atlas/types_by_scaffold.png``: on the left, spaces x
crossing numbers, how many named types each space makes; on the right, spaces x the
simplest types (at most ``--max-types``, default 60: whole crossing numbers from 0 up;
marker area: designs on a log scale, colour: first label sum).  The cube's -2..2 space
alone has 2,111 named types, so a column per type of every space would not read; the
README under the picture says how many the right panel leaves out.

Run: ``python experiments/atlas_table.py [--atlas FILE] [--out DIR] [--max-types N]`` (seconds).
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


def markdown(rows: list[IndexRow], meta: dict, atlas: str, caption: str = "") -> str:
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
        *([caption, ""] if caption else []),
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


MAX_TYPES = 60
"""Type columns of the picture's right panel at most: the simplest crossing numbers, whole."""

COUNT_BANDS = [(0, 0), *((n, n) for n in range(2, 13)), (13, 10_000)]
"""Crossing-number columns of the picture's left panel (named types counted per space)."""


def shown_types(keep: list[IndexRow], cap: int) -> list[IndexRow]:
    """The types the dot panel shows, simplest first: every type of the smallest crossing numbers, at most ``cap``.

    A crossing number is shown whole or not at all (the first type past ``cap`` leaves its own out).
    """
    types = sorted({r.type: r for r in keep}.values(), key=type_order)
    if len(types) <= cap:
        return types
    limit = types[cap].crossing_number or 0
    return [r for r in types if (r.crossing_number or 0) < limit]


def plot(rows: list[IndexRow], meta: dict, path: str, cap: int = MAX_TYPES) -> str:
    """Draw the picture at ``path``; return its caption (what it shows and leaves out)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.colors import LogNorm

    spaces = spaces_of(rows, meta)
    line = {s: i for i, s in enumerate(spaces)}
    keep = [r for r in rows if named(r)]
    every = {r.type for r in keep}
    types = shown_types(keep, cap)
    most = max((r.crossing_number or 0 for r in types), default=0)
    column = {r.type: i for i, r in enumerate(types)}
    dots = [r for r in keep if r.type in column]
    counts = np.zeros((len(spaces), len(COUNT_BANDS)), int)
    for r in keep:
        band_of = [lo <= (r.crossing_number or 0) <= hi for lo, hi in COUNT_BANDS]
        if any(band_of):
            counts[line[r.scaffold, r.labels], band_of.index(True)] += 1
    width, height = 3.5 + 0.32 * len(COUNT_BANDS) + 0.24 * len(types), 2.2 + 0.3 * len(spaces)
    fig, (left, right) = plt.subplots(
        1,
        2,
        figsize=(width, height),
        sharey=True,
        gridspec_kw={"width_ratios": [len(COUNT_BANDS), len(types) + 3], "wspace": 0.03},
    )
    shown = np.ma.masked_equal(counts, 0)
    left.imshow(shown, aspect="auto", cmap="Greys", norm=LogNorm(1, max(2, counts.max()) * 3), interpolation="none")
    for (y, x), n in np.ndenumerate(counts):
        if n:
            left.text(x, y, f"{n:,}", ha="center", va="center", fontsize=6.5, color="w" if n > 150 else "k")
    left.set_xticks(range(len(COUNT_BANDS)), [band(lo, hi) for lo, hi in COUNT_BANDS], fontsize=8)
    left.set_xlabel("crossing number", fontsize=8)
    left.set_title("named types per crossing number", fontsize=9)
    left.set_yticks(range(len(spaces)), [f"{s} {labels}" for s, labels in spaces], fontsize=8)
    left.set_ylim(len(spaces) - 0.5, -0.5)
    top = max((r.designs for r in dots), default=1)
    area = [10 + 140 * math.log1p(r.designs) / math.log1p(top) for r in dots]
    xs, ys = [column[r.type] for r in dots], [line[r.scaffold, r.labels] for r in dots]
    scatter = right.scatter(xs, ys, s=area, c=[r.first_sum_abs for r in dots], cmap="viridis", edgecolors="k", lw=0.3)
    right.set_xticks(range(len(types)), [r.type for r in types], rotation=90, fontsize=7.5)
    right.set_xlim(-0.7, len(types) - 0.3)
    right.grid(alpha=0.25)
    right.tick_params(axis="y", left=False)
    left_out = len(every) - len(types)
    right.set_title(
        f"the {len(types)} named types of up to {most} crossings (area: log of designs, colour: first Σ|t|); "
        f"{left_out:,} more types of {most + 1}+ crossings are counted on the left only",
        fontsize=9,
    )
    fig.colorbar(scatter, ax=right, label="first Σ|t|", pad=0.01, fraction=0.03)
    fig.suptitle("Named knot and link types by scaffold", fontsize=11, y=1 - 0.25 / height)
    fig.subplots_adjust(top=1 - 0.75 / height)
    fig.savefig(path + ".tmp.png", dpi=110, bbox_inches="tight")
    plt.close(fig)
    os.replace(path + ".tmp.png", path)
    return (
        f"Left: how many named types of each crossing number each space makes (all {len(every):,} named types).  "
        f"Right: the {len(types)} named types of up to {most} crossings, space by space (area: designs on a log "
        f"scale, colour: first Σ\\|t\\|); the other {left_out:,}, of {most + 1} crossings or more, are listed below."
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--atlas", default=SHIPPED, help="the atlas index (default: the shipped one)")
    parser.add_argument("--out", default=OUT, help="folder for README.md and types_by_scaffold.png")
    parser.add_argument(
        "--max-types", type=int, default=MAX_TYPES, help="type columns of the picture at most (the simplest)"
    )
    args = parser.parse_args(argv)
    rows, meta = read_index(args.atlas)
    os.makedirs(args.out, exist_ok=True)
    caption = plot(rows, meta, os.path.join(args.out, "types_by_scaffold.png"), args.max_types)
    readme = os.path.join(args.out, "README.md")
    with open(readme + ".tmp", "w", encoding="utf-8") as fh:
        fh.write(markdown(rows, meta, args.atlas, caption))
    os.replace(readme + ".tmp", readme)
    print(f"wrote {readme} and types_by_scaffold.png ({len(rows)} rows)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
