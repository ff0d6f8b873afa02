"""The few simplest designs of one atlas type, kept as the designs stream by.

Simplest: smallest ``sum |t|``, then fewest non-zero labels, then smallest largest
``|t|``, then the labels themselves (so the choice does not depend on the order the
designs come in).  Up to ``k`` are kept for each chirality identify reports (the
table's diagram, its mirror, not told apart), so a lookup of ``m3_1`` finds mirror
images even where the table's chirality is as simple.
"""

from __future__ import annotations

import bisect
from dataclasses import dataclass, field

import numpy as np

from .records import DesignRecord, Example

EXAMPLES = 5
"""Designs kept per chirality of a type (:attr:`Examples.k`)."""

Key = tuple[tuple[int, int, int], tuple[int, ...]]


def costs(labels_2d: np.ndarray) -> list[tuple[int, int, int]]:
    """Each design's cost ``(sum |t|, non-zero labels, largest |t|)``, for ``labels_2d`` ``(n, n_edges)`` at once."""
    a = np.abs(np.asarray(labels_2d, np.int64))
    return list(zip(a.sum(axis=1).tolist(), (a != 0).sum(axis=1).tolist(), a.max(axis=1, initial=0).tolist()))


@dataclass
class Examples:
    """The ``k`` simplest designs of each chirality of a type, with what the atlas knows of them."""

    k: int = EXAMPLES
    kept: dict[str, list[tuple[Key, Example]]] = field(default_factory=dict)

    def add(self, labels: np.ndarray, cost: tuple[int, int, int], rec: DesignRecord) -> None:
        """Offer one design (``cost``: sum |t|, non-zero labels, largest |t|; ``rec``: its identification)."""
        mirror = rec.mirror
        side = "undetermined" if mirror is None else "mirror" if mirror else "table"
        row = self.kept.setdefault(side, [])
        full = len(row) >= self.k
        if full and cost > row[-1][0][0]:  # the common case in a big space: not among the simplest
            return
        key: Key = (cost, tuple(int(x) for x in labels))
        if full and key >= row[-1][0]:
            return
        example = Example(key[1], cost[0], cost[1], rec.crossings, mirror)
        bisect.insort(row, (key, example), key=lambda item: item[0])
        del row[self.k :]

    def records(self) -> tuple[Example, ...]:
        """Return the kept designs, simplest first."""
        every = sorted((item for row in self.kept.values() for item in row), key=lambda item: item[0])
        return tuple(example for _, example in every)
