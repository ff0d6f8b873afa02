"""Benchmark ``lkspace.solve``: single-component and exact-N queries from the cube to 5,000+ faces.

Writes ``results/bench_solve.csv`` (one row per query) and prints the table.  Meshes: the
built-in solids, geodesic and cube spheres (:mod:`lkspace.scaffolds.spheres`), and
non-manifold ones: cube spheres with fins (an extra quad on every fifth or seventh
edge, K = 3), a chain of books and honeycomb supercells (K = 3 and 4).  Queries: ``--components 1 --no-zero`` and
exact N = 2 and N = 5, each as ``lkspace solve`` runs it (fast path first) and with CP-SAT
alone (``--no-fast-path``; exact N with CP-SAT alone only up to 1,500 faces).

    python experiments/bench_solve.py [--time-limit 60] [--workers 2] [--quick]
"""

from __future__ import annotations

import argparse
import csv
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

import lkspace  # noqa: E402
from lkspace import Scaffold  # noqa: E402
from lkspace.io.atomic import atomic_path  # noqa: E402
from lkspace.scaffolds.spheres import cube_sphere, geodesic_sphere  # noqa: E402


def with_fins(scaffold: Scaffold, every: int = 5, height: float = 0.15) -> Scaffold:
    """Glue a quad fin along every ``every``-th edge, pointing outward (those edges get K = 3)."""
    vertices = list(scaffold.vertices)
    faces = scaffold.faces()
    for e in range(0, scaffold.n_edges, every):
        a, b = scaffold.edge_vertices[e]
        pa, pb = scaffold.vertices[a], scaffold.vertices[b]
        out = (pa + pb) / 2
        out = out / np.linalg.norm(out)
        n = len(vertices)
        vertices += [pa + height * out, pb + height * out]
        faces.append([int(a), int(b), n + 1, n])
    return Scaffold.from_faces(np.array(vertices), faces, name=f"{scaffold.name}+fins/{every}")


def books(n_spines: int) -> Scaffold:
    """A chain of books: spines j = 0..n-1 on the x axis, consecutive spines joined by a quad,
    and one free page on each spine pointing +y (inner spines have K = 3)."""
    vertices, faces = [], []
    for j in range(n_spines):
        vertices += [[2.0 * j, 0, 0], [2.0 * j, 0, 1], [2.0 * j + 0.2, 1, 0], [2.0 * j + 0.2, 1, 1]]
        faces.append([4 * j, 4 * j + 2, 4 * j + 3, 4 * j + 1])
        if j + 1 < n_spines:
            faces.append([4 * j, 4 * j + 4, 4 * j + 5, 4 * j + 1][::-1])
    return Scaffold.from_faces(np.array(vertices), faces, name=f"books:{n_spines}")


def meshes(quick: bool):
    yield lkspace.load("cube")
    yield lkspace.load("dodecahedron")
    yield lkspace.load("truncated-octahedron")
    yield geodesic_sphere(2)
    yield cube_sphere(10)
    yield with_fins(cube_sphere(6))
    yield books(300)
    yield lkspace.load("honeycomb:cI@2x2x2")  # periodic, non-manifold (K = 3)
    if not quick:
        yield geodesic_sphere(3)
        yield geodesic_sphere(4)
        yield cube_sphere(29)
        yield with_fins(cube_sphere(29), every=7)
        yield books(2600)
        yield lkspace.load("honeycomb:cI@9x9x9")  # 5,103 faces, every edge K = 3
        yield lkspace.load("honeycomb:cP@12x12x12")  # 5,184 faces, every edge K = 4


def run_query(scaffold, n, no_zero, fast, args):
    t0 = time.perf_counter()
    result = lkspace.solve(
        scaffold,
        n,
        no_zero=no_zero,
        options=lkspace.SolveOptions(fast_path=fast, time_limit=args.time_limit, workers=args.workers, seed=0),
    )
    wall = time.perf_counter() - t0
    return {
        "mesh": scaffold.name,
        "faces": scaffold.n_faces,
        "edges": scaffold.n_edges,
        "max_degree": int(scaffold.edge_degrees.max()),
        "components": n,
        "no_zero": no_zero,
        "fast_path_allowed": fast,
        "method": result.method,
        "status": result.status,
        "seconds": round(wall, 4),
        "model_nodes": result.stats.get("model_nodes", ""),
    }


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--time-limit", type=float, default=60.0)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--quick", action="store_true", help="small meshes only")
    parser.add_argument("-o", "--output", default=os.path.join("results", "bench_solve.csv"))
    args = parser.parse_args(argv)
    lkspace.solve(lkspace.load("tetrahedron"), 1)  # warm up numba ...
    lkspace.solve(lkspace.load("tetrahedron"), 2, options=lkspace.SolveOptions(fast_path=False))  # ... and ortools
    rows = []
    for scaffold in meshes(args.quick):
        queries = [(1, True, True), (2, False, True), (5, False, True), (1, True, False)]
        if scaffold.n_faces <= 1500:  # CP-SAT alone on exact N: small and medium meshes only
            queries += [(2, False, False), (5, False, False)]
        for n, no_zero, fast in queries:
            row = run_query(scaffold, n, no_zero, fast, args)
            rows.append(row)
            print(" ".join(f"{k}={v}" for k, v in row.items()), flush=True)
    os.makedirs(os.path.dirname(args.output) or ".", exist_ok=True)
    with atomic_path(args.output) as tmp, open(tmp, "w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
