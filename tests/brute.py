"""Exhaustive enumeration of small design spaces (tests only): the oracle for ``solve``.

Every assignment of allowed labels is traced with :func:`lkspace.trace`.  On an edge of
degree 1 every label gives the same strands ((i + t) mod 1 = 0), so such edges take only
their first allowed label; everything else is enumerated label by label.
"""

from __future__ import annotations

import itertools
from collections import Counter

import numpy as np

from lkspace import trace


def allowed_per_edge(scaffold, labels, no_zero=False, fixes=None, parities=None) -> list[list[int]]:
    """The labels each edge may take, filtered exactly as the query says."""
    out = []
    for e in range(scaffold.n_edges):
        opts = [int(t) for t in labels if not (no_zero and t == 0)]
        if fixes and e in fixes:
            opts = [fixes[e]]
        if parities and e in parities:
            opts = [t for t in opts if t % 2 == parities[e]]
        out.append(opts)
    return out


def designs(scaffold, allowed: list[list[int]]):
    """Yield ``(labels, components)`` for every assignment (degree-1 edges: first label only)."""
    degrees = scaffold.edge_degrees
    choices = [opts[:1] if degrees[e] == 1 else opts for e, opts in enumerate(allowed)]
    for combo in itertools.product(*choices):
        labels = np.array(combo, np.int64)
        yield labels, trace(scaffold, labels).components


def component_census(scaffold, allowed) -> Counter:
    """Number of assignments with each component count."""
    return Counter(n for _, n in designs(scaffold, allowed))


def residue_classes(scaffold, allowed, components: int) -> set[tuple[int, ...]]:
    """Distinct residue vectors (``t mod K`` per edge) of the designs with ``components``."""
    degrees = scaffold.edge_degrees
    return {tuple((labels % degrees).tolist()) for labels, n in designs(scaffold, allowed) if n == components}
