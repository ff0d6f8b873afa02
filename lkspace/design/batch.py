"""Many residue classes per compiled call: traces, canonical rows, holding together, counts.

The walk of :mod:`lkspace.design.walk` goes class by class.  Where classes are large (the
cube with labels ``-2..2``: 60,000 assignments per class) one call per class is cheap;
where they are tiny (``honeycomb:oF`` with ``-1..1``: one assignment each) per-class Python
calls cost 1000x the work.  So classes go through the kernels of
:mod:`lkspace.design.batch_kernels` in batches of about :data:`BATCH_ASSIGNMENTS`
assignments (and at most :data:`BATCH_PORTS` ports x classes of trace arrays), one class
alone (in chunks) when it is larger than that.  Results are the same as class by class:
the same strand walk, the same canonical test, the same Burnside count.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass

import numpy as np

from ..strands.ports import port_model
from .batch_kernels import (
    Actions,
    ClassOptions,
    LiftInputs,
    Rows,
    TraceArrays,
    WalkPorts,
    expand_classes,
    rows_hold_together_finite,
    rows_hold_together_lift,
    trace_classes,
)
from .orbit_kernels import burnside_classes
from .space import DesignSpace

BATCH_ASSIGNMENTS = 1 << 13
"""Assignments per batch of small classes (a larger class is walked alone, in chunks)."""

BATCH_PORTS = 1 << 16
"""Largest ``classes x ports`` of one batch's trace arrays (bounds memory on big scaffolds)."""

INT64_SAFE = 1 << 62


@dataclass(frozen=True, eq=False)
class ClassTraces:
    """Strands of a batch of residue classes (label-independent facts).

    Attributes
    ----------
    components : (n_c,) int64
    lengths : (n_c, n_s) int64
        Corner links per strand, descending (stable in walk order), -1 padded.
    periods : (n_c, n_s, dim) int64
        Periods in the same order as ``lengths``.
    walk_periods, port_strand, port_shift
        Periods in walk order and, per port, strand and lattice shift (for holding together).
    """

    components: np.ndarray
    lengths: np.ndarray
    periods: np.ndarray
    walk_periods: np.ndarray
    port_strand: np.ndarray
    port_shift: np.ndarray

    def select(self, keep: np.ndarray) -> ClassTraces:
        """Return the traces of the classes ``keep`` (indices or a mask)."""
        return ClassTraces(*(a[keep] for a in self._arrays()))

    def slim(self) -> ClassTraces:
        """Return the traces catalog rows need: without the arrays only holding together reads (left empty)."""
        return ClassTraces(self.components, self.lengths, self.periods, *_no_walk_arrays())

    def _arrays(self) -> tuple[np.ndarray, ...]:
        return self.components, self.lengths, self.periods, self.walk_periods, self.port_strand, self.port_shift


def walk_ports(space: DesignSpace) -> WalkPorts:
    """Port-model arrays of the scaffold for :func:`trace_classes`."""
    sc = space.scaffold
    model = port_model(sc)
    translation = sc.side_translation if sc.periodic else np.zeros((sc.n_corners, 0), np.int64)
    return WalkPorts(
        corner_partner=model.corner_partner,
        port_a=model.port_a,
        port_b=model.port_b,
        edge_starts=model.edge_starts,
        slot_edge=model.slot_edge,
        slot_index=model.slot_index,
        degrees=np.asarray(sc.edge_degrees, np.int64),
        translation=np.ascontiguousarray(translation, np.int64),
    )


def edge_ports(space: DesignSpace) -> tuple[np.ndarray, np.ndarray]:
    """Return the ports of each edge, its leader first: ``(ptr (n_edges + 1,), ports)`` (CSR)."""
    sc = space.scaffold
    model = port_model(sc)
    edge_of_port = np.repeat(sc.side_edge, 2)
    leader = model.port_a[model.edge_starts[:-1]]
    ports = np.arange(2 * sc.n_corners)
    is_leader = ports == leader[edge_of_port]
    order = np.lexsort((~is_leader, edge_of_port))  # by edge; each edge's leader first
    ptr = np.searchsorted(edge_of_port[order], np.arange(sc.n_edges + 1))
    return ptr.astype(np.int64), order.astype(np.int64)


def trace_batch(space: DesignSpace, residues: np.ndarray) -> ClassTraces:
    """Trace every class of ``residues (n_c, n_edges)`` (one compiled call)."""
    ports = walk_ports(space)
    n_c = len(residues)
    n_ports = len(ports.corner_partner)
    dim = ports.translation.shape[1]
    out = TraceArrays(
        components=np.empty(n_c, np.int64),
        lengths=np.empty((n_c, n_ports // 2), np.int64),
        periods=np.zeros((n_c, n_ports // 2, dim), np.int64),
        port_strand=np.empty((n_c, n_ports), np.int64),
        port_shift=np.zeros((n_c, n_ports, dim), np.int64),
    )
    trace_classes(np.ascontiguousarray(residues, np.int64), ports, out)
    comp = out.components
    n_s = int(comp.max()) if n_c else 0
    lengths, walk_periods = out.lengths[:, :n_s], out.periods[:, :n_s]
    order = np.argsort(-lengths, axis=1, kind="stable")  # padding (-1) sorts last
    sorted_lengths = np.take_along_axis(lengths, order, axis=1)
    sorted_periods = np.take_along_axis(walk_periods, order[:, :, None], axis=1)
    return ClassTraces(comp, sorted_lengths, sorted_periods, walk_periods, out.port_strand, out.port_shift)


def holds_batch(space: DesignSpace, traces: ClassTraces, labels: np.ndarray, row_class: np.ndarray) -> np.ndarray:
    """(m,) bool: whether each row ``labels[i]`` (of class ``row_class[i]`` of ``traces``) holds together.

    Finite scaffolds: union-find over each class's distinct strands per edge.  Periodic
    ones: over every port, with lattice potentials, and the index of the lift.
    """
    if not space.scaffold.periodic:
        ptr, strands = edge_strands(space, traces.port_strand)
        return rows_hold_together_finite(
            np.ascontiguousarray(labels, np.int8),
            np.ascontiguousarray(row_class, np.int64),
            traces.components,
            ptr,
            strands,
        )
    port_ptr, ports = edge_ports(space)
    lift = LiftInputs(
        components=traces.components,
        periods=np.ascontiguousarray(traces.walk_periods),
        port_strand=traces.port_strand,
        port_shift=np.ascontiguousarray(traces.port_shift),
        edge_port_ptr=port_ptr,
        edge_ports=ports,
        tau=walk_ports(space).translation,
    )
    return rows_hold_together_lift(
        np.ascontiguousarray(labels, np.int8), np.ascontiguousarray(row_class, np.int64), lift
    )


def edge_strands(space: DesignSpace, port_strand: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return the distinct strands through each edge of each class, CSR over ``class * n_edges + edge``."""
    sc = space.scaffold
    n_c, n_ports = port_strand.shape
    n_max = n_ports // 2 + 1
    edge_of_port = np.repeat(sc.side_edge, 2).astype(np.int64)
    keys = (np.arange(n_c, dtype=np.int64)[:, None] * sc.n_edges + edge_of_port[None, :]) * n_max + port_strand
    keys = np.unique(keys)
    ptr = np.searchsorted(keys // n_max, np.arange(n_c * sc.n_edges + 1))
    return ptr.astype(np.int64), (keys % n_max).astype(np.int64)


def class_sizes(space: DesignSpace, indices: np.ndarray) -> np.ndarray:
    """(n_c,) float64: assignments per class (float: only for batching decisions)."""
    n_opts = space.residue_table.n_opts
    e = np.arange(indices.shape[1])
    return np.prod(n_opts[e[None, :], indices].astype(np.float64), axis=1)


def stabilizer_csr(space: DesignSpace, class_ids: np.ndarray, identity: bool) -> tuple[np.ndarray, np.ndarray]:
    """``(ptr, ids)``: the stabilizers of the representative classes ``class_ids`` (CSR)."""
    co = space.classes
    starts, stops = co.stab_ptr[class_ids] + (0 if identity else 1), co.stab_ptr[class_ids + 1]
    counts = stops - starts
    ptr = np.zeros(len(class_ids) + 1, np.int64)
    np.cumsum(counts, out=ptr[1:])
    ids = co.stab_ids[np.repeat(starts - ptr[:-1], counts) + np.arange(ptr[-1])]
    return ptr, np.ascontiguousarray(ids, np.int64)


def expand_batch(space: DesignSpace, class_ids: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Canonical rows of the (small) representative classes ``class_ids``: labels, stabilizer sizes, batch class."""
    co = space.classes
    table = space.residue_table
    n_opts, opts = table.n_opts, table.opts
    perms, signs = space.action
    inv = np.ascontiguousarray(np.argsort(perms, axis=1))
    indices = np.ascontiguousarray(co.indices[class_ids])
    total = int(class_sizes(space, indices).sum())
    out = np.empty((total, space.scaffold.n_edges), np.int8)
    stab, cls = np.empty(total, np.int64), np.empty(total, np.int64)
    ptr, ids = stabilizer_csr(space, class_ids, identity=False)
    actions = Actions(inv_perms=inv, signs=np.ascontiguousarray(signs))
    m = expand_classes(indices, ClassOptions(opts=opts, n_opts=n_opts), actions, ptr, ids, Rows(out, stab), cls)
    return out[:m], stab[:m], cls[:m]


def batches_of(space: DesignSpace, class_ids: Sequence[int] | np.ndarray) -> Iterator[np.ndarray]:
    """Cut ``class_ids`` (in order) into runs: small classes together, a large class alone."""
    ids = np.asarray(class_ids, np.int64)
    if len(ids) == 0:
        return
    sizes = class_sizes(space, space.classes.indices[ids])
    max_classes = max(1, BATCH_PORTS // (2 * space.scaffold.n_corners))
    start = 0
    while start < len(ids):
        if sizes[start] >= BATCH_ASSIGNMENTS:
            yield ids[start : start + 1]
            start += 1
            continue
        cum = np.cumsum(sizes[start : start + max_classes])
        stop = start + int(np.searchsorted(cum, BATCH_ASSIGNMENTS, side="right"))
        stop = min(max(stop, start + 1), len(ids))
        while stop > start + 1 and sizes[stop - 1] >= BATCH_ASSIGNMENTS:
            stop -= 1
        yield ids[start:stop]
        start = stop


def counts_fit_int64(space: DesignSpace) -> bool:
    """Whether every class's Burnside sum fits in int64 (else counts are exact Python ints)."""
    n_opts = space.residue_table.n_opts
    bound = math.prod(int(x) for x in n_opts.max(axis=1)) * space.n_actions
    return bound < INT64_SAFE


def cycle_csr(space: DesignSpace) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Cycles of every group action as CSR: ``(ptr (n_g + 1,), heads, even)``."""
    cycles = space.cycles
    ptr = np.zeros(len(cycles) + 1, np.int64)
    np.cumsum([len(h) for h, _ in cycles], out=ptr[1:])
    heads = np.concatenate([h for h, _ in cycles]).astype(np.int64)
    even = np.concatenate([ev for _, ev in cycles]).astype(np.bool_)
    return ptr, heads, even


def has_zero_table(space: DesignSpace) -> np.ndarray:
    """(n_edges, max_r) bool: whether label 0 is among a residue's options on an edge."""
    table = space.residue_table
    n_opts, opts = table.n_opts, table.opts
    return np.any((opts == 0) & (np.arange(opts.shape[2]) < n_opts[:, :, None]), axis=2)


def design_counts(space: DesignSpace, class_ids: np.ndarray) -> np.ndarray:
    """Designs per representative class ``class_ids`` (int64, or object of exact ints if large)."""
    if not counts_fit_int64(space):
        return np.array([space.class_design_count(int(c)) for c in class_ids], dtype=object)
    ptr, ids = stabilizer_csr(space, class_ids, identity=True)
    c_ptr, c_head, c_even = cycle_csr(space)
    indices = np.ascontiguousarray(space.classes.indices[class_ids])
    n_opts = space.residue_table.n_opts
    return burnside_classes(indices, n_opts, has_zero_table(space), ptr, ids, c_ptr, c_head, c_even)


def class_components(space: DesignSpace, class_ids: np.ndarray | None = None) -> np.ndarray:
    """(n,) int64: components of the representative classes ``class_ids`` (default all), batched."""
    co = space.classes
    ids = np.arange(len(co.codes)) if class_ids is None else np.asarray(class_ids, np.int64)
    out = np.empty(len(ids), np.int64)
    step = max(1, BATCH_PORTS // (2 * space.scaffold.n_corners))
    for s in range(0, len(ids), step):
        out[s : s + step] = trace_batch(space, co.residues[ids[s : s + step]]).components
    return out


def concat_traces(parts: list[ClassTraces]) -> ClassTraces:
    """One :class:`ClassTraces` of several batches, for their rows' columns.

    Strand arrays are padded to the widest (each part copied once, into place); the arrays
    only holding together reads are left empty (:meth:`ClassTraces.slim`).
    """
    n_s = max(p.lengths.shape[1] for p in parts)
    components = np.concatenate([p.components for p in parts])
    lengths = np.full((len(components), n_s), -1, np.int64)
    periods = np.zeros((len(components), n_s, parts[0].periods.shape[2]), np.int64)
    start = 0
    for p in parts:
        stop, width = start + len(p.components), p.lengths.shape[1]
        lengths[start:stop, :width] = p.lengths
        periods[start:stop, :width] = p.periods
        start = stop
    return ClassTraces(components, lengths, periods, *_no_walk_arrays())


def _no_walk_arrays() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Empty ``walk_periods``, ``port_strand`` and ``port_shift`` (traces that no longer hold together rows)."""
    return np.zeros((0, 0, 0), np.int64), np.zeros((0, 0), np.int64), np.zeros((0, 0, 0), np.int64)


def representative_table(space: DesignSpace) -> np.ndarray:
    """(n_edges, max_r) int8: per edge and residue, the option with the smallest ``|t|`` (ties: positive)."""
    table = space.residue_table
    n_res, n_opts, opts = table.n_res, table.n_opts, table.opts
    out = np.zeros(n_opts.shape, np.int8)
    for e in range(len(n_res)):
        for i in range(int(n_res[e])):
            o = opts[e, i, : n_opts[e, i]]
            out[e, i] = o[np.lexsort((-o, np.abs(o)))[0]]
    return out
