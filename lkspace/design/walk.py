"""The design-space walk: one row per design up to symmetry.

A **design** is an orbit of label assignments ``t in SET^edges`` under the symmetry group
``G`` of the mode (:mod:`lkspace.symmetry.group`; a reflection maps ``t`` on ``e`` to ``-t`` on its
image).  The strands depend only on the **residue class** ``t mod K`` per edge (``K`` the
edge's degree), so the walk goes class by class:

1. List the residue classes (product over edges of the residues the label set reaches)
   and let ``G`` act on them.  A class is a **representative class** when its residue
   vector, written as indices into each edge's sorted residues, is the lexicographically
   smallest of its ``G``-orbit; its **stabilizer** ``H`` is the set of group elements
   fixing it.
2. Trace each representative class once (the compiled walk of :mod:`lkspace.strands.walk` on the
   residues, no ``Trace`` objects): components, strand lengths, periods.
3. Expand the class's label assignments (a product set, walked in lexicographic order by
   a numba kernel) and keep those that are the lexicographically smallest under ``H``.

**Canonical representative.**  Of all assignments in an orbit, the row holds the one
that is smallest in the order "residue vector ``t mod K`` in edge order first, then the
labels ``t`` in edge order", both lexicographic.  Because ``G`` maps residue classes to
residue classes, that minimum lies in the orbit's representative class and is the
``H``-smallest there, so testing it needs only ``H`` (usually trivial), never the whole
group.  ``orbit_size = |G| / |Stab(t)|`` with ``Stab(t) = {h in H : h t = t}``, counted
in the same kernel.  ``|G|`` is the number of distinct signed edge permutations
(:meth:`~lkspace.symmetry.group.SymmetryGroup.action`).

Null edge-sides stored with a scaffold are not part of a design space: the walk traces
every strand closed.

Counting without listing is :mod:`lkspace.design.counting`.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from typing import NotRequired, TypedDict

import numpy as np

from ..strands.tracing import trace
from .batch import BATCH_ASSIGNMENTS, ClassTraces, batches_of, expand_batch, holds_batch, trace_batch
from .batch_kernels import Actions, ClassOptions, Rows, expand_class_range, rows_hold_together_finite
from .space import ClassInfo, DesignSpace

CHUNK = 1 << 20


class ResidueRow(TypedDict):
    """One ``--mode residues`` row (a residue-class orbit), the columns of the residues schema (:mod:`lkspace.catalog.schema`)."""

    residues: list[int]
    labels: list[int]
    components: int
    orbit_size: int
    designs: int
    classes: int
    holds_together: bool
    n_zero: int
    n_odd: int
    residue_class: int
    strand_lengths: list[int]
    n_infinite: NotRequired[int]
    strand_periods: NotRequired[list[list[int]]]


def holds_together_rows(space: DesignSpace, residues: np.ndarray, info: ClassInfo, labels: np.ndarray) -> np.ndarray:
    """(m,) bool: whether each design of one residue class holds together.

    Finite scaffolds: a compiled union-find over the class's strands.  Periodic ones need
    the infinite lift (:mod:`lkspace.strands.holding_together`), which depends only on the residues
    and on which labels are zero: traced once per distinct zero pattern.
    """
    if not space.scaffold.periodic:
        one_class = np.zeros(len(labels), np.int64)
        return rows_hold_together_finite(
            np.ascontiguousarray(labels, np.int8),
            one_class,
            np.array([info.components]),
            info.edge_ptr,
            info.edge_strands,
        )
    nonzero = labels != 0
    if len(labels) == 1:
        patterns, inverse = nonzero, np.zeros(1, np.int64)
    else:
        patterns, inverse = np.unique(nonzero, axis=0, return_inverse=True)
    moduli = space.moduli
    verdicts = np.empty(len(patterns), bool)
    for i, pattern in enumerate(patterns):
        # same residues, same zero pattern: a residue of 0 on a nonzero edge becomes K
        stand_in = np.where(pattern & (residues == 0), moduli, residues)
        verdicts[i] = trace(space.scaffold, stand_in).holds_together
    return verdicts[inverse.reshape(-1)]


@dataclass
class DesignBlock:
    """Designs of a run of representative classes (or a chunk of one large class).

    Attributes
    ----------
    class_codes : (n_c,) int64
        ``residue_class`` code of each class of the run.
    traces : ClassTraces
        Per class: components, strand lengths and periods.
    row_class : (m,) int64
        Class (index into ``class_codes``) of each row.
    labels : (m, n_edges) int8
    orbit_sizes : (m,) int64
    holds_together : (m,) bool
    """

    class_codes: np.ndarray
    traces: ClassTraces
    row_class: np.ndarray
    labels: np.ndarray
    orbit_sizes: np.ndarray
    holds_together: np.ndarray

    def head(self, n: int) -> DesignBlock:
        """Return the first ``n`` rows."""
        return DesignBlock(
            self.class_codes,
            self.traces,
            self.row_class[:n],
            self.labels[:n],
            self.orbit_sizes[:n],
            self.holds_together[:n],
        )


def walk_blocks(
    space: DesignSpace, class_ids: Iterable[int] | None = None, components: int | None = None
) -> Iterator[DesignBlock]:
    """Yield the designs of the representative classes ``class_ids`` (default all), in order.

    Small classes go many to a compiled call (:mod:`lkspace.design.batch`); a class larger
    than :data:`~lkspace.design.batch.BATCH_ASSIGNMENTS` assignments alone, in chunks of
    :data:`CHUNK`.
    """
    co = space.classes
    ids = np.arange(len(co.codes)) if class_ids is None else np.fromiter(class_ids, np.int64)
    for run in batches_of(space, ids):
        traces = trace_batch(space, co.residues[run])
        if components is not None:
            keep = traces.components == components
            run, traces = run[keep], traces.select(keep)
            if len(run) == 0:
                continue
        if len(run) == 1 and space.size_of(co.indices[run[0]]) >= BATCH_ASSIGNMENTS:
            yield from _large_class(space, int(run[0]), traces)
            continue
        labels, stab, row_class = expand_batch(space, run)
        holds = holds_batch(space, traces, labels, row_class)
        yield DesignBlock(co.codes[run], traces.slim(), row_class, labels, space.n_actions // stab, holds)


def _large_class(space: DesignSpace, c: int, traces: ClassTraces) -> Iterator[DesignBlock]:
    co = space.classes
    perms, signs = space.action
    inv = np.ascontiguousarray(np.argsort(perms, axis=1))
    signs = np.ascontiguousarray(signs)
    options = ClassOptions(opts=space.residue_table.opts, n_opts=space.residue_table.n_opts)
    actions = Actions(inv_perms=inv, signs=signs)
    e = np.arange(space.scaffold.n_edges)
    index = np.ascontiguousarray(co.indices[c])
    n_opts = options.n_opts[e, index]
    h = np.ascontiguousarray(co.stabilizers[c][1:], np.int64)
    size = math.prod(n_opts.tolist())
    for start in range(0, size, CHUNK):
        stop = min(size, start + CHUNK)
        out = np.empty((stop - start, len(e)), np.int8)
        stab = np.empty(stop - start, np.int64)
        m = expand_class_range(index, options, actions, h, start, stop, Rows(out, stab))
        labels = out[:m]
        row_class = np.zeros(m, np.int64)
        holds = holds_batch(space, traces, labels, row_class)
        yield DesignBlock(co.codes[[c]], traces.slim(), row_class, labels, space.n_actions // stab[:m], holds)


def residue_row(
    space: DesignSpace, indices: np.ndarray, stabilizer: np.ndarray, info: ClassInfo | None = None
) -> ResidueRow:
    """Return the ``--mode residues`` row of the class orbit of ``indices`` (a representative)."""
    e = np.arange(len(indices))
    residues = space.residue_table.values[e, indices]
    info = info or space.class_info(residues)
    labels = space.representative_labels(indices)
    holds = bool(holds_together_rows(space, residues, info, labels[None, :])[0])
    n_classes = space.n_actions // len(stabilizer)
    big = 2**63 - 1  # counts past int64 are stored as -1 (possible only for huge spaces)
    assignments = space.size_of(indices) * n_classes
    designs = space.design_count(indices, stabilizer)
    row: ResidueRow = {
        "residues": residues.astype(np.int8).tolist(),
        "labels": labels.tolist(),
        "components": info.components,
        "orbit_size": assignments if assignments <= big else -1,
        "designs": designs if designs <= big else -1,
        "classes": n_classes,
        "holds_together": holds,
        "n_zero": int(np.sum(labels == 0)),
        "n_odd": int(np.sum(residues % 2 != 0)),
        "residue_class": space.class_code(indices),
        "strand_lengths": info.strand_lengths.tolist(),
    }
    if space.scaffold.periodic:
        row["n_infinite"] = int(np.sum(np.any(info.periods != 0, axis=1)))
        row["strand_periods"] = info.periods.tolist()
    return row
