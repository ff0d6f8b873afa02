"""The compiled loop of a census (:mod:`lkspace.design.census`): components of many residue vectors.

One kernel call walks a contiguous range of **choices**: residue vectors built from a few
free variables (the cycles of one group action; for the identity, every edge), traces
each one's strands (components only) and counts it in a histogram cell keyed by its
component number and by how many of its variables carry each label count.  Consecutive
choices differ mostly in the last variable, so only the edge links of the variables that
changed are rebuilt.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from ..compiled.kernels import kernel
from ..compiled.loops import next_digits, set_digits


class Term(NamedTuple):
    """The residue vectors fixed by one group action: variables (cycles) and their choices.

    A NamedTuple: :func:`~lkspace.design.census_kernel.census_range` takes it as it is
    (see there for the arrays).
    """

    var_ptr: np.ndarray
    var_edges: np.ndarray
    var_signs: np.ndarray
    n_choices: np.ndarray
    choice_res: np.ndarray
    choice_val: np.ndarray

    @property
    def size(self) -> int:
        """Number of residue vectors (exact)."""
        return math.prod(int(x) for x in self.n_choices)


class CensusPorts(NamedTuple):
    """The arrays of :class:`~lkspace.strands.ports.PortModel` the census walk reads."""

    corner_partner: np.ndarray
    port_a: np.ndarray
    port_b: np.ndarray
    edge_starts: np.ndarray


@kernel
def census_range(
    first: int, stop: int, term: Term, n_vals: int, moduli: np.ndarray, ports: CensusPorts, hist: np.ndarray
) -> None:
    """Add choices ``first..stop`` (mixed radix, variable 0 most significant) to ``hist``.

    Variable ``v`` sets the residue of each of its edges ``var_edges[var_ptr[v]:var_ptr[v+1]]``
    to ``var_signs[...] * choice_res[v, choice] mod K``; ``choice_val[v, choice]`` is the
    index of its label count among the ``n_vals`` counted ones (-1: a factor 1, not
    counted).  ``hist[components, cell]`` counts choices; the cell is the mixed-radix
    number (base ``n_var + 1``) of how many variables have each counted value.  The
    variables are the arrays of ``term`` (:class:`~lkspace.design.census.Term`).
    """
    var_ptr, var_edges, var_signs = term.var_ptr, term.var_edges, term.var_signs
    n_choices, choice_res, choice_val = term.n_choices, term.choice_res, term.choice_val
    corner_partner, port_a, port_b, edge_starts = ports.corner_partner, ports.port_a, ports.port_b, ports.edge_starts
    n_var = len(n_choices)
    n_ports = len(corner_partner)
    partner = np.empty(n_ports, np.int64)
    visited = np.zeros(n_ports, np.bool_)
    digits = np.zeros(n_var, np.int64)
    exps = np.zeros(max(n_vals, 1), np.int64)
    set_digits(digits, n_choices, first)
    changed = 0  # variables 0..n_var-1 from `changed` on need their edge links rebuilt
    for _ in range(stop - first):
        for v in range(changed, n_var):
            r = choice_res[v, digits[v]]
            for p in range(var_ptr[v], var_ptr[v + 1]):
                e = var_edges[p]
                k = moduli[e]
                res = (var_signs[p] * r) % k
                for q in range(edge_starts[e], edge_starts[e + 1]):
                    target = edge_starts[e] + (q - edge_starts[e] + res) % k
                    partner[port_a[q]] = port_b[target]
                    partner[port_b[target]] = port_a[q]
        cell = 0
        for d in range(n_vals):
            exps[d] = 0
        for v in range(n_var):
            c = choice_val[v, digits[v]]
            if c >= 0:
                exps[c] += 1
        for d in range(n_vals - 1, -1, -1):
            cell = cell * (n_var + 1) + exps[d]
        visited[:] = False
        comps = 0
        for x0 in range(n_ports):
            if visited[x0]:
                continue
            x = x0
            # lkspace.strands.walk.walk_strand written out: its records (steps, port_strand), unread here,
            # cost this kernel 7-16% in choices per second (measured, interleaved)
            while True:
                y = corner_partner[x]
                visited[x] = True
                visited[y] = True
                z = partner[y]
                if z == x0:
                    break
                x = z
            comps += 1
        hist[comps, cell] += 1
        changed = max(next_digits(digits, n_choices), 0)
