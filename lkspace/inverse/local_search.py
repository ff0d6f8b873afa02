"""Local search for designs with exactly N components (a heuristic; no proofs).

Used by the solver's fast path where greedy merging (:mod:`lkspace.inverse.constructive`) gets
stuck, typically on non-manifold scaffolds such as honeycomb supercells.  The state is a
labelling within the allowed labels; a move re-labels one edge whose ports lie on at
least two strands (when there are too many strands) or any edge of degree >= 2 (too
few), trying one label per residue class (the cheapest) and keeping the one whose
component count is closest to N; sideways moves are kept, worse ones with a small
probability.  Every evaluation is an exact trace (numba), so what it returns is correct
by construction and is traced again by the solver.  It stops at the time budget or after
``max(PATIENCE, 2 * n_edges)`` moves without getting closer to N, so an infeasible query
costs little before CP-SAT takes over.
"""

from __future__ import annotations

import time

import numpy as np

from ..model.scaffold import Scaffold
from ..runtime.progress import Step
from ..strands.walk import walk
from ..words import plural
from .query import Query, allowed_labels, cheapest_label

WORSE_MOVE_PROBABILITY = 0.02
PATIENCE = 300  # moves without getting closer to N (at least; more on big scaffolds) before giving up


def residue_options(scaffold: Scaffold, query: Query) -> list[np.ndarray]:
    """Per edge: the cheapest allowed label of each residue class mod K."""
    out = []
    for k, labels in zip(scaffold.edge_degrees.tolist(), allowed_labels(scaffold, query), strict=True):
        residues = labels % k
        picks = []
        for r in np.unique(residues):
            pick = cheapest_label(labels[residues == r], query.objective)
            assert pick is not None  # some label has residue r
            picks.append(pick[1])
        out.append(np.array(picks))
    return out


def local_search(
    scaffold: Scaffold,
    query: Query,
    start: np.ndarray,
    count: int,
    seed: int,
    time_budget: float,
    step: Step | None = None,
) -> list[np.ndarray]:
    """Search for up to ``count`` distinct designs with ``query.components`` strands, from ``start``.

    ``step`` (a :func:`lkspace.runtime.progress.task` step) is told the closest count so far.
    ``time_budget`` counts from the call (the set-up included).
    """
    deadline = time.perf_counter() + time_budget
    options = residue_options(scaffold, query)
    edge_of_port = np.repeat(scaffold.side_edge, 2)
    target = query.components
    rng = np.random.default_rng(seed)

    def evaluate(labels: np.ndarray) -> tuple[int, np.ndarray]:
        _, (_, starts, _, _, port_strand, _) = walk(scaffold, labels)
        return len(starts) - 1, port_strand

    labels = np.asarray(start, np.int64).copy()
    n, port_strand = evaluate(labels)
    designs, seen = [], set()
    movable = np.flatnonzero([len(o) > 1 for o in options])
    patience = max(PATIENCE, 2 * scaffold.n_edges)
    closest, stale = abs(n - target), 0
    while len(movable) and time.perf_counter() < deadline and stale < patience:
        if n == target:
            key = labels.tobytes()
            if key not in seen:
                seen.add(key)
                designs.append(labels.copy())
                if len(designs) == count:
                    break
            e = int(rng.choice(movable))  # a random kick to look for another design
            labels[e] = rng.choice(options[e])
            n, port_strand = evaluate(labels)
            continue
        if n > target:  # merge: an edge whose ports lie on two or more strands
            pairs = np.unique(edge_of_port * (n + 1) + port_strand)
            spread = np.bincount(pairs // (n + 1), minlength=scaffold.n_edges) >= 2
            pool = np.intersect1d(np.flatnonzero(spread), movable, assume_unique=True)
        else:
            pool = movable
        if len(pool) == 0:
            break
        e = int(rng.choice(pool))
        if step is not None:
            step.advance()
        best: tuple[int, np.ndarray, int, np.ndarray] | None = None  # distance to N, labels, strands, port_strand
        for t in rng.permutation(options[e]):
            if t == labels[e]:
                continue
            trial = labels.copy()
            trial[e] = t
            m, strands = evaluate(trial)
            if best is None or abs(m - target) < best[0]:
                best = (abs(m - target), trial, m, strands)
        if best is not None and (best[0] <= abs(n - target) or rng.random() < WORSE_MOVE_PROBABILITY):
            _, labels, n, port_strand = best
        if abs(n - target) < closest:
            closest, stale = abs(n - target), 0
            if step is not None:
                step.note(f"local search: closest {plural(n, 'component')}, want {target}")
        else:
            stale += 1
    return designs
