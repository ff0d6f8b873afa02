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

import igraph as ig
import numpy as np

from lkspace import __version__, load
from lkspace.errors import LkspaceError
from lkspace.knots.assembly import assemble_pd
from lkspace.knots.naming import name_pd
from lkspace.model.scaffold import Scaffold
from lkspace.scaffolds.constructed import table
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
MAX_KINKS = 6
"""Most faces left over (each a kink, +1 in sum |t|) for a design on a scaffold to be searched."""
"""Distinct embeddings named per (type, colouring, scaffold) before giving up."""
LABEL_SET = "search"
"""The ``labels`` column of the atlas rows this search adds."""


def dual_graph(s: Scaffold) -> tuple[ig.Graph, dict[tuple[int, int], int]]:
    """The dual graph of a closed scaffold (faces as vertices) and ``(face, face) -> edge of S``."""
    sides: dict[int, list[int]] = {}
    for corner, e in enumerate(s.side_edge):
        sides.setdefault(int(e), []).append(int(s.corner_face[corner]))
    edge_of = {}
    for e, (f, g) in sides.items():
        edge_of[min(f, g), max(f, g)] = e
    return ig.Graph(n=s.n_faces, edges=sorted(edge_of)), edge_of


def tait_graph(pd: list, colouring: str) -> tuple[int, list[tuple[int, int, int]]] | None:
    """``(faces, [(f, g, label), ...])``: the collapsed Tait graph of one colouring, parallel edges summed.

    Summing is right for the edges of one twist region that the mesh kept apart, wrong for
    two twist regions between the same faces (a pretzel): naming the design tells.
    """
    mesh = diagram_mesh(pd, colouring=colouring)
    sides: dict[frozenset[int], list[int]] = {}
    for f, face in enumerate(mesh.faces):
        for a, b in zip(face, face[1:] + face[:1]):
            sides.setdefault(frozenset((a, b)), []).append(f)
    summed: dict[tuple[int, int], int] = {}
    for (u, v), t in zip(mesh.edges, mesh.labels):
        f, g = sides[frozenset((u, v))]
        if f == g:
            return None
        summed[min(f, g), max(f, g)] = summed.get((min(f, g), max(f, g)), 0) + t
    return len(mesh.faces), [(f, g, t) for (f, g), t in summed.items() if t]


def embeddings(n: int, edges: list, host: ig.Graph, edge_of: dict, n_edges: int) -> list[np.ndarray]:
    """Label vectors of S for the subgraph embeddings of the Tait graph (kinks on the faces left over)."""
    pattern = ig.Graph(n=n, edges=[(f, g) for f, g, _ in edges])
    maps = host.get_subisomorphisms_lad(pattern, induced=False)
    out: dict[bytes, np.ndarray] = {}
    step = max(1, len(maps) // (4 * TRIES))
    for m in maps[::step]:
        labels = np.zeros(n_edges, np.int64)
        for f, g, t in edges:
            a, b = m[f], m[g]
            labels[edge_of[min(a, b), max(a, b)]] = t
        covered, frontier = set(m), list(m)
        while frontier:  # breadth first: join every face left over by a kink
            nxt = []
            for a in frontier:
                for b in host.neighbors(a):
                    if b not in covered:
                        covered.add(b)
                        labels[edge_of[min(a, b), max(a, b)]] = 1
                        nxt.append(b)
            frontier = nxt
        out.setdefault(labels.tobytes(), labels)
        if len(out) >= TRIES:
            break
    return list(out.values())


def named(s: Scaffold, labels: np.ndarray) -> tuple[str | None, bool | None, int | None]:
    """Name, chirality and crossings of the simplified diagram of a design (``None``: not named)."""
    try:
        d = assemble_pd(s, labels)
        got = name_pd([[int(v) for v in x] for x in d.pd], d.n_components, floer=False)
    except LkspaceError:
        return None, None, None
    return got.name, got.mirror, got.crossings


def dihedron_candidates(pd: list) -> list[tuple[str, np.ndarray]]:
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


def search_type(name: str, entry: dict, hosts: dict) -> dict[str, dict]:
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

    for scaffold, labels in dihedron_candidates(entry["pd"]):
        if scaffold not in found:
            keep(scaffold, load(scaffold), labels, 0)
    graphs = [g for g in (tait_graph(entry["pd"], c) for c in ("fewer", "more")) if g is not None]
    for scaffold, (s, host, edge_of) in hosts.items():
        for n, edges in sorted(graphs, key=lambda g: -g[0]):  # more faces first: fewer kinks
            if n > s.n_faces or s.n_faces - n > MAX_KINKS:
                continue
            if scaffold in found and found[scaffold]["kinks"] <= s.n_faces - n:
                break
            for labels in embeddings(n, edges, host, edge_of, s.n_edges):
                if keep(scaffold, s, labels, s.n_faces - n):
                    break
    return found


def standard_types() -> dict[str, dict]:
    """The 379 types: prime knots to 10 crossings, prime links to 9 (the shipped table of diagrams)."""
    return {k: v for k, v in table().items() if v["crossings"] <= (10 if v["components"] == 1 else 9)}


def run_one(item: tuple[str, dict]) -> dict:
    """The search's row of one type (for a process pool)."""
    name, entry = item
    t0 = time.perf_counter()
    found = search_type(name, entry, HOST_GRAPHS)
    return {"name": name, "seconds": round(time.perf_counter() - t0, 3), "designs": found}


HOST_GRAPHS: dict = {}


def _init() -> None:
    for h in HOSTS:
        s = load(h)
        HOST_GRAPHS[h] = (s, *dual_graph(s))


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
    if fresh or previous is None:  # a resumed run that named nothing keeps the record of the run that did
        write_report(OUT, types, ordered, run)
    if args.atlas:
        add_to_atlas(types, ordered)


if __name__ == "__main__":
    main()
