"""Whether a traced structure holds together (SPEC §1).

Two strands wind around each other at an edge with ``t != 0`` that both run through; the
structure holds together when that relation connects all strands.

For a periodic scaffold the question is about the infinite lift: strand copies ``(s, T)``
for lattice translations ``T``.  Strand ``s`` owns port ``x`` in the face copy shifted by
``port_shift[x]`` from its start, so ports ``x`` (of ``s``) and ``y`` (of ``s'``) on the same
edge class meet at one edge instance exactly when copy ``(s', B)`` and copy ``(s, A)`` satisfy
``B - A = shift_x + tau_x - shift_y - tau_y`` (``tau``: the side translation).  The lift is
connected iff the quotient relation is connected and the translations it can realize —
the shifts around cycles of a spanning tree plus every thread's period — generate the
whole lattice ``Z^dim``; otherwise it falls apart into ``lift_index`` (possibly infinitely
many) congruent pieces per quotient piece.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np


@dataclass(frozen=True)
class Connectivity:
    """Holding-together summary.

    Attributes
    ----------
    n_pieces : int
        Connected groups of strands in the quotient (finite: of the structure).
    lift_index : int or None
        Periodic only: index of the realizable translations in the lattice when the
        quotient is connected (1: the lift holds together; 0: infinitely many pieces).
    """

    n_pieces: int
    lift_index: int | None

    @property
    def holds_together(self) -> bool:
        return self.n_pieces == 1 and self.lift_index in (None, 1)


def winding_links(trace) -> tuple[np.ndarray, np.ndarray]:
    """Strand pairs winding around each other and the lift shift of each pair.

    At each edge with ``t != 0`` every port is linked to the edge's slot-0 end-``a`` port
    (a star per edge: enough for connectivity, linear in the corners).  Returns
    ``pairs (n, 2) int64`` (strand of the leader, strand of the port) and
    ``shifts (n, dim) int64`` (translation of the second strand's copy relative to the
    first's, see the module docstring).
    """
    from .tracing import sc_port_model

    sc = trace.scaffold
    model = sc_port_model(sc)
    has_sides = sc.edge_degrees > 0
    leader_port = np.full(sc.n_edges, -1, np.int64)
    leader_port[has_sides] = model.port_a[model.edge_starts[:-1][has_sides]]
    ports = np.arange(2 * sc.n_corners)
    edge_of_port = np.repeat(sc.side_edge, 2)
    active = (trace.twists[edge_of_port] != 0) & (ports != leader_port[edge_of_port])
    x = leader_port[edge_of_port[active]]
    y = ports[active]
    pairs = np.column_stack([trace.port_strand[x], trace.port_strand[y]])
    if sc.periodic:
        tau = sc.side_translation
        shifts = trace.port_shift[x] + tau[x // 2] - trace.port_shift[y] - tau[y // 2]
    else:
        shifts = np.zeros((len(pairs), 0), np.int64)
    return pairs, shifts


@numba.njit(cache=True)
def _egcd(a, b):  # pragma: no cover - compiled
    """(g, x, y) with a*x + b*y = g = gcd(a, b) >= 0."""
    x0, y0, x1, y1 = 1, 0, 0, 1
    while b != 0:
        q = a // b
        a, b = b, a - q * b
        x0, x1 = x1, x0 - q * x1
        y0, y1 = y1, y0 - q * y1
    if a < 0:
        return -a, -x0, -y0
    return a, x0, y0


@numba.njit(cache=True)
def _insert(basis, has, v):  # pragma: no cover - compiled
    """Add integer vector ``v`` to the echelon ``basis`` (dim x dim, row c has pivot c)."""
    dim = len(v)
    for c in range(dim):
        if v[c] == 0:
            continue
        if not has[c]:
            basis[c, :] = v
            has[c] = True
            return
        g, x, y = _egcd(basis[c, c], v[c])
        p, q = basis[c, c] // g, v[c] // g
        row = x * basis[c, :] + y * v
        v = p * v - q * basis[c, :]
        basis[c, :] = row
        for j in range(c + 1, dim):  # keep entries small: reduce modulo later pivots
            if has[j] and basis[j, j] != 0:
                v = v - (v[j] // basis[j, j]) * basis[j, :]


@numba.njit(cache=True)
def _index(basis, has):  # pragma: no cover - compiled
    index = 1
    for c in range(len(has)):
        if not has[c]:
            return 0
        index *= abs(basis[c, c])
    return index


@numba.njit(cache=True)
def _lift(pairs, shifts, periods, n):  # pragma: no cover - compiled
    """Union-find with lattice potentials: (pieces in the quotient, lift index)."""
    dim = shifts.shape[1]
    parent = np.arange(n)
    size = np.ones(n, np.int64)
    pot = np.zeros((n, dim), np.int64)  # translation of a strand's copy relative to its parent's
    basis = np.zeros((dim, dim), np.int64)
    has = np.zeros(dim, np.bool_)
    pieces = n
    for k in range(periods.shape[0]):
        _insert(basis, has, periods[k].copy())
    for k in range(pairs.shape[0]):
        a, b = pairs[k, 0], pairs[k, 1]
        pa = np.zeros(dim, np.int64)
        while parent[a] != a:
            pa += pot[a]
            a = parent[a]
        pb = np.zeros(dim, np.int64)
        while parent[b] != b:
            pb += pot[b]
            b = parent[b]
        rel = pa + shifts[k] - pb  # copy of root b relative to root a
        if a == b:
            _insert(basis, has, rel)
        elif size[a] >= size[b]:
            parent[b] = a
            pot[b] = rel
            size[a] += size[b]
            pieces -= 1
        else:
            parent[a] = b
            pot[a] = -rel
            size[b] += size[a]
            pieces -= 1
    return pieces, _index(basis, has)


def lattice_index(vectors: np.ndarray, dim: int) -> int:
    """Index in ``Z^dim`` of the subgroup generated by integer ``vectors (m, dim)``; 0 if infinite.

    Examples
    --------
    >>> lattice_index(np.array([[2, 0], [0, 1]]), 2), lattice_index(np.array([[1, 1]]), 2)
    (2, 0)
    """
    vectors = np.asarray(vectors, dtype=np.int64).reshape(-1, dim)
    return int(_lift(np.zeros((0, 2), np.int64), np.zeros((0, dim), np.int64), vectors, 1)[1])


def connectivity(trace) -> Connectivity:
    """Compute :class:`Connectivity` of a :class:`~lkspace.tracing.Trace`."""
    pairs, shifts = winding_links(trace)
    periods = trace.periods if trace.scaffold.periodic else np.zeros((0, 0), np.int64)
    pieces, index = _lift(pairs, np.ascontiguousarray(shifts), np.ascontiguousarray(periods), trace.components)
    if not trace.scaffold.periodic or pieces != 1:
        return Connectivity(int(pieces), None)
    return Connectivity(1, int(index))
