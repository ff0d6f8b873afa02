"""The helpers kernels share (lkspace/compiled/loops.py) against plain references, plain and compiled.

Each helper is run as the plain Python function kernels call in small jobs and, wrapped
in a :class:`~lkspace.compiled.kernels.Kernel`, compiled; both must match a reference written here
(``itertools.product``, tuple comparison of explicit images, networkx components, the gcd
of maximal minors).
"""

from __future__ import annotations

import itertools
import math

import networkx as nx
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from lkspace.compiled.kernels import kernel
from lkspace.compiled.loops import join, lattice_index_rows, next_digits, set_digits, stabilizer_if_smallest

COMPILED = {f: kernel(f).compiled for f in (set_digits, next_digits, stabilizer_if_smallest, join, lattice_index_rows)}


def both(f):
    """The plain helper and its compiled version."""
    return (f, COMPILED[f])


@settings(max_examples=30, deadline=None)
@given(st.lists(st.integers(1, 4), min_size=1, max_size=4))
def test_mixed_radix_counts_like_product(radices):
    radices = np.array(radices, np.int64)
    expected = list(itertools.product(*(range(r) for r in radices)))
    for set_f, next_f in zip(both(set_digits), both(next_digits), strict=True):
        digits = np.zeros(len(radices), np.int64)
        set_f(digits, radices, 0)
        seen = []
        for number, row in enumerate(expected):
            fresh = np.zeros(len(radices), np.int64)
            set_f(fresh, radices, number)
            assert tuple(fresh) == row == tuple(digits)
            seen.append(tuple(digits))
            changed = next_f(digits, radices)
            if number + 1 < len(expected):
                nxt = expected[number + 1]
                assert changed == next(j for j in range(len(row)) if row[j] != nxt[j])
            else:
                assert changed == -1 and not digits.any()  # wrapped around to zero
        assert seen == expected


def _brute_stabilizer(labels, moduli, inv_perms, signs, actions):
    """0 if some action's image is smaller in (residues, labels) order, else 1 + how many fix the labels."""

    def key(t):
        return (tuple(int(x) % int(k) for x, k in zip(t, moduli, strict=True)) if len(moduli) else (), tuple(t))

    own = key(labels)
    images = [key([int(signs[a]) * int(labels[inv_perms[a, j]]) for j in range(len(labels))]) for a in actions]
    if any(img < own for img in images):
        return 0
    return 1 + sum(img == own for img in images)


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.booleans())
def test_canonical_test_against_explicit_images(seed, by_residue):
    rng = np.random.default_rng(seed)
    n, n_a = int(rng.integers(1, 6)), int(rng.integers(1, 6))
    inv_perms = np.array([rng.permutation(n) for _ in range(n_a)], np.int64)
    signs = rng.choice(np.array([-1, 1], np.int64), n_a)
    labels = rng.integers(-2, 3, n).astype(np.int64)
    moduli = rng.integers(1, 4, n).astype(np.int64) if by_residue else np.zeros(0, np.int64)
    residues = labels % moduli if by_residue else labels
    actions = np.arange(n_a, dtype=np.int64)
    lo = int(rng.integers(0, n_a))
    expected = _brute_stabilizer(labels, moduli, inv_perms, signs, actions[lo:])
    for f in both(stabilizer_if_smallest):
        assert f(labels, residues, moduli, inv_perms, signs, actions, lo, n_a) == expected


@settings(max_examples=40, deadline=None)
@given(st.integers(1, 12), st.lists(st.tuples(st.integers(0, 11), st.integers(0, 11)), max_size=20))
def test_union_find_counts_components(n, links):
    links = [(a % n, b % n) for a, b in links]
    graph = nx.Graph()
    graph.add_nodes_from(range(n))
    graph.add_edges_from(links)
    for f in both(join):
        parent, size = np.arange(n, dtype=np.int64), np.ones(n, np.int64)
        pot, none = np.zeros((n, 0), np.int64), np.zeros(0, np.int64)
        pieces = n - sum(bool(f(parent, size, pot, a, b, none, none)) for a, b in links)
        assert pieces == nx.number_connected_components(graph)


def test_union_find_potentials_close_cycles():
    # strands 0 -> 1 -> 2 shifted by (1, 0) each, then 2 -> 0 by (0, 3): the cycle closes (2, 3)
    for f in both(join):
        parent, size, pot = np.arange(3, dtype=np.int64), np.ones(3, np.int64), np.zeros((3, 2), np.int64)
        rel = np.zeros(2, np.int64)
        assert f(parent, size, pot, 0, 1, np.array([1, 0]), rel)
        assert f(parent, size, pot, 1, 2, np.array([1, 0]), rel)
        assert not f(parent, size, pot, 2, 0, np.array([0, 3]), rel)
        assert rel.tolist() == [2, 3]


def _minor_gcd_index(vectors, dim):
    """Index of the lattice spanned by integer rows: gcd of the dim x dim minors (0: rank below dim)."""

    def det(m):
        if len(m) == 1:
            return m[0][0]
        return sum((-1) ** c * m[0][c] * det([row[:c] + row[c + 1 :] for row in m[1:]]) for c in range(len(m)))

    rows = [list(map(int, v)) for v in vectors]
    return math.gcd(*(det([rows[i] for i in pick]) for pick in itertools.combinations(range(len(rows)), dim)), 0)


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 3), st.integers(0, 5), st.integers(0, 2**32 - 1))
def test_lattice_index_is_the_gcd_of_maximal_minors(dim, m, seed):
    vectors = np.random.default_rng(seed).integers(-4, 5, (m, dim)).astype(np.int64)
    expected = _minor_gcd_index(vectors, dim) if m >= dim else 0
    for f in both(lattice_index_rows):
        basis, has, v = np.zeros((dim, dim), np.int64), np.zeros(dim, np.bool_), np.zeros(dim, np.int64)
        assert f(vectors, m, basis, has, v) == expected
