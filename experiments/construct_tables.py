"""Construct every type of the knot and link tables and check each construction.

For every prime knot of KnotInfo up to ``--max-knot`` crossings and every prime link of
LinkInfo up to ``--max-link``, build the checkerboard design of the table's diagram in
each placement (``lkspace.scaffolds.constructed.LAYOUTS``), name its strands with
lkspace's identification (the combinatorial diagram of the labels, then the tables), and
keep the first placement that gives the type in the table's chirality and whose default
geometry passes the embedding check in both chiralities (``knot:NAME`` and ``knot:mNAME``
export as they are).

Writes ``lkspace/data/diagrams.json.gz`` (every type's PD code and checked placement:
what ``knot:NAME`` / ``link:NAME`` load) and ``results/construct/report.{json,md}``:
counts constructed / identified as the target / mirror right, time per type, and the
crossings of each design against the table's crossing number.  Types above the checked
range ship with their PD code and ``"layout": null`` (``lkspace construct`` still checks
them when it runs).

    python experiments/construct_tables.py --max-knot 10 --max-link 9
"""

from __future__ import annotations

import argparse
import gzip
import json
import os
import platform
import subprocess
import time

import database_knotinfo as dki

from lkspace import __version__
from lkspace.errors import LkspaceError
from lkspace.knots.assembly import assemble_pd
from lkspace.knots.naming import name_pd, one_based
from lkspace.linktypes.construct import clear, reversals
from lkspace.scaffolds.constructed import LAYOUTS, TABLE_FILE, design_scaffold, layouts

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def table_types(max_knot_all: int = 12, max_link_all: int = 11) -> dict[str, dict]:
    """Name -> ``{"pd", "components", "crossings"}`` for every prime knot to 12 and link to 11 crossings."""
    out: dict[str, dict] = {}
    for row in dki.link_list()[1:]:
        c = int(row.get("crossing_number") or 99)
        if row.get("pd_notation") and 0 < c <= max_knot_all:
            amphichiral = "amphicheiral" in str(row.get("symmetry_type") or "")
            out[row["name"]] = {
                "pd": json.loads(row["pd_notation"]),
                "components": 1,
                "crossings": c,
                "amphichiral": amphichiral,
            }
    for row in dki.link_list(proper_links=True)[1:]:
        name = row["name"].split("{")[0]
        c = int(row.get("crossing_number") or 99)
        if name not in out and row.get("pd_notation_vector") and c <= max_link_all:
            pd = json.loads(row["pd_notation_vector"].replace("{", "[").replace("}", "]"))
            out[name] = {"pd": pd, "components": int(row["components"]), "crossings": c, "amphichiral": None}
    return out


MOVED = 40
"""Other diagrams tried for a type none of whose table diagram's placements passes: random seeds 0..MOVED-1."""


def check(name: str, entry: dict) -> dict:
    """Check the table's diagram (:func:`check_diagram`); where no placement passes, other minimal diagrams of the type.

    Another diagram is the table's moved by Reidemeister moves (spherogram's ``backtrack(30)``
    then ``simplify("global")``, ``random.seed(k)`` first): the same oriented link, so the same
    type and chirality.  The first with the table's crossing number one of whose placements
    passes replaces the table's in ``entry["pd"]`` (what ships), and its row says so.
    """
    row = check_diagram(name, entry)
    if row.get("layout"):
        return row
    import random

    import spherogram

    seen = {json.dumps(entry["pd"])}
    for seed in range(MOVED):
        random.seed(seed)
        link = spherogram.Link([list(x) for x in entry["pd"]])
        link.backtrack(30)
        link.simplify("global")
        code = one_based(link.PD_code())
        if len(code) != entry["crossings"] or json.dumps(code) in seen:
            continue
        seen.add(json.dumps(code))
        moved = check_diagram(name, {**entry, "pd": code})
        if moved.get("layout"):
            entry["pd"] = code
            moved["diagram"] = f"the table's moved by Reidemeister moves (seed {seed})"
            moved["seconds"] = round(moved["seconds"] + row["seconds"], 3)
            return moved
    return row


def check_diagram(name: str, entry: dict) -> dict:
    """Try each placement of ``entry["pd"]``; return the row of the report.

    The target is the table diagram's own name and chirality (``name_pd`` of its PD code):
    a LinkInfo orientation may be named as the mirror image of the entry's name.
    """
    t0 = time.perf_counter()
    want = name_pd(entry["pd"], entry["components"], floer=False)
    row: dict = {"name": name, "components": entry["components"], "table_crossings": entry["crossings"]}
    for layout in layouts(entry["pd"]):
        try:
            s = design_scaffold(entry["pd"], name, layout)
            d = assemble_pd(s, s.labels)
            got = name_pd([[int(v) for v in x] for x in d.pd], d.n_components, floer=False)
        except LkspaceError as exc:
            if len(row.setdefault("errors", [])) < 3:
                row["errors"].append(f"{layout}: {exc}")
            continue
        if "layout" not in row and not row.get("constructed"):  # the design reported: the first made, or the kept one
            row.update(constructed=True, design_crossings=int(abs(s.labels).sum()), edges=s.n_edges, faces=s.n_faces)
        if len(row.setdefault("names", [])) < 3:
            row["names"].append(f"{layout}: {got.chiral_name or got.name}")
        by = None
        if want.name is None and got.name is None:
            by = _unnamed_match(entry["pd"], d.pd)
        if got.name == name or by:
            row["identified"] = True
            if by:
                row["identified_by"] = by
            if want.mirror is None or got.mirror == want.mirror:
                refused = clear(s) or clear(s.with_labels(-s.labels))  # both chiralities are built-ins
                if refused is not None:
                    row["refused"] = row.get("refused", 0) + 1
                    if len(row.setdefault("errors", [])) < 3:
                        row["errors"].append(f"{layout}: {refused}")
                    continue
                row.update(layout=layout, mirror_right=True, design_crossings=int(abs(s.labels).sum()))
                row.update(
                    edges=s.n_edges, faces=s.n_faces, tries=len(row.get("names", [])) + len(row.get("errors", []))
                )
                break
    row["seconds"] = round(time.perf_counter() - t0, 3)
    return row


def _unnamed_match(table_pd: list, design_pd) -> str | None:
    """How a design the tables' names miss is identified with the table's diagram, or ``None``.

    Isometric exteriors (SnapPy), else, where SnapPy cannot decide (a non-hyperbolic
    link), equal Jones and HOMFLY-PT polynomials for some orientation of the components.
    """
    if _isometric(table_pd, design_pd):
        return "isometric exteriors (the tables' names miss this diagram)"
    if reversals(table_pd) & reversals([[int(v) for v in x] for x in design_pd]):
        return "Jones and HOMFLY-PT equal for some orientation of the components (SnapPy cannot compare the exteriors)"
    return None


def _isometric(table_pd: list, design_pd) -> bool:
    """Whether SnapPy finds the two diagrams' exteriors isometric (for links lkspace cannot name)."""
    import snappy

    one = snappy.Link([list(map(int, x)) for x in table_pd]).exterior()
    two = snappy.Link([[int(v) for v in x] for x in design_pd]).exterior()
    try:
        return bool(one.is_isometric_to(two))
    except RuntimeError:
        return False


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max-knot", type=int, default=10)
    parser.add_argument("--max-link", type=int, default=9)
    parser.add_argument("--resume", action="store_true", help="keep the rows of results/construct/report.json")
    parser.add_argument(
        "--only", default="", help="comma-separated names to check again, keeping every other row (implies --resume)"
    )
    parser.add_argument(
        "--clearance",
        action="store_true",
        help="keep the report's rows, but check again each type whose kept placement fails the embedding check",
    )
    args = parser.parse_args()
    types = table_types()
    out = os.path.join(ROOT, "results", "construct")
    if args.clearance:
        clearance_pass(types, args, out)
        return
    done: dict[str, dict] = {}
    only = set(args.only.split(",")) if args.only else set()
    if (args.resume or only) and os.path.exists(os.path.join(out, "report.json")):
        with open(os.path.join(out, "report.json")) as fh:
            done = {r["name"]: r for r in json.load(fh)["types"]}
        keep_moved(types, {n: r for n, r in done.items() if n not in only})
    rows = []
    for i, (name, entry) in enumerate(types.items()):
        limit = args.max_knot if entry["components"] == 1 else args.max_link
        entry["layout"] = None
        if entry["crossings"] <= limit:
            kept = done.get(name)
            again = name in only if only else not (kept and kept.get("layout"))
            rows.append(check(name, entry) if again or not kept else kept)
            entry["layout"] = rows[-1].get("layout")
            if "layout" not in rows[-1]:
                print("MISS", name, rows[-1].get("names"), rows[-1].get("errors"), flush=True)
        if i % 500 == 499 or i == len(types) - 1:
            write(types, rows, args, out)


def keep_moved(types: dict[str, dict], rows: dict[str, dict]) -> None:
    """Put back the shipped diagram of each type whose kept row was made from a moved one (``row["diagram"]``)."""
    with gzip.open(TABLE_FILE, "rt", encoding="utf-8") as fh:
        shipped = json.load(fh)
    for name, row in rows.items():
        if "diagram" in row and name in types:
            types[name]["pd"] = shipped[name]["pd"]


def clearance_pass(types: dict[str, dict], args: argparse.Namespace, out: str) -> None:
    """Check each kept placement's default geometry in both chiralities; check again the types refused.

    The standard tables first (knots to 10 crossings, links to 9), then the rest in table
    order; the table and report are written every 50 types, so a stopped pass keeps its
    work, and ``results/construct/clearance.json`` counts the types checked, refused
    before and refused after.  A type no placement of which passes keeps its old placement.
    """
    with open(os.path.join(out, "report.json")) as fh:
        old = json.load(fh)
    rows = {r["name"]: r for r in old["types"]}
    keep_moved(types, rows)
    path = os.path.join(out, "clearance.json")
    stats = {"checked": [], "refused_before": [], "refused_after": []}
    if os.path.exists(path):
        with open(path) as fh:
            stats = {k: v for k, v in json.load(fh).items() if k in stats}
    for name, entry in types.items():
        entry["layout"] = rows[name].get("layout") if name in rows else None

    def standard(name: str) -> bool:
        entry = types[name]
        return entry["crossings"] <= (10 if entry["components"] == 1 else 9)

    order = [n for n in types if n in rows and n not in stats["checked"]]
    order.sort(key=lambda n: not standard(n))
    for i, name in enumerate(order):
        entry, row = types[name], rows[name]
        if row.get("layout"):
            s = design_scaffold(entry["pd"], name, row["layout"])
            if clear(s) or clear(s.with_labels(-s.labels)):
                stats["refused_before"].append(name)
                new = check(name, entry)
                if new.get("layout"):
                    rows[name] = new
                    entry["layout"] = new["layout"]
                else:
                    stats["refused_after"].append(name)
                    row["clearance"] = "refused in every placement that names right"
                print(name, entry["layout"], flush=True)
        stats["checked"].append(name)
        if i % 50 == 49 or i == len(order) - 1:
            counts = {f"n_{k}": len(v) for k, v in stats.items()}
            with open(path, "w") as fh:
                json.dump({**counts, "load_average": os.getloadavg(), **stats}, fh, indent=1)
            write(types, list(rows.values()), args, out, old["summary"])
            print(json.dumps(counts), flush=True)


def write(
    types: dict[str, dict], rows: list[dict], args: argparse.Namespace, out: str, kept: dict | None = None
) -> None:
    """Write the shipped table and the report (every type not checked yet has ``layout: null``)."""
    payload = json.dumps(types, separators=(",", ":")).encode()
    tmp = TABLE_FILE + ".tmp"
    with gzip.GzipFile(tmp, "wb", mtime=0) as fh:
        fh.write(payload)
    os.replace(tmp, TABLE_FILE)
    summary = {
        "checked": len(rows),
        "constructed": sum(bool(r.get("constructed")) for r in rows),
        "identified": sum(bool(r.get("identified")) for r in rows),
        "mirror_right": sum(bool(r.get("mirror_right")) for r in rows),
        "minimal_crossings": sum(r.get("design_crossings") == r["table_crossings"] for r in rows),
        "identified_by_isometry": sum("isometric" in r.get("identified_by", "") for r in rows),
        "identified_by_polynomials": sum("HOMFLY" in r.get("identified_by", "") for r in rows),
        "seconds_per_type": round(sum(r["seconds"] for r in rows) / max(1, len(rows)), 3),
        "by_layout": {k: sum(str(r.get("layout")).split(":")[0].split("/")[0] == k for r in rows) for k in LAYOUTS},
        "other_colouring": sum(str(r.get("layout")).endswith("/more") for r in rows),
        "largest_face_outside": sum(r.get("layout") in LAYOUTS for r in rows),
        "max_knot": args.max_knot if kept is None else kept["max_knot"],
        "max_link": args.max_link if kept is None else kept["max_link"],
        "commit": subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, cwd=ROOT
        ).stdout.strip(),
        "version": __version__,
        "machine": platform.node(),
        "load_average": os.getloadavg(),
    }
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "report.json"), "w") as fh:
        json.dump({"summary": summary, "types": rows}, fh, indent=1)
    lines = ["# Every table type constructed and identified", "", "| | count |", "|---|---|"]
    lines += [f"| {k} | {v} |" for k, v in summary.items() if not isinstance(v, (dict, tuple))]
    lines += ["", "Placements kept: " + ", ".join(f"{k} {v}" for k, v in summary["by_layout"].items()), ""]
    if os.path.exists(os.path.join(out, "clearance.json")):
        with open(os.path.join(out, "clearance.json")) as fh:
            c = json.load(fh)
        lines += [
            f"Embedding check of the kept placements (`--clearance`, both chiralities): {c['n_checked']} types "
            f"checked, {c['n_refused_before']} refused before, {c['n_refused_after']} left with no placement "
            "that passes (names in `clearance.json`).",
            "",
        ]
    lines += [
        "## By crossing number",
        "",
        "| | crossings | types | made and named right | seconds per type |",
        "|---|---:|---:|---:|---:|",
    ]
    groups: dict[tuple[str, int], list[dict]] = {}
    for r in rows:
        groups.setdefault(("knots" if r["components"] == 1 else "links", r["table_crossings"]), []).append(r)
    for (kind, c), members in sorted(groups.items()):
        right = sum(bool(r.get("mirror_right")) for r in members)
        mean = sum(r["seconds"] for r in members) / len(members)
        lines.append(f"| {kind} | {c} | {len(members)} | {right} | {mean:.2f} |")
    lines.append("")
    misses = [r for r in rows if not r.get("mirror_right")]
    lines += ["## Misses", ""] + [f"- {r['name']}: {r.get('names')} {r.get('errors', '')}" for r in misses]
    with open(os.path.join(out, "README.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print(json.dumps(summary))


if __name__ == "__main__":
    main()
