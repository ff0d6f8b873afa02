"""Census of large design spaces: exact counts by component number, in shards.

Three studies (results in ``results/census/``, small JSON/MD/PNG files):

``parity``
    The dodecahedron, icosahedron and truncated octahedron under rotations, labels
    ``{0, 1}`` and ``{-1, 0, 1}``.  Every edge has degree K = 2, so ``{-1, 0, 1}`` reaches
    the residues 0 (label 0) and 1 (labels -1 and 1): the same ``2^E`` parity vectors as
    ``{0, 1}``, each standing for ``2^(odd edges)`` assignments.  One pass over the parity
    vectors of every Burnside term (:mod:`lkspace.design.census`) counts, per component
    number, how many vectors have each number of odd cycle variables; the two label sets
    are two weightings of the same histograms (weight 1, and ``2^odd``).  Shards are
    checkpointed (``$LKSPACE_CENSUS_CHECKPOINTS``, default ``/tmp/lkspace-census``) after
    each one, so a run can stop and go on; ``results/census/parity-NAME.json`` holds the
    counts, or for a run that did not finish the shards done and an extrapolation.

``lattice``
    The paper's open question, how the number of distinct LK structures grows with the
    lattice: supercells of ``tiling:square``, ``tiling:hexagonal`` (labels {0,1}),
    ``honeycomb:cP`` (labels 0..3: every residue of its degree-4 edges) and
    ``honeycomb:cI`` (labels 0..2, and {0,1}): designs and single-thread (one-component)
    designs versus cells, with wall time and throughput; a table and a plot.

``plan``
    Measured rates (residue vectors per second per core) and the core-hours of spaces
    beyond this machine.

Run from the repository root, e.g. ``nice python experiments/census.py parity --jobs 2``.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, ROOT)

from lkspace import load  # noqa: E402
from lkspace.design.census import SHARD_CHOICES, census, shard_term, terms  # noqa: E402
from lkspace.design.counting import burnside_total  # noqa: E402
from lkspace.design.space import make_space  # noqa: E402
from lkspace.runtime.schedulers import run_tasks  # noqa: E402

OUT = os.path.join(ROOT, "results", "census")
CHECKPOINTS = os.environ.get("LKSPACE_CENSUS_CHECKPOINTS", "/tmp/lkspace-census")
SOLIDS = ("dodecahedron", "icosahedron", "truncated-octahedron")


def save(name: str, data: dict) -> None:
    os.makedirs(OUT, exist_ok=True)
    tmp = os.path.join(OUT, name + ".tmp")
    with open(tmp, "w") as fh:
        json.dump(data, fh, indent=1)
        fh.write("\n")
    os.replace(tmp, os.path.join(OUT, name))


def parity(solid: str, jobs: int, budget: float) -> dict:
    """Census of ``solid`` for {0,1} and {-1,0,1} (one pass), checkpointed; stop after ``budget`` seconds."""
    space = make_space(load(solid), "-1..1", "rotations")
    all_terms = terms(space)
    items = []
    for g, t in enumerate(all_terms):
        items += [(g, a, min(t.size, a + SHARD_CHOICES)) for a in range(0, t.size, SHARD_CHOICES)]
    name = f"parity-{solid}.json"
    checkpoint = os.path.join(CHECKPOINTS, name)
    state = json.load(open(checkpoint)) if os.path.exists(checkpoint) else {}
    done = {tuple(k) for k in state.get("done", [])}
    hists = {int(g): _dense(cells) for g, cells in state.get("hists", {}).items()}
    seconds = float(state.get("seconds", 0.0))
    todo = [it for it in items if tuple(it) not in done]
    started = time.perf_counter()
    ran = 0
    for pos, hist in run_tasks(shard_term, (space, all_terms), todo, "local", jobs, name="census"):
        g = todo[pos][0]
        h = hist.astype(object)
        hists[g] = h if g not in hists else _add(hists[g], h)
        done.add(tuple(todo[pos]))
        ran += todo[pos][2] - todo[pos][1]
        elapsed = seconds + time.perf_counter() - started
        state = _parity_state(space, all_terms, items, done, hists, elapsed, jobs)
        os.makedirs(CHECKPOINTS, exist_ok=True)
        with open(checkpoint + ".tmp", "w") as fh:
            json.dump(state, fh)
        os.replace(checkpoint + ".tmp", checkpoint)
        save(name, {k: v for k, v in state.items() if k not in ("done", "hists")})
        if time.perf_counter() - started > budget:
            break
    return state


def _dense(cells: list[list[int]]) -> np.ndarray:
    rows = max([c[0] for c in cells] + [0]) + 1
    cols = max([c[1] for c in cells] + [0]) + 1
    out = np.zeros((rows, cols), dtype=object)
    for comp, cell, n in cells:
        out[comp, cell] = n
    return out


def _add(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    rows, cols = max(a.shape[0], b.shape[0]), max(a.shape[1], b.shape[1])
    out = np.zeros((rows, cols), dtype=object)
    out[: a.shape[0], : a.shape[1]] += a
    out[: b.shape[0], : b.shape[1]] += b
    return out


def _parity_state(space, all_terms, items, done, hists, seconds, jobs) -> dict:
    vectors_total = sum(b - a for _, a, b in items)
    vectors_done = sum(b - a for g, a, b in items if (g, a, b) in done)
    complete = len(done) == len(items)
    result: dict = {
        "scaffold": space.scaffold.name,
        "edges": space.scaffold.n_edges,
        "symmetry": "rotations",
        "group_order": space.group_order,
        "parity_vectors": 2**space.scaffold.n_edges,
        "shards": len(items),
        "shards_done": len(done),
        "vectors_total": vectors_total,
        "vectors_done": vectors_done,
        "seconds": round(seconds, 1),
        "jobs": jobs,
        "vectors_per_second": round(vectors_done / max(seconds, 1e-9)),
        "complete": complete,
        "done": sorted(list(k) for k in done),
        "hists": {str(g): [[int(c), int(k), int(h[c, k])] for c, k in zip(*np.nonzero(h))] for g, h in hists.items()},
    }
    if complete:
        result.update(parity_counts(space, all_terms, hists))
    else:
        rate = result["vectors_per_second"]
        result["extrapolated_seconds_for_all"] = round(vectors_total / max(rate, 1))
    return result


LABEL_SETS = [("0,1", 1, 1), ("-1..1", 1, 2), ("-2..2", 3, 2), ("-3..3", 3, 4)]
"""Label sets counted from one parity pass: name, labels of residue 0, labels of residue 1 (K = 2)."""


def parity_counts(space, all_terms, hists) -> dict:
    """Designs by components of every label set of :data:`LABEL_SETS` from the parity histograms.

    Under rotations every cycle's signs multiply to +1, so a term's vector with ``k`` of its
    ``n`` cycle variables odd stands for ``even^(n - k) * odd^k`` fixed assignments.
    """
    n_g = space.n_actions
    out: dict = {}
    for name, even, odd in LABEL_SETS:
        by: dict[int, int] = {}
        for g, h in hists.items():
            n_var = len(all_terms[g].n_choices)
            for comp, cell in zip(*(x.tolist() for x in np.nonzero(h)), strict=True):
                by[comp] = by.get(comp, 0) + int(h[comp, cell]) * even ** (n_var - cell) * odd**cell
        assert all(n % n_g == 0 for n in by.values())
        counts = {str(c): n // n_g for c, n in sorted(by.items()) if n}
        check = burnside_total(make_space(space.scaffold, name, "rotations"))
        out[f"labels {name}"] = {
            "designs": sum(counts.values()),
            "burnside_total_agrees": sum(counts.values()) == check,
            "by_components": counts,
        }
    return out


def parity_report(solid: str) -> None:
    """Rewrite ``results/census/parity-NAME.json`` from a finished checkpoint (all label sets)."""
    space = make_space(load(solid), "-1..1", "rotations")
    all_terms = terms(space)
    with open(os.path.join(CHECKPOINTS, f"parity-{solid}.json")) as fh:
        state = json.load(fh)
    hists = {int(g): _dense(cells) for g, cells in state["hists"].items()}
    summary = {k: v for k, v in state.items() if k not in ("done", "hists") and not k.startswith("labels")}
    summary.pop("burnside_totals_agree", None)
    if state["complete"]:
        summary.update(parity_counts(space, all_terms, hists))
    save(f"parity-{solid}.json", summary)


LATTICE = [  # family, label set, supercell shapes (cells grow)
    ("tiling:square", "0,1", ["1x1", "2x1", "2x2", "3x2", "4x2", "3x3", "4x3"]),
    ("tiling:hexagonal", "0,1", ["1x1", "2x1", "2x2", "3x2", "4x2"]),
    ("honeycomb:cP", "0..3", ["1x1x1", "2x1x1", "3x1x1", "2x2x1"]),
    ("honeycomb:cI", "0..2", ["1x1x1"]),
    ("honeycomb:cI", "0,1", ["1x1x1", "2x1x1"]),
]


def lattice(jobs: int, families: list[str] | None = None) -> list[dict]:
    path = os.path.join(OUT, "lattice.json")
    rows = json.load(open(path))["rows"] if families and os.path.exists(path) else []
    for family, labels, shapes in LATTICE:
        if families and family not in families:
            continue
        for shape in shapes:
            space = make_space(load(f"{family}@{shape}"), labels, "rotations")
            t0 = time.perf_counter()
            found = census(space, "local", jobs)
            dt = time.perf_counter() - t0
            cells = int(np.prod([int(x) for x in shape.split("x")]))
            vectors = sum(t.size for t in terms(space))
            row = {
                "scaffold": f"{family}@{shape}",
                "family": family,
                "labels": labels,
                "cells": cells,
                "edges": space.scaffold.n_edges,
                "group_order": space.group_order,
                "residue_vectors": space.n_classes,
                "designs": found.designs,
                "single_thread_designs": found.by_components.get(1, 0),
                "by_components": {str(k): v for k, v in found.by_components.items()},
                "seconds": round(dt, 2),
                "vectors_per_second": round(vectors / dt),
                "jobs": jobs,
            }
            print(json.dumps(row), flush=True)
            rows.append(row)
            save("lattice.json", {"rows": rows})
    return rows


def lattice_report(rows: list[dict]) -> None:
    from matplotlib.figure import Figure

    from lkspace.design.counting import count_space
    from tests.brute_periodic import brute_group, burnside

    for r in rows:
        space = make_space(load(r["scaffold"]), r["labels"], "rotations")
        # independent of lkspace.symmetry and of the census: a brute-force group, Burnside's total
        sizes = [int(x) for x in r["scaffold"].split("@")[1].split("x")]
        group = brute_group(space.scaffold, 2 * max(sizes))
        labels = [int(t) for t in space.label_set]
        r["brute_rotations"] = sum(sign == 1 for sign, _ in group)
        r["brute_designs"] = burnside(group, labels, "rotations")
        r["checked_by_brute_group"] = (r["brute_rotations"], r["brute_designs"]) == (r["group_order"], r["designs"])
        if space.n_classes <= 1 << 20:  # the same group, another counting path (by components)
            by = count_space(space).by_components or {}
            r["checked_by_class_walk"] = {str(k): v for k, v in by.items()} == r["by_components"]

    fig = Figure(figsize=(6.4, 4.0), dpi=80)
    ax = fig.add_subplot(1, 1, 1)
    keys = sorted({(r["family"], r["labels"]) for r in rows}, key=str)
    for i, (family, labels) in enumerate(keys):
        pts = sorted(
            (r["cells"], r["designs"], r["single_thread_designs"])
            for r in rows
            if (r["family"], r["labels"]) == (family, labels)
        )
        x = [p[0] for p in pts]
        color = f"C{i}"
        ax.plot(x, [p[1] for p in pts], "o-", color=color, label=f"{family} {{{labels}}}: designs")
        ax.plot(x, [max(p[2], 0.8) for p in pts], "s--", color=color, alpha=0.6, label="  single-thread")
    ax.set_yscale("log")
    ax.set_xlabel("cells in the supercell")
    ax.set_ylabel("designs up to rotation")
    ax.set_title("Distinct LK structures vs lattice size", fontsize=10)
    ax.legend(fontsize=6, ncol=2)
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "lattice.png"))
    lines = [
        "# Distinct LK structures versus lattice size",
        "",
        "Designs up to rotation (symmetries of the supercell torus) of supercells; `single-thread`:",
        "designs with one component.  Exact census (Burnside by components over every residue",
        "vector, `experiments/census.py lattice`); wall time on the shared 2-core machine (load",
        "average 8-16 during the runs; the first row of each run includes loading the compiled kernels).",
        "Labels: {0,1} on the degree-2 edges of the tilings are all their residues (parity); {0..3} and",
        "{0..2} are all residues of the cP (K = 4) and cI (K = 3) edges, so those designs are the",
        "distinct strand structures (LK structures) themselves.  The count grows about as",
        "(residues per edge)^edges / |group|: exponentially in the number of cells; the symmetry of",
        "the supercell (its group column) matters as much as its size.",
        "",
        "| supercell | labels | cells | edges | group | residue vectors | designs | single-thread | seconds | vectors/s "
        "| checked: brute group | checked: class walk |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    verdict = {True: "yes", False: "NO"}
    for r in rows:
        lines.append(
            f"| {r['scaffold']} | {{{r['labels']}}} | {r['cells']} | {r['edges']} | {r['group_order']} | "
            f"{r['residue_vectors']:,} | {r['designs']:,} | {r['single_thread_designs']:,} | {r['seconds']} | "
            f"{r['vectors_per_second']:,} | {verdict.get(r.get('checked_by_brute_group'), '-')} | "
            f"{verdict.get(r.get('checked_by_class_walk'), '-')} |"
        )
    lines += [
        "",
        "`checked: brute group`: the rotation group built by brute force, independently of",
        "`lkspace.symmetry` (`tests/brute_periodic.py`: every integer matrix N with entries up to",
        "twice the largest supercell factor, every translation, faces and edges checked), has the",
        "order in `group`, and Burnside's lemma over it gives the `designs` total.  It checks the",
        "group and the total, not the split by components.  `checked: class walk`: the split by",
        "components equals the count over representative residue classes (`count_space`) where the",
        "space has at most 2^20 residue classes; that path uses the same group, so it checks the",
        "census's counting, not the symmetry.",
        "",
        "Corrected on 2026-12-02: until then the periodic symmetry search missed the symmetries of",
        "supercells whose point-group matrices need entries beyond {-1, 0, 1} (for",
        "`tiling:hexagonal@2x1` the half-turns about in-plane axes along and across a2), so rows",
        "with a too-small group over-counted designs; `checked` compared two counts made with that",
        "same group and could not see it.",
        "",
        "![designs vs cells](lattice.png)",
        "",
    ]
    save("lattice.json", {"rows": rows})
    with open(os.path.join(OUT, "lattice.md"), "w") as fh:
        fh.write("\n".join(lines))


BEYOND = [  # scaffold, labels, what it answers
    ("truncated-octahedron", "-1..1", "parity classes {0,1}, {-1,0,1}, -2..2, ... (one pass)"),
    ("tiling:square@4x4", "0,1", "square lattice, 16 cells"),
    ("tiling:square@5x5", "0,1", "square lattice, 25 cells"),
    ("tiling:hexagonal@4x4", "0,1", "hexagonal lattice, 16 cells"),
    ("honeycomb:cP@2x2x2", "0..3", "cubic honeycomb, 8 cells, all residues"),
    ("honeycomb:cI@2x1x1", "0..2", "bcc honeycomb, 2 cells, all residues"),
    ("honeycomb:cI@3x1x1", "0,1", "bcc honeycomb, 3 cells, parity"),
]


MEASURE = [
    ("dodecahedron", "-1..1"),
    ("truncated-octahedron", "-1..1"),
    ("tiling:square@4x3", "0,1"),
    ("honeycomb:cP@2x2x1", "0..3"),
]


def plan(sample: int = 1 << 21) -> None:
    """Core-hours of spaces beyond this machine, from CPU-time rates measured here.

    The census walks every port of every residue vector, so CPU seconds per vector are
    about ``c * ports``; ``c`` is measured on ``sample`` vectors of a few spaces in this
    process (CPU time: robust to the other jobs on the machine, unlike wall time).
    """
    measured = []
    for name, labels in MEASURE:
        space = make_space(load(name), labels, "rotations")
        all_terms = terms(space)
        shard_term((space, all_terms), (0, 0, 1000))  # compiled outside the timing
        t0 = time.process_time()
        shard_term((space, all_terms), (0, 0, sample))
        cpu = time.process_time() - t0
        ports = 2 * space.scaffold.n_corners
        measured.append(
            {"space": f"{name} {{{labels}}}", "ports": ports, "vectors_per_cpu_second": round(sample / cpu)}
        )
    c = float(np.median([1 / (m["vectors_per_cpu_second"] * m["ports"]) for m in measured]))
    rows = []
    for name, labels, what in BEYOND:
        space = make_space(load(name), labels, "rotations")
        vectors = sum(t.size for t in terms(space))
        ports = 2 * space.scaffold.n_corners
        rows.append(
            {
                "scaffold": name,
                "labels": labels,
                "what": what,
                "edges": space.scaffold.n_edges,
                "residue_vectors": vectors,
                "ports": ports,
                "core_hours": vectors * c * ports / 3600,
            }
        )
    save("plan.json", {"cpu_seconds_per_vector_and_port": c, "measured": measured, "rows": rows})
    lines = [
        "# Plan: census of spaces beyond this machine",
        "",
        "A census costs one strand walk (every port) per residue vector of every Burnside term",
        f"(`experiments/census.py plan`).  Measured here in CPU time: {c * 1e9:.2f} ns per port and",
        "vector on one core (median of the spaces below; wall time on this shared machine was 2-5x",
        "longer, the other jobs taking the rest).",
        "",
        "| measured on | ports | vectors per CPU second |",
        "|---|---|---|",
        *[f"| {m['space']} | {m['ports']} | {m['vectors_per_cpu_second']:,} |" for m in measured],
        "",
        "| space | labels | edges | residue vectors | core-hours | on 100 cores |",
        "|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['scaffold']} ({r['what']}) | {{{r['labels']}}} | {r['edges']} | {r['residue_vectors']:.3g} | "
            f"{r['core_hours']:,.3g} | {r['core_hours'] / 100:,.3g} h |"
        )
    lines += [
        "",
        "Shards are 2^24 vectors (about 6 CPU seconds each), so each of these runs as Dask tasks",
        "(`lkspace enumerate SPACE --count-only --scheduler tcp://...`, docs/scale.md) with linear",
        "speed-up; the histograms are summed exactly.  Spaces of about 10^14 vectors (hexagonal 4x4,",
        "cP 2x2x2) need ~5*10^4 core-hours (days on a thousand cores); each further cell multiplies",
        "that by the residues per edge to the edges per cell, so past these the exact total from",
        "Burnside over the whole group (instant, `by_components: null`) is what remains.",
        "",
    ]
    with open(os.path.join(OUT, "plan.md"), "w") as fh:
        fh.write("\n".join(lines))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("study", choices=["parity", "parity-report", "lattice", "lattice-report", "plan"])
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--solids", nargs="*", default=list(SOLIDS))
    ap.add_argument("--families", nargs="*", help="lattice: only these families (rows of others kept)")
    ap.add_argument("--budget", type=float, default=1e9, help="seconds per solid before stopping (checkpointed)")
    args = ap.parse_args()
    if args.study == "parity":
        for solid in args.solids:
            state = parity(solid, args.jobs, args.budget)
            print(solid, {k: v for k, v in state.items() if k not in ("done", "hists")}, flush=True)
    elif args.study == "parity-report":
        for solid in args.solids:
            parity_report(solid)
    elif args.study == "lattice":
        lattice_report(lattice(args.jobs, args.families))
    elif args.study == "plan":
        plan()
    else:
        with open(os.path.join(OUT, "lattice.json")) as fh:
            lattice_report(json.load(fh)["rows"])


if __name__ == "__main__":
    main()
