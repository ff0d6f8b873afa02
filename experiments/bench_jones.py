"""Benchmark: the compiled Jones polynomial (:mod:`lkspace.knots.jones`) on projected random polygons.

Diagrams come from closed random polygons (1-4 components, 6-40 vertices each, wandering
around circles: many nugatory crossings, R1 and R2 moves) projected by
:func:`lkspace.knots.diagram.project`, binned by crossing count.  Per bin: the time per
diagram of :func:`~lkspace.knots.jones.jones_into` called from a compiled loop (as the
lead's kernels call it), the share of diagrams past the frontier cap (length -1), and
regina's ``Link.jones()`` on the same diagrams (``fromData``) for scale; every answer is
checked against regina's.  Writes ``results/bench_jones.json`` and ``results/bench_jones.md``.

Run: ``python experiments/bench_jones.py [--per-bin 300]``.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time

import numpy as np
from benchkit import RESULTS, load_average, provenance

from lkspace.compiled.kernels import kernel
from lkspace.knots.diagram import project
from lkspace.knots.jones import jones_buffer_size, jones_into

BINS = ((0, 10), (10, 20), (20, 40), (40, 80))


@kernel
def jones_batch(pds, starts, signs, n_free, out, lowest, lengths):  # noqa: ANN001, ANN201, D103
    width = out.shape[1]
    for i in range(len(starts) - 1):
        a, b = starts[i], starts[i + 1]
        lowest[i], lengths[i] = jones_into(pds[a:b], signs[a:b], n_free[i], out[i, :width])


def polygons(rng: np.random.Generator) -> list[np.ndarray]:
    out = []
    for _ in range(int(rng.integers(1, 5))):
        n = int(rng.integers(6, 41))
        angles = np.sort(rng.uniform(0, 2 * np.pi, n))
        radii = 1 + 0.6 * rng.standard_normal(n)
        points = np.column_stack([radii * np.cos(angles), radii * np.sin(angles), 0.8 * rng.standard_normal(n)])
        out.append(points + rng.uniform(-1.5, 1.5, 3))
    return out


def regina_link(regina, pd, signs, n_components):  # noqa: ANN001, ANN201
    """The regina link of a PD code and signs (as tests/test_jones.py builds it)."""
    head = {}
    for c, (a, b, k, d) in enumerate(pd):
        head[a] = (c, False, k)
        head[d if signs[c] > 0 else b] = (c, True, b if signs[c] > 0 else d)
    seen: set[int] = set()
    components = []
    for first in sorted(head):
        passages, edge = [], first
        while edge not in seen:
            seen.add(edge)
            c, over, edge = head[edge]
            passages.append(c + 1 if over else -(c + 1))
        if passages:
            components.append(passages)
    components += [[] for _ in range(n_components - len(components))]
    return regina.Link.fromData([int(s) for s in signs], components)


def measure_bin(diagrams: list, regina) -> dict:  # noqa: ANN001
    pds = np.array([row for d in diagrams for row in d.pd], np.int64).reshape(-1, 4)
    signs = np.concatenate([d.signs for d in diagrams]).astype(np.int64)
    starts = np.concatenate([[0], np.cumsum([d.n_crossings for d in diagrams])]).astype(np.int64)
    n_free = np.array([len(d.free_components) for d in diagrams], np.int64)
    width = max(jones_buffer_size(d.n_crossings, len(d.free_components)) for d in diagrams)
    out = np.zeros((len(diagrams), width), np.int64)
    lowest = np.zeros(len(diagrams), np.int64)
    lengths = np.zeros(len(diagrams), np.int64)
    runs = []
    for _ in range(5):
        t0 = time.perf_counter()
        jones_batch(pds, starts, signs, n_free, out, lowest, lengths)
        runs.append(time.perf_counter() - t0)
    each = []  # per diagram, one call of the compiled loop each (adds the call's own few microseconds)
    for i in range(n := len(diagrams)):
        a, b = starts[i], starts[i + 1]
        args = (pds[a:b], np.array([0, b - a], np.int64), signs[a:b], n_free[i : i + 1], out[i : i + 1])
        t0 = time.perf_counter()
        jones_batch(*args, lowest[i : i + 1], lengths[i : i + 1])
        each.append(time.perf_counter() - t0)
    mismatches = 0
    t0 = time.perf_counter()
    for i, d in enumerate(diagrams):
        poly = regina_link(regina, d.pd, d.signs, d.n_components).jones()
        if lengths[i] >= 0:
            mine = [(int(lowest[i]) + j, int(v)) for j, v in enumerate(out[i, : lengths[i]]) if v]
            theirs = [(e, int(str(poly[e]))) for e in range(poly.minExp(), poly.maxExp() + 1) if int(str(poly[e]))]
            mismatches += mine != theirs
    regina_seconds = time.perf_counter() - t0
    return {
        "diagrams": n,
        "crossings_mean": round(float(np.mean([d.n_crossings for d in diagrams])), 1),
        "too_wide": int((lengths == -1).sum()),
        "jones_us_per_diagram": round(1e6 * statistics.median(runs) / n, 1),
        "jones_us_per_diagram_best": round(1e6 * min(runs) / n, 1),
        "jones_us_p50_p95_max": [round(1e6 * float(np.percentile(each, q)), 1) for q in (50, 95, 100)],
        "regina_us_per_diagram": round(1e6 * regina_seconds / n, 1),
        "mismatches_with_regina": mismatches,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--per-bin", type=int, default=300)
    args = parser.parse_args()
    import regina

    rng = np.random.default_rng(2026)
    bins: dict[tuple[int, int], list] = {b: [] for b in BINS}
    while any(len(v) < args.per_bin for v in bins.values()):
        d = project(polygons(rng), seed=int(rng.integers(2**31)))
        for lo, hi in BINS:
            if lo <= d.n_crossings < hi and len(bins[lo, hi]) < args.per_bin:
                bins[lo, hi].append(d)
    t0 = time.perf_counter()
    jones_batch(np.zeros((0, 4), np.int64), np.zeros(1, np.int64), np.zeros(0, np.int64), np.zeros(0, np.int64),
                np.zeros((0, 1), np.int64), np.zeros(0, np.int64), np.zeros(0, np.int64))  # fmt: skip
    compile_seconds = time.perf_counter() - t0
    rows = {f"{lo}-{hi - 1}": measure_bin(bins[lo, hi], regina) for lo, hi in BINS}
    record = {
        "provenance": provenance(),
        "load_average": load_average(),
        "compile_or_cache_load_seconds": round(compile_seconds, 2),
        "bins": rows,
    }
    (RESULTS / "bench_jones.json").write_text(json.dumps(record, indent=2) + "\n")
    lines = [
        "# Compiled Jones polynomial (`lkspace.knots.jones`)",
        "",
        "Projected random polygons (1-4 components, 6-40 vertices each; `experiments/bench_jones.py`),",
        "binned by crossing count.  `jones_into` runs inside a compiled loop; regina's `Link.jones()`",
        "on the same diagrams for scale.  Median and best of 5 runs per bin; then each diagram",
        "timed alone (one call of the compiled loop: a few µs of call overhead included; a max of",
        "milliseconds is the process losing the CPU on this shared 2-core machine).",
        "",
        f"Machine: {record['provenance']['machine']}, load average {record['load_average']}, "
        f"commit {record['provenance']['commit']}; compile or cache load {compile_seconds:.2f} s.",
        "",
        "| crossings | diagrams | mean crossings | too wide (-1) | jones µs/diagram (median, best) "
        "| one diagram µs (p50, p95, max) | regina µs/diagram | mismatches |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for name, r in rows.items():
        lines.append(
            f"| {name} | {r['diagrams']} | {r['crossings_mean']} | {r['too_wide']} | "
            f"{r['jones_us_per_diagram']}, {r['jones_us_per_diagram_best']} | "
            f"{', '.join(map(str, r['jones_us_p50_p95_max']))} | {r['regina_us_per_diagram']} | "
            f"{r['mismatches_with_regina']} |"
        )
    (RESULTS / "bench_jones.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
