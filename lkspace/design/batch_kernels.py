"""Compiled kernels that treat many residue classes in one call (see :mod:`lkspace.design.batch`).

A scaffold whose residue classes are tiny (``honeycomb:oF`` with labels ``-1..1``: one
assignment per class) spends its time in per-class Python calls unless many classes go
through one compiled call.  These kernels take a batch of classes as arrays:

* :func:`trace_classes`: the strand walk of :mod:`lkspace.strands.walk` for each class's
  residues (the same traversal, so strands come in the same order);
* :func:`expand_classes`: the canonical assignments of each class, as
  :func:`lkspace.design.walk.canonical_block` finds them for one class;
* :func:`rows_hold_together_lift`: whether each row holds together, finite or periodic (the
  infinite lift of :mod:`lkspace.strands.holding_together`: union-find with lattice
  potentials, then the index of the realizable translations);

The orbit kernels (representatives, stabilizers, Burnside counts) are in
:mod:`lkspace.design.orbit_kernels`.

Each kernel is self-contained (kernels do not call each other, :mod:`lkspace.kernels`).
"""

from __future__ import annotations

import numpy as np

from ..kernels import kernel


@kernel
def trace_classes(
    residues: np.ndarray,
    corner_partner: np.ndarray,
    port_a: np.ndarray,
    port_b: np.ndarray,
    edge_starts: np.ndarray,
    slot_edge: np.ndarray,
    slot_index: np.ndarray,
    degrees: np.ndarray,
    translation: np.ndarray,
    components: np.ndarray,
    lengths: np.ndarray,
    periods: np.ndarray,
    port_strand: np.ndarray,
    port_shift: np.ndarray,
) -> None:
    """Walk the strands of each class ``residues (n_c, n_edges)``, in walk order.

    Fills ``components (n_c,)``, ``lengths (n_c, n_corners)`` (corner links per strand,
    -1 past the last strand), ``periods (n_c, n_corners, dim)``, and, per port,
    ``port_strand (n_c, 2 n_corners)`` and ``port_shift (n_c, 2 n_corners, dim)``.
    """
    n_c = residues.shape[0]
    n_slots = len(port_a)
    n_ports = 2 * n_slots
    dim = translation.shape[1]
    partner = np.empty(n_ports, np.int64)
    visited = np.zeros(n_ports, np.bool_)
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
            x = x0
            n_steps = 0
            while True:
                y = corner_partner[x]
                n_steps += 1
                visited[x] = True
                visited[y] = True
                port_strand[c, x] = n_strands
                port_strand[c, y] = n_strands
                for j in range(dim):
                    port_shift[c, x, j] = periods[c, n_strands, j]
                    port_shift[c, y, j] = periods[c, n_strands, j]
                z = partner[y]
                for j in range(dim):
                    periods[c, n_strands, j] += translation[y // 2, j] - translation[z // 2, j]
                if z == x0:
                    break
                x = z
            lengths[c, n_strands] = n_steps
            n_strands += 1
        components[c] = n_strands


@kernel
def expand_classes(
    indices: np.ndarray,
    opts: np.ndarray,
    n_opts: np.ndarray,
    inv_perms: np.ndarray,
    signs: np.ndarray,
    stab_ptr: np.ndarray,
    stab_ids: np.ndarray,
    out_labels: np.ndarray,
    out_stab: np.ndarray,
    out_class: np.ndarray,
) -> int:
    """Canonical assignments of every class ``indices (n_c, n_edges)``; return how many.

    Each class's assignments are walked in mixed radix (last edge fastest) and kept when
    lexicographically smallest under the class's stabilizer ``stab_ids[stab_ptr[c]:stab_ptr[c+1]]``
    (identity left out): rows in ``out_labels``, stabilizer sizes in ``out_stab``, batch
    class in ``out_class`` (sized for every assignment of the batch).
    """
    n_c, n_e = indices.shape
    digits = np.zeros(n_e, np.int64)
    cur = np.zeros(n_e, np.int64)
    cnt = np.zeros(n_e, np.int64)
    m = 0
    for c in range(n_c):
        size = 1
        for j in range(n_e):
            cnt[j] = n_opts[j, indices[c, j]]
            digits[j] = 0
            cur[j] = opts[j, indices[c, j], 0]
            size *= cnt[j]
        for _ in range(size):
            canon = True
            stab = 1
            for p in range(stab_ptr[c], stab_ptr[c + 1]):
                h = stab_ids[p]
                cmp = 0
                s = signs[h]
                for j in range(n_e):
                    v = s * cur[inv_perms[h, j]]
                    if v != cur[j]:
                        cmp = -1 if v < cur[j] else 1
                        break
                if cmp < 0:
                    canon = False
                    break
                if cmp == 0:
                    stab += 1
            if canon:
                for j in range(n_e):
                    out_labels[m, j] = cur[j]
                out_stab[m] = stab
                out_class[m] = c
                m += 1
            j = n_e - 1
            while j >= 0:
                digits[j] += 1
                if digits[j] < cnt[j]:
                    cur[j] = opts[j, indices[c, j], digits[j]]
                    break
                digits[j] = 0
                cur[j] = opts[j, indices[c, j], 0]
                j -= 1
    return m


@kernel
def rows_hold_together_lift(
    labels: np.ndarray,
    row_class: np.ndarray,
    components: np.ndarray,
    periods: np.ndarray,
    port_strand: np.ndarray,
    port_shift: np.ndarray,
    edge_port_ptr: np.ndarray,
    edge_ports: np.ndarray,
    tau: np.ndarray,
) -> np.ndarray:
    """(m,) bool: whether each row ``labels[i]`` of class ``row_class[i]`` holds together.

    Strands of the class are joined at every edge with a nonzero label (each port of the
    edge to the edge's first port, :func:`~lkspace.strands.holding_together.winding_links`).
    Periodic scaffolds (``tau`` has ``dim > 0`` columns) also need the lift: one piece,
    and the periods plus the cycle translations generate ``Z^dim`` (index 1).
    """
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
    pa = np.zeros(dim, np.int64)
    pb = np.zeros(dim, np.int64)
    v = np.zeros(dim, np.int64)
    for i in range(m):
        c = row_class[i]
        n = components[c]
        if n <= 1 and dim == 0:
            continue
        for k in range(n):
            parent[k] = k
            size[k] = 1
            for j in range(dim):
                pot[k, j] = 0
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
        if pieces != 1:
            out[i] = False
            continue
        if dim == 0:
            continue
        for k in range(n):
            for j in range(dim):
                vec[n_vec, j] = periods[c, k, j]
            n_vec += 1
        # index of the lattice spanned by vec[:n_vec] (lkspace.strands.holding_together.echelon_index)
        basis[:, :] = 0
        has[:] = False
        for r in range(n_vec):
            for j in range(dim):
                v[j] = vec[r, j]
            for col in range(dim):
                if v[col] == 0:
                    continue
                if not has[col]:
                    for j in range(dim):
                        basis[col, j] = v[j]
                    has[col] = True
                    break
                g, b2 = basis[col, col], v[col]
                x0, y0, x1, y1 = 1, 0, 0, 1
                while b2 != 0:
                    q = g // b2
                    g, b2 = b2, g - q * b2
                    x0, x1 = x1, x0 - q * x1
                    y0, y1 = y1, y0 - q * y1
                if g < 0:
                    g, x0, y0 = -g, -x0, -y0
                p1, q1 = basis[col, col] // g, v[col] // g
                for j in range(dim):
                    bj = basis[col, j]
                    basis[col, j] = x0 * bj + y0 * v[j]
                    v[j] = p1 * v[j] - q1 * bj
                for jj in range(col + 1, dim):
                    if has[jj] and basis[jj, jj] != 0:
                        f = v[jj] // basis[jj, jj]
                        for j in range(dim):
                            v[j] -= f * basis[jj, j]
        index = 1
        for col in range(dim):
            if not has[col]:
                index = 0
                break
            index *= abs(basis[col, col])
        out[i] = index == 1
    return out


@kernel
def rows_hold_together_finite(
    labels: np.ndarray, row_class: np.ndarray, components: np.ndarray, ptr: np.ndarray, strands: np.ndarray
) -> np.ndarray:
    """(m,) bool for finite scaffolds: strands joined at nonzero-label edges form one piece.

    ``strands[ptr[c * n_edges + e]:ptr[c * n_edges + e + 1]]`` are the distinct strands of
    batch class ``c`` through edge ``e`` (the per-class form of
    :func:`lkspace.design.walk.rows_hold_together`).
    """
    m, n_e = labels.shape
    out = np.ones(m, np.bool_)
    parent = np.empty(max(1, int(components.max()) if len(components) else 1), np.int64)
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
            a = strands[ptr[base]]
            while parent[a] != a:
                a = parent[a]
            for p in range(ptr[base] + 1, ptr[base + 1]):
                b = strands[p]
                while parent[b] != b:
                    b = parent[b]
                if a != b:
                    parent[b] = a
                    pieces -= 1
        out[i] = pieces == 1
    return out
