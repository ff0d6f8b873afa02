"""Slow references for the diagram's candidate search (tests only): every pair is compared.

:func:`near_pairs_every` applies the circle test of :func:`lkspace.knots.diagram.near_pairs`
to all pairs, with the same arithmetic (so ties come out alike); :func:`box_pairs_every`
compares boxes in plain Python.
"""

from __future__ import annotations

import numpy as np


def near_pairs_every(p0: np.ndarray, p1: np.ndarray) -> set[tuple[int, int]]:
    """Pairs ``i < j`` of segments ``p0 -> p1`` whose projected circles meet, from all pairs."""
    a2, b2 = p0[:, :2], p1[:, :2]
    mid = 0.5 * (a2 + b2)
    half = 0.5 * np.linalg.norm(b2 - a2, axis=1)
    i, j = np.triu_indices(len(mid), 1)
    near = np.linalg.norm(mid[i] - mid[j], axis=1) <= half[i] + half[j]
    return set(zip(i[near].tolist(), j[near].tolist(), strict=True))


def box_pairs_every(low: list[list[float]], high: list[list[float]]) -> set[tuple[int, int]]:
    """Pairs ``i < j`` of closed boxes ``low[k]..high[k]`` that overlap, from all pairs."""
    return {
        (i, j)
        for i in range(len(low))
        for j in range(i + 1, len(low))
        if all(low[i][d] <= high[j][d] and low[j][d] <= high[i][d] for d in range(2))
    }
