"""Walking the symmetric designs of an :class:`~lkspace.design.invariant.InvariantSpace`.

The fixed assignments are a product over ``H``'s edge orbits; a compiled kernel walks it
in mixed radix (last orbit fastest), expands each to edge labels and keeps it when it is
the smallest of its ``N``-orbit in (``t mod K`` per edge, then ``t`` per edge), counting its
stabilizer in ``N`` on the way (the helpers of :mod:`lkspace.compiled.loops`).  Kept rows are grouped by residue vector, each residue
class traced once (:func:`~lkspace.design.batch.trace_batch`), and returned as
:class:`~lkspace.design.walk.DesignBlock` s, the rows the catalog writer takes.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import NamedTuple

import numpy as np

from ..compiled.kernels import kernel
from ..compiled.loops import next_digits, set_digits, stabilizer_if_smallest
from ..errors import TooLargeError
from .batch import holds_batch, trace_batch
from .batch_kernels import Actions, Rows
from .invariant import InvariantSpace
from .walk import DesignBlock

CHUNK = 1 << 18
"""Fixed assignments per kernel call."""

MAX_FIXED = 1 << 28
"""Largest number of fixed assignments listed (counting by Burnside has no bound)."""


class FixedAssignments(NamedTuple):
    """The assignments fixed by ``H`` as :func:`invariant_canonical` walks them.

    ``opts (n_orbits, max_o)``, ``n_opts (n_orbits,)``: representative labels per orbit;
    ``edge_orbit``, ``edge_rel (n_edges,)``: edge label = ``edge_rel * u[edge_orbit]``;
    ``moduli (n_edges,)``: ``K`` per edge.
    """

    opts: np.ndarray
    n_opts: np.ndarray
    edge_orbit: np.ndarray
    edge_rel: np.ndarray
    moduli: np.ndarray


@kernel
def invariant_canonical(fixed: FixedAssignments, actions: Actions, start: int, stop: int, out: Rows) -> int:
    """Keep the fixed assignments ``start..stop`` that are canonical under ``N``; return how many.

    ``actions``: those of ``N``, identity first.  Kept rows go to ``out``.
    """
    opts, n_opts, edge_orbit, edge_rel, moduli = (
        fixed.opts,
        fixed.n_opts,
        fixed.edge_orbit,
        fixed.edge_rel,
        fixed.moduli,
    )
    inv_perms, signs, out_labels, out_stab = actions.inv_perms, actions.signs, out.labels, out.stab
    n_e = len(edge_orbit)
    n_a = len(signs)
    digits = np.zeros(len(n_opts), np.int64)
    set_digits(digits, n_opts, start)
    x = np.empty(n_e, np.int64)
    res = np.empty(n_e, np.int64)
    ids = np.arange(n_a)
    m = 0
    for _ in range(start, stop):
        for j in range(n_e):
            x[j] = edge_rel[j] * opts[edge_orbit[j], digits[edge_orbit[j]]]
            res[j] = x[j] % moduli[j]
        stab = stabilizer_if_smallest(x, res, moduli, inv_perms, signs, ids, 1, n_a)
        if stab:
            for j in range(n_e):
                out_labels[m, j] = x[j]
            out_stab[m] = stab
            m += 1
        next_digits(digits, n_opts)
    return m


def invariant_blocks(space: InvariantSpace, components: int | None = None) -> Iterator[DesignBlock]:
    """Yield the symmetric designs of ``space`` (rows canonical under ``N``), a chunk at a time.

    Raises
    ------
    TooLargeError
        More than :data:`MAX_FIXED` fixed assignments to walk.
    """
    n_fixed = space.n_fixed
    if n_fixed > MAX_FIXED:
        raise TooLargeError(
            f"{space.scaffold.name}: {n_fixed:,} assignments fixed by {space.subgroup} are too many to list "
            f"(limit {MAX_FIXED:,}); pick a larger subgroup"
        )
    if n_fixed == 0:
        return
    orbit, rel = space.orbits.orbit, space.orbits.rel
    n_opts = np.array([len(o) for o in space.options], np.int64)
    opts = np.zeros((len(n_opts), int(n_opts.max())), np.int64)
    for i, o in enumerate(space.options):
        opts[i, : len(o)] = o
    perms, signs = space.action
    actions = Actions(inv_perms=np.ascontiguousarray(np.argsort(perms, axis=1)), signs=signs)
    fixed = FixedAssignments(opts, n_opts, orbit, rel, space.base.moduli)
    n_e = space.scaffold.n_edges
    for start in range(0, n_fixed, CHUNK):
        stop = min(n_fixed, start + CHUNK)
        out = np.empty((stop - start, n_e), np.int8)
        stab = np.empty(stop - start, np.int64)
        work = (stop - start) * max(1, len(signs)) * n_e
        m = invariant_canonical.run(work, fixed, actions, start, stop, Rows(out, stab))
        if m:
            block = rows_block(space, out[:m], len(signs) // stab[:m], components)
            if block is not None:
                yield block


def rows_block(
    space: InvariantSpace, labels: np.ndarray, orbit_sizes: np.ndarray, components: int | None
) -> DesignBlock | None:
    """Return a :class:`DesignBlock` of the rows ``labels (m, n_edges)``: their residue classes traced once each."""
    base = space.base
    residues = labels.astype(np.int64) % base.moduli
    classes, row_class = np.unique(residues, axis=0, return_inverse=True)
    row_class = row_class.reshape(-1).astype(np.int64)
    traces = trace_batch(base, classes)
    if components is not None:
        keep = traces.components[row_class] == components
        if not keep.any():
            return None
        labels, orbit_sizes, row_class = labels[keep], orbit_sizes[keep], row_class[keep]
    holds = holds_batch(base, traces, labels, row_class)
    codes = np.array([_class_code(space, r) for r in classes], np.int64)
    return DesignBlock(codes, traces.slim(), row_class, labels, orbit_sizes.astype(np.int64), holds)


def _class_code(space: InvariantSpace, residues: np.ndarray) -> int:
    """Return the ``residue_class`` code of a residue vector (-1 past 64 bits)."""
    lookup = space.base.residue_table.lookup
    code = space.base.class_code(lookup[np.arange(len(residues)), residues])
    return code if code < 2**63 else -1
