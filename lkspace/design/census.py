"""Census: exact design counts by component number for spaces too big to list, in shards.

Burnside's lemma, split by components (constant on an orbit, and a function of the
residues ``t mod K`` only)::

    designs with c components = (1/|G|) sum_g #{t in SET^E : g t = t, components(t) = c}

An assignment fixed by ``g`` is constant along each cycle of ``g``'s edge permutation up
to its signs, so the fixed ones are enumerated at the level of residues: one **variable**
per cycle (for the identity, per edge) taking each residue class ``r`` the label set
reaches, weighted by the labels of that class (``n(r)``: the label count when the signs
around the cycle multiply to +1; when they multiply to -1 only ``t = 0`` is fixed, so
the weight is 1 for the class of 0 and the class is skipped otherwise).  Each residue
vector is traced once (components only, :mod:`lkspace.design.census_kernel`).

Weights stay exact: a shard counts residue vectors per ``(components, how many variables
have each label count)`` in int64 cells, and the sum ``count * prod n^k`` is taken in
Python integers.  Example: labels ``{-1, 0, 1}`` on edges of degree K = 2 (every edge of
a polyhedron) reach residues 0 (label 0) and 1 (labels -1 and 1), so they have the
residue classes of labels ``{0, 1}`` with weight ``2^(odd edges)``: both label sets come
from one pass over the ``2^E`` parity vectors.

Shards are contiguous ranges of one term's choices (about :data:`SHARD_CHOICES` each);
they run on any scheduler of :mod:`lkspace.runtime.schedulers` and their histograms are summed.  A
shard is walked in compiled calls of about :data:`CALL_PORT_VISITS` port visits, short
enough that Ctrl-C (seen between calls) stops a census within a moment.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..errors import LabelError, TooLargeError
from ..runtime.progress import task
from ..runtime.schedulers import run_tasks
from ..strands.ports import port_model
from ..words import plural
from .census_kernel import CensusPorts, Term, census_range
from .space import DesignSpace

SHARD_CHOICES = 1 << 24
"""Most residue vectors per shard (seconds of work on one core for a polyhedron)."""

MIN_SHARD_CHOICES = 1 << 18
"""Fewest residue vectors per shard: a census is cut into about :data:`TARGET_SHARDS` shards
between the two bounds, so that its progress moves every second or so."""

TARGET_SHARDS = 1000

CALL_PORT_VISITS = 1 << 24
"""Port visits per compiled call (about a tenth of a second): a shard is walked in calls
this short, so that Ctrl-C, which Python sees only between calls, stops it promptly."""

NS_PER_PORT_VECTOR = 3.36
"""CPU nanoseconds per port and residue vector, the median measured in ``results/census/plan.md``."""

MAX_CENSUS_VECTORS = 1 << 45
"""Most residue vectors a census takes on (3.5e13: about 2 million shards, thousands of core-hours).

Past it a census is refused before any work (its shard list alone would fill memory);
the exact total without the split by components (Burnside over the whole group) is instant.
"""

MAX_VALUE_KINDS = 3
"""Distinct label counts per residue class (besides 1) a census keeps apart exactly."""


@dataclass
class Census:
    """Exact census of a design space: designs by components (Python ints)."""

    by_components: dict[int, int]
    assignments_by_components: dict[int, int]
    group_order: int
    residue_vectors: int
    shards: int

    @property
    def designs(self) -> int:
        """All designs."""
        return sum(self.by_components.values())


def value_kinds(space: DesignSpace) -> np.ndarray:
    """Return the distinct label counts (> 1) of residue classes: the exponents a census keeps."""
    table = space.residue_table
    n_res, n_opts = table.n_res, table.n_opts
    vals = sorted({int(n_opts[e, i]) for e in range(len(n_res)) for i in range(int(n_res[e]))} - {1})
    if len(vals) > MAX_VALUE_KINDS:
        raise LabelError(f"a census keeps at most {MAX_VALUE_KINDS} distinct class sizes apart; {vals}")
    return np.array(vals, np.int64)


def terms(space: DesignSpace) -> list[Term]:
    """One :class:`Term` per distinct signed edge permutation of the group (identity first)."""
    table = space.residue_table
    n_res, values, n_opts, opts, lookup = table.n_res, table.values, table.n_opts, table.opts, table.lookup
    kinds = value_kinds(space).tolist()
    perms, signs = space.action
    zero_idx = lookup[:, 0]
    out = []
    for perm, s in zip(perms.tolist(), signs.tolist(), strict=True):
        seen = [False] * len(perm)
        ptr, edges, esigns, n_ch, ch_res, ch_val = [0], [], [], [], [], []
        for e in range(len(perm)):
            if seen[e]:
                continue
            x, sign = e, 1
            while not seen[x]:
                seen[x] = True
                edges.append(x)
                esigns.append(sign)
                x, sign = perm[x], sign * s
            even = sign == 1  # the product of signs around the cycle
            choices = []
            for i in range(int(n_res[e])):
                if even:
                    n = int(n_opts[e, i])
                    choices.append((int(values[e, i]), kinds.index(n) if n in kinds else -1))
                elif i == zero_idx[e] and np.any(opts[e, i, : n_opts[e, i]] == 0):
                    choices.append((0, -1))
            ptr.append(len(edges))
            n_ch.append(len(choices))
            ch_res.append([c[0] for c in choices])
            ch_val.append([c[1] for c in choices])
        width = max([len(c) for c in ch_res] + [1])
        res_arr = np.zeros((len(n_ch), width), np.int64)
        val_arr = np.full((len(n_ch), width), -1, np.int64)
        for v, (r, c) in enumerate(zip(ch_res, ch_val, strict=True)):
            res_arr[v, : len(r)], val_arr[v, : len(c)] = r, c
        out.append(
            Term(
                np.array(ptr, np.int64),
                np.array(edges, np.int64),
                np.array(esigns, np.int64),
                np.array(n_ch, np.int64),
                res_arr,
                val_arr,
            )
        )
    return out


def shard_term(shared: tuple[DesignSpace, list[Term]], item: tuple[int, int, int]) -> np.ndarray:
    """Task: the histogram ``(n_corners + 1, cells)`` of choices ``first..stop`` of term ``g``."""
    space, all_terms = shared
    g, first, stop = item
    t = all_terms[g]
    model = port_model(space.scaffold)
    n_vals = len(value_kinds(space))
    hist = np.zeros((space.scaffold.n_corners + 1, (len(t.n_choices) + 1) ** n_vals), np.int64)
    if 0 in t.n_choices.tolist():
        return hist
    step = max(1, CALL_PORT_VISITS // max(len(model.corner_partner), 1))
    ports = CensusPorts(model.corner_partner, model.port_a, model.port_b, model.edge_starts)
    for a in range(first, stop, step):
        census_range(a, min(stop, a + step), t, n_vals, space.moduli, ports, hist)
    return hist


def cell_weights(n_var: int, kinds: list[int]) -> list[int]:
    """Weight ``prod kinds[d] ** exps[d]`` of every histogram cell (exact ints)."""
    cells = (n_var + 1) ** len(kinds)
    out = []
    for cell in range(cells):
        w, rest = 1, cell
        for kind in kinds:
            w *= kind ** (rest % (n_var + 1))
            rest //= n_var + 1
        out.append(w)
    return out


@dataclass(frozen=True)
class CensusEstimate:
    """What a census of a space costs, known before any work.

    Attributes
    ----------
    vectors : int
        Residue vectors over every Burnside term.
    shards : int
        Tasks of about :data:`SHARD_CHOICES` vectors.
    cpu_seconds : float
        CPU time at :data:`NS_PER_PORT_VECTOR` per port and vector (one core; ``jobs`` split it).
    """

    vectors: int
    shards: int
    cpu_seconds: float

    def __str__(self) -> str:
        hours = self.cpu_seconds / 3600
        cost = f"{hours:.3g} CPU hours" if hours >= 1 else f"{self.cpu_seconds / 60:.2g} CPU minutes"
        parts = plural(self.shards, "part") if self.shards < 10**9 else f"{self.shards:.3g} parts"
        return f"a census of {self.vectors:.3g} residue vectors in {parts} (about {cost})"


def shard_size(vectors: int) -> int:
    """Residue vectors per shard of a census of ``vectors``: about :data:`TARGET_SHARDS` shards, within bounds."""
    return min(SHARD_CHOICES, max(MIN_SHARD_CHOICES, vectors // TARGET_SHARDS))


def census_estimate(space: DesignSpace, shard_choices: int | None = None) -> CensusEstimate:
    """Return the cost of :func:`census` on ``space``; raise :class:`TooLargeError` past :data:`MAX_CENSUS_VECTORS`.

    ``shard_choices``: vectors per shard (default :func:`shard_size`).
    """
    sizes = [t.size for t in terms(space)]
    vectors = sum(sizes)
    shard_choices = shard_choices or shard_size(vectors)
    ports = 2 * space.scaffold.n_corners
    estimate = CensusEstimate(
        vectors, sum(-(-n // shard_choices) for n in sizes), vectors * ports * NS_PER_PORT_VECTOR * 1e-9
    )
    if vectors > MAX_CENSUS_VECTORS:
        raise TooLargeError(
            f"{space.scaffold.name}: {estimate} is past what lkspace runs ({MAX_CENSUS_VECTORS:.3g} vectors); "
            "leave out `jobs`, `components` and `scheduler` for the exact total without the split by "
            "components (instant), or use a smaller label set or scaffold"
        )
    return estimate


def census(
    space: DesignSpace,
    scheduler: str = "local",
    jobs: int = 1,
    shard_choices: int | None = None,
    progress: Callable[[int, int], object] | None = None,
) -> Census:
    """Count the designs of ``space`` by components exactly, in shards (see the module docstring).

    ``progress(shards done, shards)`` is called as shards finish (and a ``census`` step
    of :mod:`lkspace.runtime.progress` advances).  Refused before any work past
    :data:`MAX_CENSUS_VECTORS` (:func:`census_estimate`).
    """
    estimate = census_estimate(space, shard_choices)
    shard_choices = shard_choices or shard_size(estimate.vectors)
    all_terms = terms(space)
    kinds = value_kinds(space).tolist()
    items = []
    for g, t in enumerate(all_terms):
        size = t.size
        items += [(g, a, min(size, a + shard_choices)) for a in range(0, size, shard_choices)]
    totals: list[dict[int, int]] = [{} for _ in all_terms]
    done = 0
    shards = run_tasks(shard_term, (space, all_terms), items, scheduler, jobs, name="lkspace-census")
    with task("census", total=len(items)) as step:
        for pos, hist in shards:
            g = items[pos][0]
            weights = cell_weights(len(all_terms[g].n_choices), kinds)
            for comp, cell in zip(*np.nonzero(hist), strict=True):
                totals[g][int(comp)] = totals[g].get(int(comp), 0) + int(hist[comp, cell]) * weights[cell]
            done += 1
            step.advance()
            if progress is not None:
                progress(done, len(items))
    by: dict[int, int] = {}
    for part in totals:
        for comp, n in part.items():
            by[comp] = by.get(comp, 0) + n
    n_g = space.n_actions
    for n in by.values():
        if n % n_g:
            raise ArithmeticError(f"census of {space.scaffold.name}: {n} is not divisible by {n_g}")  # a bug if so
    result = {c: n // n_g for c, n in sorted(by.items()) if n}
    return Census(result, dict(sorted(totals[0].items())), space.group_order, space.n_classes, len(items))
