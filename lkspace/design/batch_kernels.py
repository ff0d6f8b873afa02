"""Compiled kernels that treat many residue classes in one call (see :mod:`lkspace.design.batch`).

A scaffold whose residue classes are tiny (``honeycomb:oF`` with labels ``-1..1``: one
assignment per class) spends its time in per-class Python calls unless many classes go
through one compiled call.  These kernels take a batch of classes as arrays:

* :func:`trace_classes`: the strand walk of :mod:`lkspace.strands.walk` for each class's
  residues (its helper :func:`~lkspace.strands.walk.walk_strand`, so strands come in the same order);
* :func:`expand_classes`: the canonical assignments of each class, and
  :func:`expand_class_range`: those of a part of one large class (both through the
  helpers :func:`class_options` and :func:`canonical_rows`);
* :func:`rows_hold_together_lift`: whether each row holds together, finite or periodic (the
  infinite lift of :mod:`lkspace.strands.holding_together`: union-find with lattice
  potentials, then the index of the realizable translations), and
  :func:`rows_hold_together_finite`, the same for finite scaffolds over fewer links;

The orbit kernels (representatives, stabilizers, Burnside counts) are in
:mod:`lkspace.design.orbit_kernels`.

The loops they share with other kernels (mixed-radix counting, the canonical test,
union-find, the lattice index) are the helpers of :mod:`lkspace.compiled.loops`.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..compiled.kernels import helper, kernel
from ..compiled.loops import find, lattice_index_rows, set_digits, stabilizer_if_smallest
from ..strands.walk import walk_strand


class WalkPorts(NamedTuple):
    """The port model of a scaffold as the strand walk of :func:`trace_classes` reads it.

    The arrays of :class:`~lkspace.strands.ports.PortModel` (``corner_partner``,
    ``port_a``, ``port_b``, ``edge_starts``, ``slot_edge``, ``slot_index``), with the
    edges' ``degrees (n_edges,) int64`` and the sides' ``translation (n_corners, dim) int64``
    (``dim = 0`` on a finite scaffold).
    """

    corner_partner: np.ndarray
    port_a: np.ndarray
    port_b: np.ndarray
    edge_starts: np.ndarray
    slot_edge: np.ndarray
    slot_index: np.ndarray
    degrees: np.ndarray
    translation: np.ndarray


class TraceArrays(NamedTuple):
    """What :func:`trace_classes` fills per class (``n_c`` classes, see there for shapes)."""

    components: np.ndarray
    lengths: np.ndarray
    periods: np.ndarray
    port_strand: np.ndarray
    port_shift: np.ndarray


class LiftInputs(NamedTuple):
    """What :func:`rows_hold_together_lift` reads of a batch of traced classes and of the scaffold.

    ``components (n_c,)``, ``periods (n_c, n_s, dim)`` in walk order, ``port_strand (n_c,
    n_ports)`` and ``port_shift (n_c, n_ports, dim)`` of the classes; the ports of each edge
    ``edge_ports[edge_port_ptr[e]:edge_port_ptr[e + 1]]`` (its first port first) and the
    side translations ``tau (n_corners, dim)``.
    """

    components: np.ndarray
    periods: np.ndarray
    port_strand: np.ndarray
    port_shift: np.ndarray
    edge_port_ptr: np.ndarray
    edge_ports: np.ndarray
    tau: np.ndarray


class ClassOptions(NamedTuple):
    """The labels of each residue class per edge (:class:`~lkspace.design.space.ResidueTable` layout).

    ``opts (n_edges, max_res, max_opts)``: the labels of residue index ``i`` of edge ``j``
    are ``opts[j, i, :n_opts[j, i]]``.
    """

    opts: np.ndarray
    n_opts: np.ndarray


class Actions(NamedTuple):
    """Signed edge permutations as the canonical test reads them.

    Action ``a`` maps labels ``t`` to ``signs[a] * t[inv_perms[a]]`` (``inv_perms (n_a,
    n_edges)``, ``signs (n_a,)``).
    """

    inv_perms: np.ndarray
    signs: np.ndarray


class Rows(NamedTuple):
    """Canonical rows written by a kernel: ``labels (m, n_edges) int8`` and ``stab (m,) int64`` (stabilizer sizes)."""

    labels: np.ndarray
    stab: np.ndarray


@kernel
def trace_classes(residues: np.ndarray, ports: WalkPorts, out: TraceArrays) -> None:
    """Walk the strands of each class ``residues (n_c, n_edges)``, in walk order.

    Fills ``out``: ``components (n_c,)``, ``lengths (n_c, n_corners)`` (corner links per
    strand, -1 past the last strand), ``periods (n_c, n_corners, dim)``, and, per port,
    ``port_strand (n_c, 2 n_corners)`` and ``port_shift (n_c, 2 n_corners, dim)``.
    """
    corner_partner, port_a, port_b, edge_starts = ports.corner_partner, ports.port_a, ports.port_b, ports.edge_starts
    slot_edge, slot_index, degrees, translation = ports.slot_edge, ports.slot_index, ports.degrees, ports.translation
    components, lengths, periods = out.components, out.lengths, out.periods
    port_strand, port_shift = out.port_strand, out.port_shift
    n_c = residues.shape[0]
    n_slots = len(port_a)
    n_ports = 2 * n_slots
    dim = translation.shape[1]
    partner = np.empty(n_ports, np.int64)
    visited = np.zeros(n_ports, np.bool_)
    steps = np.empty(n_slots, np.int64)
    for c in range(n_c):
        for q in range(n_slots):
            e = slot_edge[q]
            k = degrees[e]
            target = edge_starts[e] + (slot_index[q] + residues[c, e]) % k
            partner[port_a[q]] = port_b[target]
            partner[port_b[target]] = port_a[q]
        visited[:] = False
        lengths[c, :] = -1
        n_strands = 0
        for x0 in range(n_ports):
            if visited[x0]:
                continue
            for j in range(dim):
                periods[c, n_strands, j] = 0
            n_steps, _ = walk_strand(
                corner_partner,
                partner,
                translation,
                x0,
                n_strands,
                visited,
                steps,
                0,
                port_strand[c],
                port_shift[c],
                periods[c, n_strands],
            )
            lengths[c, n_strands] = n_steps
            n_strands += 1
        components[c] = n_strands


@kernel
def expand_classes(
    indices: np.ndarray,
    options: ClassOptions,
    actions: Actions,
    stab_ptr: np.ndarray,
    stab_ids: np.ndarray,
    out: Rows,
    out_class: np.ndarray,
) -> int:
    """Canonical assignments of every class ``indices (n_c, n_edges)``; return how many.

    Each class's assignments go through :func:`canonical_rows` with the class's stabilizer
    ``stab_ids[stab_ptr[c]:stab_ptr[c+1]]`` (identity left out): rows in ``out``, batch
    class in ``out_class`` (sized for every assignment of the batch).
    """
    n_c, n_e = indices.shape
    work = np.empty((3, n_e), np.int64)
    table = np.empty((n_e, options.opts.shape[2]), np.int64)
    m = 0
    for c in range(n_c):
        size = class_options(indices[c], options, table, work[1])
        first = m
        m = canonical_rows(table, actions, stab_ids[stab_ptr[c] : stab_ptr[c + 1]], 0, size, out, m, work)
        out_class[first:m] = c
    return m


@kernel
def expand_class_range(
    index: np.ndarray,
    options: ClassOptions,
    actions: Actions,
    stabilizer: np.ndarray,
    start: int,
    stop: int,
    out: Rows,
) -> int:
    """Canonical assignments ``start..stop`` of the class ``index (n_edges,)`` (a large class, in chunks).

    ``stabilizer``: the class's stabilizer, identity left out; see :func:`canonical_rows`.
    Returns how many rows were written to ``out``.
    """
    work = np.empty((3, len(index)), np.int64)
    table = np.empty((len(index), options.opts.shape[2]), np.int64)
    class_options(index, options, table, work[1])
    return canonical_rows(table, actions, stabilizer, start, stop, out, 0, work)


@helper
def class_options(index: np.ndarray, options: ClassOptions, table: np.ndarray, radices: np.ndarray) -> int:
    """Copy the labels of the class ``index (n_edges,)`` to ``table`` and their counts to ``radices``; return the class size.

    ``table[j, :radices[j]] = opts[j, index[j], :n_opts[j, index[j]]]`` (``residue_table`` layout).
    """
    opts, n_opts = options.opts, options.n_opts
    size = 1
    for j in range(len(index)):
        radices[j] = n_opts[j, index[j]]
        size *= radices[j]
        for d in range(radices[j]):
            table[j, d] = opts[j, index[j], d]
    return size


@helper
def canonical_rows(
    class_opts: np.ndarray,
    actions: Actions,
    stabilizer: np.ndarray,
    start: int,
    stop: int,
    out: Rows,
    m: int,
    work: np.ndarray,
) -> int:
    """Append the canonical ones of assignments ``start..stop`` of one class to row ``m`` on; return the new row count.

    The class's assignments put ``class_opts[j, d]`` on edge ``j`` for ``d < work[1, j]`` (the
    caller fills ``work[1]`` with the label count per edge), numbered in mixed radix (last
    edge fastest).  One is kept when it is the smallest under the ``stabilizer`` (action
    ids of ``actions``, identity left out; :func:`~lkspace.compiled.loops.stabilizer_if_smallest`):
    its labels go to ``out.labels[m]``, its stabilizer size to ``out.stab[m]``.
    ``work (3, n_edges) int64``: digits, radices, labels.
    """
    inv_perms, signs, out_labels, out_stab = actions.inv_perms, actions.signs, out.labels, out.stab
    hi = len(stabilizer)
    n_e = len(class_opts)
    digits, radices, labels = work[0], work[1], work[2]
    set_digits(digits, radices, start)
    for j in range(n_e):
        labels[j] = class_opts[j, digits[j]]
    no_moduli = radices[:0]  # the stabilizer keeps the residues: compare labels alone
    for _ in range(start, stop):
        stab = 1
        if hi > 0:
            stab = stabilizer_if_smallest(labels, labels, no_moduli, inv_perms, signs, stabilizer, 0, hi)
        if stab:
            for j in range(n_e):
                out_labels[m, j] = labels[j]
            out_stab[m] = stab
            m += 1
        # next_digits, with each changed label set as its digit changes: this loop runs once per
        # assignment, and the shared step plus a second pass over the labels costs 1.5x the walk
        j = n_e - 1
        while j >= 0:
            digits[j] += 1
            if digits[j] < radices[j]:
                labels[j] = class_opts[j, digits[j]]
                break
            digits[j] = 0
            labels[j] = class_opts[j, 0]
            j -= 1
    return m


@kernel
def rows_hold_together_lift(labels: np.ndarray, row_class: np.ndarray, lift: LiftInputs) -> np.ndarray:
    """(m,) bool: whether each row ``labels[i]`` of class ``row_class[i]`` holds together.

    Strands of the class are joined at every edge with a nonzero label (each port of the
    edge to the edge's first port, :func:`~lkspace.strands.holding_together.winding_links`).
    Periodic scaffolds (``tau`` has ``dim > 0`` columns) also need the lift: one piece,
    and the periods plus the cycle translations generate ``Z^dim`` (index 1).
    """
    components, periods, port_strand, port_shift = lift.components, lift.periods, lift.port_strand, lift.port_shift
    edge_port_ptr, edge_ports, tau = lift.edge_port_ptr, lift.edge_ports, lift.tau
    m, n_e = labels.shape
    dim = tau.shape[1]
    n_max = port_strand.shape[1]
    out = np.ones(m, np.bool_)
    parent = np.empty(n_max, np.int64)
    size = np.empty(n_max, np.int64)
    pot = np.zeros((n_max, dim), np.int64)
    vec = np.zeros((n_max + len(edge_ports), dim), np.int64)
    basis = np.zeros((dim, dim), np.int64)
    has = np.zeros(dim, np.bool_)
    v = np.zeros(dim, np.int64)
    pa = np.zeros(dim, np.int64)
    pb = np.zeros(dim, np.int64)
    for i in range(m):
        c = row_class[i]
        n = components[c]
        if n <= 1 and dim == 0:
            continue
        for k in range(n):
            parent[k] = k
            size[k] = 1
        n_vec = 0
        pieces = n
        for e in range(n_e):
            if labels[i, e] == 0:
                continue
            x = edge_ports[edge_port_ptr[e]]
            for p in range(edge_port_ptr[e] + 1, edge_port_ptr[e + 1]):
                y = edge_ports[p]
                a = port_strand[c, x]
                b = port_strand[c, y]
                if a == b:  # one strand: no join, and the link closes the shift between its ports (if any)
                    closes = False
                    for j in range(dim):
                        vec[n_vec, j] = port_shift[c, x, j] + tau[x // 2, j] - port_shift[c, y, j] - tau[y // 2, j]
                        closes |= vec[n_vec, j] != 0
                    n_vec += closes  # a zero translation generates nothing: left out
                    continue
                # lkspace.compiled.loops.join written out: as a call it costs this kernel 1.4x (measured)
                for j in range(dim):
                    pa[j] = 0
                    pb[j] = 0
                while parent[a] != a:
                    for j in range(dim):
                        pa[j] += pot[a, j]
                    a = parent[a]
                while parent[b] != b:
                    for j in range(dim):
                        pb[j] += pot[b, j]
                    b = parent[b]
                for j in range(dim):
                    v[j] = pa[j] + port_shift[c, x, j] + tau[x // 2, j] - port_shift[c, y, j] - tau[y // 2, j] - pb[j]
                if a == b:
                    if dim > 0:
                        for j in range(dim):
                            vec[n_vec, j] = v[j]
                        n_vec += 1
                elif size[a] >= size[b]:
                    parent[b] = a
                    for j in range(dim):
                        pot[b, j] = v[j]
                    size[a] += size[b]
                    pieces -= 1
                else:
                    parent[a] = b
                    for j in range(dim):
                        pot[a, j] = -v[j]
                    size[b] += size[a]
                    pieces -= 1
        if pieces != 1 or dim == 0:
            out[i] = pieces == 1
            continue
        for k in range(n):  # loops, not a slice assignment: that measured 10% slower here
            for j in range(dim):
                vec[n_vec + k, j] = periods[c, k, j]
        out[i] = lattice_index_rows(vec, n_vec + n, basis, has, v) == 1
    return out


@kernel
def rows_hold_together_finite(
    labels: np.ndarray, row_class: np.ndarray, components: np.ndarray, ptr: np.ndarray, strands: np.ndarray
) -> np.ndarray:
    """(m,) bool for finite scaffolds: strands joined at nonzero-label edges form one piece.

    ``strands[ptr[c * n_edges + e]:ptr[c * n_edges + e + 1]]`` are the distinct strands of
    batch class ``c`` through edge ``e``.
    """
    m, n_e = labels.shape
    out = np.ones(m, np.bool_)
    n_max = 1  # a loop, not components.max(): that code's loading imports numba's array math and scipy.linalg (0.2 s)
    for c in range(len(components)):
        n_max = max(n_max, components[c])
    parent = np.empty(n_max, np.int64)
    for i in range(m):
        c = row_class[i]
        n = components[c]
        if n <= 1:
            continue
        for k in range(n):
            parent[k] = k
        pieces = n
        for e in range(n_e):
            if labels[i, e] == 0:
                continue
            base = c * n_e + e
            a = find(parent, strands[ptr[base]])
            for p in range(ptr[base] + 1, ptr[base + 1]):
                b = find(parent, strands[p])
                if a != b:
                    parent[b] = a
                    pieces -= 1
        out[i] = pieces == 1
    return out
