"""Structured design spaces: symmetric designs of the Platonic solids, surfaces of small graphs.

Writes ``results/structured/symmetric_platonic.{md,json}`` (per solid and subgroup: the
subgroup's order, edge orbits, fixed assignments and designs up to the normalizer, for
labels -1..1 and -2..2) and ``results/structured/graph_surfaces.{md,json}`` (per graph:
the face sets with every edge on 2 (or 3) faces up to automorphism, and the strand
structures and designs they carry) and ``results/structured/motifs.{md,json}`` (motif classes on
a few supercells, with how many hold together and how many are all threads).
Run: ``python experiments/structured_spaces.py``.
"""

from __future__ import annotations

import json
import math
import pathlib
import time

import numpy as np

from lkspace import load, trace
from lkspace.design.embeddings import graph_surfaces
from lkspace.design.graph_faces import named_graph
from lkspace.design.invariant import make_invariant_space
from lkspace.design.invariant_walk import invariant_blocks
from lkspace.design.motifs import cell_map, check_tiles, motif_classes, tiling_matrix
from lkspace.symmetry.group import symmetry_group

OUT = pathlib.Path(__file__).resolve().parents[1] / "results" / "structured"
SOLIDS = ("tetrahedron", "cube", "octahedron", "dodecahedron", "icosahedron")
SUBGROUPS = {
    "tetrahedron": ["rotations", "C3:vertex=0", "C2:edge=0", "stabilizer:face=0", "isometry-stabilizer:edge=0"],
    "cube": ["rotations", "C4:face=0", "C2:face=0", "C3:vertex=0", "C2:edge=0", "isometry-stabilizer:face=0"],
    "octahedron": ["rotations", "C4:vertex=0", "C2:vertex=0", "C3:face=0", "C2:edge=0", "isometry-stabilizer:vertex=0"],
    "dodecahedron": ["rotations", "C5:face=0", "C3:vertex=0", "C2:edge=0", "isometry-stabilizer:face=0"],
    "icosahedron": ["rotations", "C5:vertex=0", "C3:face=0", "C2:edge=0", "isometry-stabilizer:vertex=0"],
}
LIST_UP_TO = 200_000
"""Fixed assignments up to which designs are also split by components (listed)."""

MOTIFS = [
    ("tiling:square", (2, 2), (1, 1), ()),
    ("tiling:square", (4, 2), (2, 1), (1,)),
    ("tiling:square", (2, 2), (2, 2), (0,)),
    ("tiling:hexagonal", (2, 2), (1, 1), ()),
    ("honeycomb:cP", (2, 2, 2), (1, 1, 1), ()),
    ("honeycomb:cP", (2, 1, 1), (2, 1, 1), (0, 0, 0)),
]

GRAPHS = [
    ("K4", 4, 2),
    ("K4", 4, 4),
    ("K5", 3, 3),
    ("octahedron", 4, 2),
    ("cube", 6, 2),
    ("K3,3", 6, 2),
    ("petersen", 9, 2),
]


def symmetric_rows() -> list[dict]:
    rows = []
    for solid in SOLIDS:
        sc = load(solid)
        for labels in ("-1..1", "-2..2"):
            lab = np.arange(-1, 2) if labels == "-1..1" else np.arange(-2, 3)
            for sub in SUBGROUPS[solid]:
                t0 = time.perf_counter()
                space = make_invariant_space(sc, lab, "rotations", sub)
                row = {"solid": solid, "labels": labels, **space.summary(), "designs": space.count_designs()}
                if space.n_fixed <= LIST_UP_TO:
                    by: dict[int, int] = {}
                    for block in invariant_blocks(space):
                        for c in block.traces.components[block.row_class].tolist():
                            by[c] = by.get(c, 0) + 1
                    assert sum(by.values()) == row["designs"]
                    row["by_components"] = dict(sorted(by.items()))
                row.pop("vertex_perms")
                row["seconds"] = round(time.perf_counter() - t0, 3)
                rows.append(row)
                print(solid, labels, sub, row["designs"], row["seconds"], flush=True)
    return rows


def graph_rows() -> list[dict]:
    rows = []
    for name, length, per_edge in GRAPHS:
        t0 = time.perf_counter()
        found = graph_surfaces(named_graph(name), length, per_edge, [-1, 0, 1])
        rows.append(
            {
                "graph": name,
                "max_length": length,
                "per_edge": per_edge,
                "face_sets": len(found),
                "covers": sum(s.covers for s in found),
                "structures": sum(s.structures for s in found),
                "designs_-1..1": sum(s.designs or 0 for s in found),
                "surfaces": [
                    {
                        "face_sizes": sorted(len(f) for f in s.faces),
                        "covers": s.covers,
                        "symmetry": s.symmetry,
                        "radial_orders": s.radial_orders,
                        "structures": s.structures,
                        "designs": s.designs,
                    }
                    for s in found
                ],
                "seconds": round(time.perf_counter() - t0, 3),
            }
        )
        print(name, length, per_edge, len(found), rows[-1]["structures"], rows[-1]["seconds"], flush=True)
    return rows


def motif_rows() -> list[dict]:
    rows = []
    for name, sizes, block, shifts in MOTIFS:
        t0 = time.perf_counter()
        base = load(name)
        sc = load(f"{name}@{'x'.join(map(str, sizes))}")
        base_edge, cell = cell_map(base, sc, sizes)
        tiling = tiling_matrix(block, shifts)
        check_tiles(tiling, sizes)
        perms, signs = symmetry_group(sc).action("rotations")
        classes = motif_classes(base_edge, cell, tiling, [-1, 0, 1], perms, signs)
        traces = [trace(sc, c.labels) for c in classes]
        threads = [int(np.any(np.asarray(t.periods) != 0, axis=1).sum()) for t in traces]
        rows.append(
            {
                "scaffold": sc.name,
                "block": list(block),
                "offsets": list(shifts),
                "motifs": sum(c.motifs for c in classes),
                "classes": len(classes),
                "hold_together": sum(t.holds_together for t in traces),
                "all_threads": sum(1 for t, n in zip(traces, threads, strict=True) if n == t.components),
                "components": sorted({int(t.components) for t in traces}),
                "seconds": round(time.perf_counter() - t0, 3),
            }
        )
        print(rows[-1], flush=True)
    return rows


def laves_row() -> dict:
    """The Laves cell (periodic: outside the cover search): which sets of its 10-ring classes cover evenly."""
    import itertools

    import lkspace

    sc = load("laves")
    even = {}
    for r in range(1, sc.n_faces + 1):
        for faces in itertools.combinations(range(sc.n_faces), r):
            sides = np.concatenate([np.arange(sc.face_starts[f], sc.face_starts[f + 1]) for f in faces])
            degrees = np.bincount(sc.side_edge[sides], minlength=sc.n_edges)
            if len(set(degrees.tolist())) == 1:
                even.setdefault(int(degrees[0]), []).append(list(faces))
    k = int(sc.edge_degrees[0])
    geometric = sum(len(df) for df in lkspace.designs(sc, list(range(k)), selection=lkspace.Selection(mode="residues")))
    return {
        "edges_per_cell": sc.n_edges,
        "ring_classes_per_cell": sc.n_faces,
        "even_covers": {str(d): len(v) for d, v in even.items()},
        "degree": k,
        "radial_orders_per_cell": math.factorial(k - 1) ** sc.n_edges,
        "structures_geometric_order": geometric,
    }


def write(rows: list[dict], graphs: list[dict]) -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "symmetric_platonic.json").write_text(json.dumps(rows, indent=1) + "\n")
    (OUT / "graph_surfaces.json").write_text(json.dumps(graphs, indent=1) + "\n")
    lines = [
        "# Symmetric designs of the Platonic solids",
        "",
        "Designs fixed by a subgroup H of the rotations (or, for `isometry-stabilizer`, of all symmetries),",
        "up to the normalizer of H in the rotation group (`lkspace enumerate SOLID --invariant H`).",
        "Written by `experiments/structured_spaces.py`.",
        "",
        "| solid | labels | H | order | normalizer | edge orbits (zero) | fixed assignments | designs | by components |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        by = ", ".join(f"{k}: {v}" for k, v in r.get("by_components", {}).items()) or "(counted, not listed)"
        lines.append(
            f"| {r['solid']} | {r['labels']} | `{r['subgroup']}` | {r['order']} | {r['normalizer_order']} | "
            f"{r['edge_orbits']} ({r['zero_orbits']}) | {r['fixed_assignments']:,} | {r['designs']:,} | {by} |"
        )
    (OUT / "symmetric_platonic.md").write_text("\n".join(lines) + "\n")
    lines = [
        "# How many distinct LK structures does one graph admit?",
        "",
        "Cycles of length <= L become faces, each edge on exactly D faces; face sets up to the graph's",
        "automorphisms.  A structure is a radial order and a residue t mod K per edge, up to the",
        "automorphisms keeping the face set (distinct strand structures); designs use labels -1..1.",
        "(`lkspace surfaces GRAPH --max-length L --per-edge D --labels -1..1`; `experiments/structured_spaces.py`.)",
        "",
        "| graph | L | D | face sets | covers | structures | designs (-1..1) | face sets: sizes, symmetry, radial orders, structures |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for g in graphs:
        detail = "; ".join(
            f"{s['face_sizes']} sym {s['symmetry']} ro {s['radial_orders']} st {s['structures']:,}"
            for s in g["surfaces"][:6]
        )
        more = f"; … ({len(g['surfaces']) - 6} more)" if len(g["surfaces"]) > 6 else ""
        lines.append(
            f"| {g['graph']} | {g['max_length']} | {g['per_edge']} | {g['face_sets']} | {g['covers']} | "
            f"{g['structures']:,} | {g['designs_-1..1']:,} | {detail}{more} |"
        )
    lv = laves_row()
    (OUT / "laves.json").write_text(json.dumps(lv, indent=1) + "\n")
    lines += [
        "",
        "## The Laves graph (srs net), one primitive cell",
        "",
        "A periodic net: the cover search above takes finite graphs only, so only its 10-rings are tried as",
        f"faces.  Of the subsets of the {lv['ring_classes_per_cell']} ring classes per cell, those putting every",
        f"edge class on the same number of faces: {lv['even_covers']} (degree: count), i.e. only all of them",
        f"(every edge on {lv['degree']} rings).  Each edge then has 9! radial orders: {lv['radial_orders_per_cell']:.3e}",
        "per cell, not counted up to automorphism here.  With the geometric radial order, the residue classes",
        f"t mod {lv['degree']} up to rotations number {lv['structures_geometric_order']:,}",
        f"(`lkspace enumerate laves --labels 0..{lv['degree'] - 1} --mode residues`).",
    ]
    (OUT / "graph_surfaces.md").write_text("\n".join(lines) + "\n")


def write_motifs(rows: list[dict]) -> None:
    (OUT / "motifs.json").write_text(json.dumps(rows, indent=1) + "\n")
    lines = [
        "# Motifs on supercells",
        "",
        "Every motif with labels -1..1 on a block of cells, repeated (with the offsets below the tiling's",
        "diagonal) over the supercell; classes are designs up to the supercell's rotations",
        "(`lkspace motifs NAME --supercell S --block B --offsets O --labels -1..1`).  The class counts",
        "depend on the periodic symmetry group of the supercell.",
        "",
        "| supercell | block | offsets | motifs | classes | hold together | only threads | components |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['scaffold']} | {'x'.join(map(str, r['block']))} | {r['offsets']} | {r['motifs']:,} | "
            f"{r['classes']:,} | {r['hold_together']:,} | {r['all_threads']:,} | {r['components']} |"
        )
    (OUT / "motifs.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    write_motifs(motif_rows())
    graphs = graph_rows()
    write(symmetric_rows(), graphs)
