"""Lower bounds on the crossing number from the Jones polynomial (Kauffman, Murasugi, Thistlethwaite).

Used by :mod:`lkspace.knots.key_names` to accept a table name on a design's key alone.
"""

from __future__ import annotations

import functools
import re


def crossing_bound(jones: str, matrix: list[list[int]]) -> int | None:
    """Return a lower bound on the crossing number of every link with this Jones polynomial and linking matrix.

    ``jones`` in ``x = sqrt(t)`` (``"-x^4 + 3 x^2 - 4"``); ``None`` when it cannot be read.
    Kauffman, Murasugi, Thistlethwaite (1987): a diagram with ``n`` crossings in ``p``
    disjoint pieces has ``span V <= n + p - 1``.  A least diagram has one piece when the
    link is not split, which ``V(-1) != 0`` proves (a split link's ``V`` has the factor
    ``-t^(1/2) - t^(-1/2)``); else at most :func:`linked_groups` pieces.
    """
    terms = jones_terms(jones)
    if terms is None:
        return None
    exponents = [e for e, _ in terms]
    at_minus_one = sum(c * 1j**e for e, c in terms)  # x = i: t = -1
    pieces = 1 if abs(at_minus_one) > 0.5 else linked_groups(matrix)
    return (max(exponents) - min(exponents)) // 2 - (pieces - 1)


@functools.lru_cache(maxsize=4096)
def jones_terms(text: str) -> tuple[tuple[int, int], ...] | None:
    """Return ``(exponent of x, coefficient)`` of each term of a Jones polynomial's text, or ``None`` if it is not one."""
    terms = []
    for term in re.split(r"(?<!\^)(?=[+-])", text.replace(" ", "")):
        if not term:
            continue
        match = re.fullmatch(r"([+-]?)(\d*)(x(?:\^(-?\d+))?)?", term)
        if match is None or term in ("+", "-"):
            return None
        sign, digits, power, exponent = match.groups()
        coefficient = (-1 if sign == "-" else 1) * int(digits or 1)
        terms.append((0 if power is None else int(exponent or 1), coefficient))
    if not terms or any(e % 2 != terms[0][0] % 2 for e, _ in terms):
        return None
    return tuple(terms)


def linked_groups(matrix: list[list[int]]) -> int:
    """Return the groups of components joined by non-zero linking numbers: at least as many as any split link's pieces.

    A split link's pieces are unions of groups: its least diagram has at most as many pieces.
    """
    group = list(range(len(matrix)))

    def root(i: int) -> int:
        while group[i] != i:
            i = group[i]
        return i

    for i, row in enumerate(matrix):
        for j, lk in enumerate(row[:i]):
            if lk:
                group[root(i)] = root(j)
    return len({root(i) for i in range(len(matrix))})
