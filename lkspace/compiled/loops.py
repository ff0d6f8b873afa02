"""The loops compiled kernels share (helpers of :mod:`lkspace.compiled.kernels`), each idea written once.

* Mixed-radix counting: :func:`set_digits` and :func:`next_digits` (the last digit
  runs fastest, as assignments and class codes are numbered).
* The canonical test: :func:`stabilizer_if_smallest`, whether labels are the smallest of
  their orbit under signed edge permutations, and how many of them fix the labels.  Action
  ``a`` maps labels ``t`` to ``signs[a] * t[inv_perms[a]]`` (:mod:`lkspace.symmetry.group`).
* Union-find, the one of the package: :func:`find` (the root of an item's piece) and
  :func:`join` (union by size with potentials: on a periodic scaffold the lattice
  translations closed by cycles, for signed edge orbits parities taken mod 2), the kernel
  :func:`join_pairs` joining many pairs in one call, and :class:`UnionFind`, the same
  arrays for plain Python callers.
  Two of the hottest loops keep a step written out, measured faster so: the walk's
  mixed-radix step in :func:`~lkspace.design.batch_kernels.canonical_rows` and ``join`` in
  :func:`~lkspace.design.batch_kernels.rows_hold_together_lift`.
* The index of an integer lattice: :func:`lattice_index_rows`.

Each works on arrays the caller allocates, so kernels call them in their inner loops
without allocating.
"""

from __future__ import annotations

import numpy as np

from .kernels import SMALL_WORK, helper, kernel


@helper
def set_digits(digits: np.ndarray, radices: np.ndarray, number: int) -> None:
    """Write ``number`` into ``digits`` in mixed radix ``radices`` (last digit least significant)."""
    for j in range(len(radices) - 1, -1, -1):
        digits[j] = number % radices[j]
        number //= radices[j]


@helper
def next_digits(digits: np.ndarray, radices: np.ndarray) -> int:
    """Add one to the mixed-radix number ``digits``; return the first position that changed.

    Positions after it went back to 0; -1 means every digit did (the count wrapped around).
    """
    j = len(radices) - 1
    while j >= 0:
        digits[j] += 1
        if digits[j] < radices[j]:
            return j
        digits[j] = 0
        j -= 1
    return -1


@helper
def stabilizer_if_smallest(
    labels: np.ndarray,
    residues: np.ndarray,
    moduli: np.ndarray,
    inv_perms: np.ndarray,
    signs: np.ndarray,
    actions: np.ndarray,
    lo: int,
    hi: int,
) -> int:
    """0 if an action ``actions[lo:hi]`` maps ``labels`` lower, else 1 + how many fix them.

    Lower means lexicographically smaller in (``t mod moduli`` per edge, then ``t`` per edge),
    ``residues`` holding ``labels mod moduli``.  Empty ``moduli`` compares ``t`` alone: enough
    when every action keeps the residues (the stabilizer of a residue class).  The 1 counts
    the identity, which ``actions[lo:hi]`` leaves out.
    """
    n = len(labels)
    stab = 1
    for p in range(lo, hi):
        a = actions[p]
        s = signs[a]
        cmp = 0
        if len(moduli):
            for j in range(n):
                r = (s * labels[inv_perms[a, j]]) % moduli[j]
                if r != residues[j]:
                    cmp = -1 if r < residues[j] else 1
                    break
        if cmp == 0:
            for j in range(n):
                v = s * labels[inv_perms[a, j]]
                if v != labels[j]:
                    cmp = -1 if v < labels[j] else 1
                    break
        if cmp < 0:
            return 0
        if cmp == 0:
            stab += 1
    return stab


@helper
def find(parent: np.ndarray | list[int], a: int) -> int:
    """Return the root of ``a`` in the forest ``parent`` (``parent[r] == r`` at a root)."""
    while parent[a] != a:
        a = parent[a]
    return a


@helper
def join(
    parent: np.ndarray | list[int],
    size: np.ndarray | list[int],
    pot: np.ndarray,
    a: int,
    b: int,
    shift: np.ndarray,
    rel: np.ndarray,
) -> bool:
    """Join the pieces of strands ``a`` and ``b``; return False when they were one piece already.

    Union by size over ``parent`` and ``size``; ``pot[s] (dim,)`` is the lattice translation of
    strand ``s``'s copy relative to its parent's, ``shift (dim,)`` that of ``b``'s copy
    relative to ``a``'s (``dim`` may be 0: a finite scaffold).  ``rel`` receives the
    translation of ``b``'s root copy relative to ``a``'s root copy: when they were one piece
    already, the translation the link closes.
    """
    dim = len(shift)
    for j in range(dim):
        rel[j] = shift[j]
    while parent[a] != a:
        for j in range(dim):
            rel[j] += pot[a, j]
        a = parent[a]
    while parent[b] != b:
        for j in range(dim):
            rel[j] -= pot[b, j]
        b = parent[b]
    if a == b:
        return False
    if size[a] >= size[b]:
        parent[b] = a
        for j in range(dim):
            pot[b, j] = rel[j]
        size[a] += size[b]
    else:
        parent[a] = b
        for j in range(dim):
            pot[a, j] = -rel[j]
        size[b] += size[a]
    return True


@kernel
def join_pairs(
    parent: np.ndarray, size: np.ndarray, pot: np.ndarray, pairs: np.ndarray, shifts: np.ndarray, closed: np.ndarray
) -> np.ndarray:
    """Join ``pairs[k, 0]`` and ``pairs[k, 1]`` for each ``k`` in order (:func:`join`); return ``(m,) bool``, which joined two pieces.

    ``shifts (m, dim)``: the potential of each pair's second item relative to its first;
    ``closed (m, dim)`` receives, for a pair already in one piece, the potential its link
    closes (the rows of joining pairs are left as they were).
    """
    m = pairs.shape[0]
    joined = np.zeros(m, np.bool_)
    rel = np.zeros(pot.shape[1], np.int64)
    for k in range(m):
        if join(parent, size, pot, pairs[k, 0], pairs[k, 1], shifts[k], rel):
            joined[k] = True
        else:
            closed[k] = rel
    return joined


class UnionFind:
    """Union-find over ``n`` items with potentials ``(n, dim)``, on the arrays of :func:`find` and :func:`join`.

    For plain Python callers (the kernels call the helpers on their own arrays).
    ``dim = 0``: no potentials, and ``parent`` and ``size`` are Python lists (the helpers
    index them as they index arrays, and plain Python indexes lists about 3x faster than
    numpy arrays); :meth:`join_pairs` hands large jobs to the compiled kernel on arrays.
    ``pieces`` counts the pieces; ``rel (dim,)`` holds what the last :meth:`join` closed
    (see :func:`join`).

    Examples
    --------
    >>> uf = UnionFind(4)
    >>> uf.join(0, 1), uf.join(2, 3), uf.join(1, 0), uf.pieces
    (True, True, False, 2)
    >>> uf.find(1) == uf.find(0), uf.find(2) == uf.find(0)
    (True, False)
    """

    def __init__(self, n: int, dim: int = 0) -> None:
        self.parent: list[int] | np.ndarray = list(range(n)) if dim == 0 else np.arange(n, dtype=np.int64)
        self.size: list[int] | np.ndarray = [1] * n if dim == 0 else np.ones(n, np.int64)
        self.pot = np.zeros((n, dim), np.int64)
        self.rel = np.zeros(dim, np.int64)
        self.pieces = n
        self._no_shift = np.zeros(dim, np.int64)

    def find(self, a: int) -> int:
        """Return the root of ``a``'s piece."""
        return int(find(self.parent, a))

    def join(self, a: int, b: int, shift: np.ndarray | None = None) -> bool:
        """Join the pieces of ``a`` and ``b`` (``shift (dim,)``: ``b``'s potential relative to ``a``'s); False if one already."""
        if join(self.parent, self.size, self.pot, a, b, self._no_shift if shift is None else shift, self.rel):
            self.pieces -= 1
            return True
        return False

    def join_pairs(self, pairs: np.ndarray, shifts: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Join every row of ``pairs (m, 2) int64`` in order (:func:`join_pairs`, compiled for large ``m``).

        Returns ``(joined (m,) bool, closed (m, dim) int64)``: whether each pair joined two
        pieces, and for the others the potential their link closes.
        """
        pairs = np.ascontiguousarray(pairs, np.int64).reshape(-1, 2)
        dim = self.pot.shape[1]
        if shifts is None:
            shifts = np.zeros((len(pairs), dim), np.int64)
        closed = np.zeros((len(pairs), dim), np.int64)
        shifts = np.ascontiguousarray(shifts, np.int64)
        if isinstance(self.parent, list) and len(pairs) < SMALL_WORK:  # dim 0: closed has no columns
            no_shift, rel = self._no_shift, self.rel
            flags = [join(self.parent, self.size, self.pot, a, b, no_shift, rel) for a, b in pairs.tolist()]
            joined = np.array(flags, np.bool_)
        else:
            parent, size = np.asarray(self.parent, np.int64), np.asarray(self.size, np.int64)
            joined = join_pairs.run(len(pairs), parent, size, self.pot, pairs, shifts, closed)
            if isinstance(self.parent, list):
                self.parent, self.size = parent.tolist(), size.tolist()
        self.pieces -= int(joined.sum())
        return joined, closed

    def roots(self) -> np.ndarray:
        """``(n,) int64``: the root of every item's piece."""
        parent = np.asarray(self.parent, np.int64)
        roots = parent.copy()
        while True:
            up = parent[roots]
            if np.array_equal(up, roots):
                return roots
            roots = up

    def potentials(self) -> np.ndarray:
        """``(n, dim) int64``: every item's potential relative to its root."""
        parent, out = np.asarray(self.parent, np.int64), self.pot.copy()
        up = parent.copy()
        while True:  # out[i] sums pot along the path from i to up[i]
            done = up == parent[up]
            if done.all():
                return out
            out[~done] += self.pot[up[~done]]
            up = np.where(done, up, parent[up])

    def copy(self) -> UnionFind:
        """Return an independent copy."""
        other = UnionFind.__new__(UnionFind)  # no arrays allocated only to be replaced
        other.parent, other.size, other.pot = self.parent.copy(), self.size.copy(), self.pot.copy()
        other.rel, other._no_shift, other.pieces = self.rel.copy(), self._no_shift, self.pieces
        return other


@helper
def lattice_index_rows(vectors: np.ndarray, n: int, basis: np.ndarray, has: np.ndarray, v: np.ndarray) -> int:
    """Index in ``Z^dim`` of the subgroup generated by the rows ``vectors[:n]`` (0: infinite).

    Rows are added one by one to an integer echelon basis (row ``c`` has pivot ``c``),
    merging pivots with the extended Euclidean algorithm.  Scratch: ``basis (dim, dim)``,
    ``has (dim,) bool``, ``v (dim,)``.
    """
    dim = vectors.shape[1]
    basis[:, :] = 0
    has[:] = False
    for k in range(n):
        for j in range(dim):
            v[j] = vectors[k, j]
        for c in range(dim):
            if v[c] == 0:
                continue
            if not has[c]:
                for j in range(dim):
                    basis[c, j] = v[j]
                has[c] = True
                break
            g, b = basis[c, c], v[c]  # extended gcd: g = basis[c, c] * x0 + v[c] * y0 >= 0
            x0, y0, x1, y1 = 1, 0, 0, 1
            while b != 0:
                q = g // b
                g, b = b, g - q * b
                x0, x1 = x1, x0 - q * x1
                y0, y1 = y1, y0 - q * y1
            if g < 0:
                g, x0, y0 = -g, -x0, -y0
            p, q = basis[c, c] // g, v[c] // g
            for j in range(dim):
                bj = basis[c, j]
                basis[c, j] = x0 * bj + y0 * v[j]
                v[j] = p * v[j] - q * bj
            for jj in range(c + 1, dim):  # keep entries small: reduce modulo later pivots
                if has[jj] and basis[jj, jj] != 0:
                    f = v[jj] // basis[jj, jj]
                    for j in range(dim):
                        v[j] -= f * basis[jj, j]
    index = 1
    for c in range(dim):
        if not has[c]:
            return 0
        index *= abs(basis[c, c])
    return index
