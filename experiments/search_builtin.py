"""Put every type of the standard tables on the built-in scaffolds: the simplest design found on each.

A design on a scaffold S draws the link whose Tait graph has the faces of S as vertices
and one edge per non-zero label (label 0: the two faces' strands do not cross there).  So
a table type whose collapsed Tait graph G (the dual of its checkerboard mesh
:func:`~lkspace.scaffolds.diagram_mesh.diagram_mesh`, one edge per twist region, label =
signed twist count) is a subgraph of the dual graph of S has a design on S: G's labels on
the matched edges.  Where G has fewer vertices than S has faces, every face left over is
joined to the matched part by one edge with label 1 along a spanning forest of the dual
graph: a bridge of the Tait graph, i.e. a kink (Reidemeister I), which costs 1 in sum |t|
and leaves the type alone.  A design with no kink has sum |t| = the crossing number.

Subgraph embeddings come from python-igraph's LAD; both colourings of the table's diagram
are tried.  Embeddings differ from the diagram's own at 2-cuts (mutants, flypes) and by a
reflection, so every candidate is named (:func:`~lkspace.knots.assembly.assemble_pd`,
:func:`~lkspace.knots.naming.name_pd`): a design named as the mirror image is negated, one
named as another type is dropped.  ``dihedron:N`` (two faces, N edges between them) takes
the types whose mesh has two faces, its labels in the order of the face's edges.

Writes ``results/builtin/{README.md,coverage.json}`` and, with ``--atlas``, adds the
designs of (type, scaffold) pairs the shipped atlas lacks to ``lkspace/data/atlas.parquet``
as rows with label set ``search`` (docs/design-to-target.md).

    nice python experiments/search_builtin.py [--types 8_17,L6a4] [--atlas]
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import subprocess
import time

import numpy as np

from lkspace import __version__, load
from lkspace.errors import LkspaceError
from lkspace.knots.assembly import assemble_pd
from lkspace.knots.naming import name_pd
from lkspace.linktypes.tait_embedding import embedded_designs
from lkspace.model.scaffold import Scaffold
from lkspace.scaffolds.constructed import TableDiagram, table
from lkspace.scaffolds.diagram_mesh import diagram_mesh

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "results", "builtin")
HOSTS = (
    ["tetrahedron", "cube", "octahedron", "dodecahedron", "icosahedron"]
    + ["truncated-tetrahedron", "cuboctahedron", "truncated-octahedron"]
    + [f"prism:{n}" for n in range(3, 11)]
    + [f"antiprism:{n}" for n in range(4, 6)]
)
"""The closed built-in scaffolds searched (``dihedron:N`` besides, for meshes of two faces)."""
TRIES = 4
"""Distinct embeddings named per (type, colouring, scaffold) before giving up."""
MAX_KINKS = 6
"""Most faces left over (each a kink, +1 in sum |t|) for a design on a scaffold to be searched."""
LABEL_SET = "search"
"""The ``labels`` column of the atlas rows this search adds."""


def named(s: Scaffold, labels: np.ndarray) -> tuple[str | None, bool | None, int | None]:
    """Name, chirality and crossings of the simplified diagram of a design (``None``: not named)."""
    try:
        d = assemble_pd(s, labels)
        got = name_pd([[int(v) for v in x] for x in d.pd], d.n_components, floer=False)
    except LkspaceError:
        return None, None, None
    return got.name, got.mirror, got.crossings


def dihedron_candidates(pd: tuple) -> list[tuple[str, np.ndarray]]:
    """Meshes of two faces: the labels around face 0 on ``dihedron:N`` (both directions)."""
    out = []
    for colouring in ("fewer", "more"):
        mesh = diagram_mesh(pd, colouring=colouring)
        if len(mesh.faces) != 2:
            continue
        face = mesh.faces[0]
        by_pair = {frozenset(e): t for e, t in zip(mesh.edges, mesh.labels)}
        cycle = [by_pair[frozenset((a, b))] for a, b in zip(face, face[1:] + face[:1])]
        nonzero = [t for t in cycle if t]
        cycle = nonzero if len(nonzero) >= 3 else cycle
        for c in (cycle, cycle[::-1]):
            s = load(f"dihedron:{len(c)}")  # its edge k joins vertices k and k + 1 (mod N)
            at = {(int(a), int(b)): e for e, (a, b) in enumerate(s.edge_vertices)}
            n = len(c)
            labels = [
                c[k] for e in range(n) for k in range(n) if at.get((k, (k + 1) % n), at.get(((k + 1) % n, k))) == e
            ]
            out.append((f"dihedron:{n}", np.array(labels, np.int64)))
    return out


def search_type(name: str, entry: TableDiagram, hosts: dict[str, Scaffold]) -> dict[str, dict]:
    """Scaffold -> the simplest design found there: ``{labels, sum_abs, nonzero, mirror, kinks}`` (table chirality)."""
    found: dict[str, dict] = {}

    def keep(scaffold: str, s: Scaffold, labels: np.ndarray, kinks: int) -> bool:
        got, mirror, crossings = named(s, labels)
        if got != name:
            return False
        if mirror:  # the mirror image: negate, so the kept design has the table's chirality
            labels = -labels
        cost = (int(abs(labels).sum()), int((labels != 0).sum()))
        old = found.get(scaffold)
        if old is None or cost < (old["sum_abs"], old["nonzero"]):
            found[scaffold] = {
                "labels": [int(t) for t in labels],
                "sum_abs": cost[0],
                "nonzero": cost[1],
                "mirror": None if mirror is None else False,
                "crossings": crossings,
                "kinks": kinks,
            }
        return True

    for scaffold, labels in dihedron_candidates(entry.pd):
        if scaffold not in found:
            keep(scaffold, load(scaffold), labels, 0)
    for scaffold, s in hosts.items():
        for kinks, labels in embedded_designs(s, entry.pd, TRIES, MAX_KINKS):  # fewest kinks first
            if keep(scaffold, s, labels, kinks):
                break
    return found


def standard_types() -> dict[str, TableDiagram]:
    """The 379 types: prime knots to 10 crossings, prime links to 9 (the shipped table of diagrams)."""
    return {k: v for k, v in table().items() if v.crossings <= (10 if v.components == 1 else 9)}


def run_one(item: tuple[str, TableDiagram]) -> dict:
    """The search's row of one type (for a process pool)."""
    name, entry = item
    t0 = time.perf_counter()
    found = search_type(name, entry, HOST_GRAPHS)
    return {"name": name, "seconds": round(time.perf_counter() - t0, 3), "designs": found}


HOST_GRAPHS: dict[str, Scaffold] = {}


def _init() -> None:
    for h in HOSTS:
        HOST_GRAPHS[h] = load(h)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--types", help="comma-separated names (default: the 379 of the standard tables)")
    parser.add_argument("--processes", type=int, default=2)
    parser.add_argument("--resume", action="store_true", help="keep the rows of results/builtin/coverage.json")
    parser.add_argument("--atlas", action="store_true", help="add the designs to lkspace/data/atlas.parquet")
    args = parser.parse_args()
    from multiprocessing import Pool

    from builtin_report import add_to_atlas, write_report

    types = standard_types()
    todo = {k: types[k] for k in args.types.split(",")} if args.types else types
    rows: dict[str, dict] = {}
    path = os.path.join(OUT, "coverage.json")
    previous = None
    if args.resume and os.path.exists(path):
        with open(path) as fh:
            previous = json.load(fh)
        rows = {r["name"]: r for r in previous["types"]}
    fresh = [(k, v) for k, v in todo.items() if k not in rows]
    load_before = os.getloadavg()
    t0 = time.perf_counter()
    with Pool(args.processes, initializer=_init) as pool:
        for i, row in enumerate(pool.imap(run_one, fresh)):
            rows[row["name"]] = row
            print(f"{i + 1}/{len(todo)} {row['name']} {row['seconds']}s {len(row['designs'])} scaffolds", flush=True)
    run = {
        "commit": subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, cwd=ROOT
        ).stdout.strip(),
        "version": __version__,
        "date": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "machine": f"{platform.node()} ({os.cpu_count()} cores)",
        "processes": args.processes,
        "load_before": [round(x, 2) for x in load_before],
        "load_after": [round(x, 2) for x in os.getloadavg()],
        "wall_seconds": round(time.perf_counter() - t0, 1),
        "scaffolds": HOSTS + ["dihedron:N"],
    }
    ordered = [rows[k] for k in types if k in rows]
    partial = args.types and not args.resume  # a few types alone: printed, never written over the whole table
    if (fresh or previous is None) and not partial:  # a resumed run that named nothing keeps the record
        write_report(OUT, types, ordered, run)
    if args.atlas:
        add_to_atlas(types, ordered)


if __name__ == "__main__":
    main()
