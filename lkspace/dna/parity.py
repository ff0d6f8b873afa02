"""Which parity patterns ``t mod 2`` let the strands run antiparallel on every edge, on any mesh.

With every edge of degree 2, whether a design's strands can be oriented antiparallel depends
only on its labels mod 2 (the strands do).  Give each face corner ``c`` a bit ``x[c]``: 0 when
the strand turning there runs along its face's orientation, 1 against (``docs/dna.md``).
Then, for an edge ``e`` with parity ``p[e]`` and sides ``s1``, ``s2``:

- along each side, from its corner at one end to its corner at the other:
  ``x[c] + x[c'] = p[e]`` (an even twist keeps the strand in its face, an odd one moves it to
  the other face, which runs the edge the other way when the faces are coherent);
- at each end, the two sides' corners there: ``x[c1] + x[c2] = sigma[e]``, with ``sigma[e] = 1``
  when both sides run the edge the same way (the faces are not coherent there), else 0: the
  two strands then run in opposite directions.

The pattern ``p`` is buildable exactly when this system over GF(2) has a solution: every
cycle of the corner graph sums to 0.  A spanning forest gives each corner's bit as an affine
function of ``p``; each other relation gives one linear equation ``row . p = rhs``.  So the
buildable patterns form an affine subspace of ``GF(2)^edges`` (the cut space on a coherently
oriented closed surface: the rule of ``docs/dna.md``; a coset without 0 on a non-orientable
one), and :func:`parity_patterns` lists its members that meet given per-edge parities.
Patterns are Python ints with edge 0 as the most significant of ``n_edges`` bits, so their
numeric order is the lexicographic order of the parity vectors.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from ..model.scaffold import Scaffold


@dataclass(frozen=True)
class ParitySystem:
    """The linear equations ``rows[i] . p = rhs[i]`` (over GF(2)) that a buildable pattern ``p`` meets.

    ``rows`` are bit masks in :func:`edge_bit` order; ``consistent`` is false when some
    equation reads ``0 = 1`` (no pattern is buildable).
    """

    n_edges: int
    rows: tuple[int, ...]
    rhs: tuple[int, ...]
    consistent: bool


def edge_bit(e: int, n_edges: int) -> int:
    """Return the bit of edge ``e`` in a pattern (edge 0 most significant)."""
    return 1 << (n_edges - 1 - e)


def parity_system(scaffold: Scaffold) -> ParitySystem:
    """Return the equations of the buildable parity patterns of ``scaffold`` (every edge of degree 2)."""
    n_e = scaffold.n_edges
    nxt, verts = scaffold.corner_next, scaffold.corners
    sides_of = scaffold.radial.edge_sides.reshape(n_e, 2)  # degree 2: two sides per edge
    forward = scaffold.side_forward
    links: list[list[tuple[int, int, int]]] = [[] for _ in range(scaffold.n_corners)]

    def link(c1: int, c2: int, mask: int, const: int) -> None:
        links[c1].append((c2, mask, const))
        links[c2].append((c1, mask, const))

    for e in range(n_e):
        s1, s2 = (int(s) for s in sides_of[e])
        bit = edge_bit(e, n_e)
        for s in (s1, s2):
            link(s, int(nxt[s]), bit, 0)
        sigma = int(bool(forward[s1]) == bool(forward[s2]))
        ends2 = {int(verts[s2]): s2, int(verts[nxt[s2]]): int(nxt[s2])}
        for c1 in (s1, int(nxt[s1])):
            link(c1, ends2[int(verts[c1])], 0, sigma)
    potential: list[tuple[int, int] | None] = [None] * scaffold.n_corners
    rows: list[int] = []
    rhs: list[int] = []
    for root in range(scaffold.n_corners):
        if potential[root] is not None:
            continue
        potential[root] = (0, 0)
        queue = [root]
        while queue:
            c = queue.pop()
            mask_c, const_c = potential[c]  # type: ignore[misc]
            for d, mask, const in links[c]:
                found = potential[d]
                if found is None:
                    potential[d] = (mask_c ^ mask, const_c ^ const)
                    queue.append(d)
                else:  # a cycle: its bits must sum to 0
                    rows.append(mask_c ^ mask ^ found[0])
                    rhs.append(const_c ^ const ^ found[1])
    consistent = all(r != 0 or b == 0 for r, b in zip(rows, rhs, strict=True))
    return ParitySystem(n_e, tuple(rows), tuple(rhs), consistent)


def reduce(rows: list[int], rhs: list[int]) -> tuple[dict[int, tuple[int, int]], bool]:
    """Gauss-Jordan elimination over GF(2): ``({pivot bit: (row, rhs)}, consistent)``, fully reduced."""
    pivots: dict[int, tuple[int, int]] = {}
    for row, b in zip(rows, rhs, strict=True):
        for bit, (prow, pb) in pivots.items():
            if row & bit:
                row, b = row ^ prow, b ^ pb
        if row == 0:
            if b:
                return {}, False
            continue
        bit = 1 << (row.bit_length() - 1)
        for other, (prow, pb) in list(pivots.items()):
            if prow & bit:
                pivots[other] = (prow ^ row, pb ^ b)
        pivots[bit] = (row, b)
    return pivots, True


@dataclass(frozen=True)
class Patterns:
    """The buildable patterns that meet given per-edge parities: ``base`` plus any sum of ``directions``.

    Attributes
    ----------
    base : int or None
        One pattern (``None``: there is none).
    directions : tuple of int
        Independent patterns whose sums, added to ``base``, give every other one.
    """

    base: int | None
    directions: tuple[int, ...]

    @property
    def count(self) -> int:
        """How many patterns there are (``2 ** len(directions)``, or 0)."""
        return 0 if self.base is None else 1 << len(self.directions)

    def generators(self) -> list[int]:
        """Return ``base`` and ``base + d`` for each direction: every pattern is a sum of an odd number of these."""
        return [] if self.base is None else [self.base, *(self.base ^ d for d in self.directions)]

    def __iter__(self) -> Iterator[int]:
        """Every pattern, in increasing order."""
        if self.base is None:
            return iter(())
        found = [self.base]
        for d in self.directions:
            found += [p ^ d for p in found]
        return iter(sorted(found))


def parity_patterns(system: ParitySystem, fixed: dict[int, int]) -> Patterns:
    """Return the buildable patterns with parity ``fixed[e]`` on the edges named (:class:`Patterns`).

    Their number is known before they are listed, so a caller can refuse a large space first.
    """
    n_e = system.n_edges
    rows, rhs = list(system.rows), list(system.rhs)
    for e, parity in fixed.items():
        rows.append(edge_bit(e, n_e))
        rhs.append(parity)
    pivots, consistent = reduce(rows, rhs) if system.consistent else ({}, False)
    if not consistent:
        return Patterns(None, ())
    free = [1 << i for i in range(n_e) if (1 << i) not in pivots]
    # a free bit set alone, and every pivot it appears in: fully reduced rows read pivot = rhs + free bits
    base = sum(bit for bit, (_row, b) in pivots.items() if b)
    directions = tuple(f | sum(bit for bit, (row, _b) in pivots.items() if row & f) for f in free)
    return Patterns(base, directions)
