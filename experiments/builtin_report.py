"""The report of ``experiments/search_builtin.py`` and its rows in the shipped atlas.

``write_report``: ``results/builtin/coverage.json`` (every type's simplest design per
scaffold, the run) and ``README.md`` (coverage by crossing number).  ``add_to_atlas``:
rows with label set ``search`` for the (type, scaffold) pairs the walked spaces lack
(for a type they reach, only designs simpler than its simplest there), each with the
design in the table's chirality and its mirror image (labels negated).
"""

from __future__ import annotations

import json
import os

from lkspace.io.atomic import write_text
from lkspace.linktypes.atlas import crossing_number
from lkspace.linktypes.common_names import common_name
from lkspace.linktypes.lookup import SHIPPED, read_index, write_index
from lkspace.linktypes.records import Example, IndexRow

LABEL_SET = "search"


def simplest(designs: dict[str, dict]) -> tuple[str, dict] | None:
    """The simplest design over all scaffolds: sum |t|, then non-zero labels, then the scaffold's name."""
    if not designs:
        return None
    return min(designs.items(), key=lambda kv: (kv[1]["sum_abs"], kv[1]["nonzero"], kv[0]))


def atlas_types() -> set[str]:
    rows, _ = read_index(SHIPPED)
    return {r.type for r in rows if r.labels != LABEL_SET}


def write_report(out: str, types: dict[str, dict], rows: list[dict], run: dict) -> None:
    """Write ``coverage.json`` and ``README.md`` (see the module docstring)."""
    before = atlas_types()
    table: dict[str, dict[str, int]] = {}
    for r in rows:
        entry = types[r["name"]]
        kind = "knots" if entry.components == 1 else "links"
        key = f"{kind} {entry.crossings}"
        best = simplest(r["designs"])
        cell = table.setdefault(key, {"types": 0, "search": 0, "minimal": 0, "atlas_before": 0, "builtin": 0})
        cell["types"] += 1
        cell["search"] += best is not None
        cell["minimal"] += best is not None and best[1]["sum_abs"] == entry.crossings
        cell["atlas_before"] += r["name"] in before
        cell["builtin"] += best is not None or r["name"] in before
        r["simplest"] = None if best is None else {"scaffold": best[0], **best[1]}
        r["crossing_number"] = entry.crossings
    totals = {k: sum(c[k] for c in table.values()) for k in ("types", "search", "minimal", "atlas_before", "builtin")}
    os.makedirs(out, exist_ok=True)
    data = {"run": run, "totals": totals, "by_crossing_number": table, "types": rows}
    write_text(os.path.join(out, "coverage.json"), json.dumps(data, indent=1) + "\n")
    lines = [
        "# The standard tables on built-in scaffolds",
        "",
        "`experiments/search_builtin.py` puts each type of the standard tables (prime knots to 10",
        "crossings, prime links to 9) on the closed built-in scaffolds by subgraph isomorphism of",
        "its Tait graph into their dual graphs, every design checked by naming it",
        '(docs/design-to-target.md, "Table types on built-in scaffolds").',
        "",
        f"Run: commit {run['commit']}, lkspace {run['version']}, {run['date']}, {run['machine']},",
        f"{run['processes']} processes, load {run['load_before']} before and {run['load_after']} after,",
        f"{run['wall_seconds']} s wall ({run['wall_seconds'] / max(1, len(rows)):.2f} s a type).",
        "",
        "| types | count | on a built-in scaffold | found by the search | of them with sum \\|t\\| = crossing number "
        "| in the atlas before | constructed only |",
        "|---|---|---|---|---|---|---|",
    ]
    for key in sorted(table, key=lambda k: (k.split()[0], int(k.split()[1]))):
        c = table[key]
        lines.append(
            f"| {key} crossings | {c['types']} | {c['builtin']} | {c['search']} | {c['minimal']} | "
            f"{c['atlas_before']} | {c['types'] - c['builtin']} |"
        )
    t = totals
    lines.append(
        f"| **all** | {t['types']} | **{t['builtin']}** ({100 * t['builtin'] / t['types']:.0f}%) | {t['search']} | "
        f"{t['minimal']} | {t['atlas_before']} | {t['types'] - t['builtin']} |"
    )
    missing = [r["name"] for r in rows if r["simplest"] is None and r["name"] not in before]
    lines += [
        "",
        "A design with sum |t| above the crossing number has kinks: faces of the scaffold the",
        "type's Tait graph leaves over, each joined by one label 1 (a nugatory crossing).",
        "",
        f"Constructed only ({len(missing)}): {', '.join(missing) or 'none'}.",
        "",
        "## Simplest design of each type",
        "",
        "| type | crossing number | scaffold | sum \\|t\\| | non-zero | labels |",
        "|---|---|---|---|---|---|",
    ]
    for r in rows:
        b = r["simplest"]
        if b is not None:
            labels = ",".join(map(str, b["labels"]))
            lines.append(
                f"| {r['name']} | {r['crossing_number']} | {b['scaffold']} | {b['sum_abs']} | {b['nonzero']} | {labels} |"
            )
    write_text(os.path.join(out, "README.md"), "\n".join(lines) + "\n")


def add_to_atlas(types: dict[str, dict], rows: list[dict]) -> None:
    """Add rows (label set ``search``) for the (type, scaffold) pairs the walked spaces lack; keep their rows.

    A type the walked spaces reach gets only designs simpler (sum |t|, then non-zero
    labels) than its simplest there, so its lookup changes only where it gets simpler.
    """
    old, meta = read_index(SHIPPED)
    kept = [r for r in old if r.labels != LABEL_SET]
    have = {(r.type, r.scaffold) for r in kept}
    best: dict[str, tuple[int, int]] = {}  # a walked type's simplest design: only simpler ones are added
    for row in kept:
        for e in row.examples:
            best[row.type] = min(best.get(row.type, (1 << 30, 0)), (e.sum_abs, e.nonzero))
    new = []
    for r in rows:
        entry = types[r["name"]]
        for scaffold, d in sorted(r["designs"].items()):
            if (r["name"], scaffold) in have or (d["sum_abs"], d["nonzero"]) >= best.get(r["name"], (1 << 30, 0)):
                continue
            labels = tuple(d["labels"])
            mirrored = tuple(-t for t in labels)
            ex = [Example(labels, d["sum_abs"], d["nonzero"], d["crossings"], d["mirror"])]
            if d["mirror"] is not None:
                ex.append(Example(mirrored, d["sum_abs"], d["nonzero"], d["crossings"], True))
            new.append(
                IndexRow(
                    type=r["name"],
                    common_name=common_name(r["name"]),
                    components=entry.components,
                    crossing_number=crossing_number(r["name"]),
                    crossings=d["crossings"],
                    table="knotinfo" if entry.components == 1 else "linkinfo",
                    scaffold=scaffold,
                    labels=LABEL_SET,
                    designs=len(ex),
                    assignments=len(ex),
                    first_sum_abs=d["sum_abs"],
                    chirality_table=int(d["mirror"] is False),
                    chirality_mirror=int(d["mirror"] is False),
                    chirality_undetermined=int(d["mirror"] is None),
                    examples_json=IndexRow.examples_text(tuple(ex)),
                    complete=False,
                )
            )
    spaces = [s for s in meta.get("spaces", []) if s.get("labels") != LABEL_SET]
    for scaffold in sorted({row.scaffold for row in new}):
        of = [row for row in new if row.scaffold == scaffold]
        spaces.append(
            {
                "scaffold": scaffold,
                "labels": LABEL_SET,
                "designs": sum(row.designs for row in of),
                "assignments": sum(row.designs for row in of),
                "types": len(of),
                "complete": False,
                "identified": sum(row.designs for row in of),
                "wall_time": 0.0,
            }
        )
    meta = {k: v for k, v in meta.items() if k != "format"}
    meta["spaces"] = spaces
    meta["search"] = "label set 'search': experiments/search_builtin.py (results/builtin/README.md)"
    write_index(SHIPPED, kept + new, meta)
    print(f"atlas: kept {len(kept)} rows, added {len(new)} rows of label set {LABEL_SET!r}")
