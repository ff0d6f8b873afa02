"""Reading a PD code: the crossing signs and the components it draws (plain Python, for small codes).

PD convention as in :mod:`lkspace.knots.jones`: ``X[i, j, k, l]`` counter-clockwise from the
incoming under edge ``i``; a crossing is positive when the over strand runs ``l -> j``.
"""

from __future__ import annotations

import numpy as np

from ..compiled.loops import UnionFind


def pd_signs(pd: np.ndarray) -> np.ndarray:
    """Return ``(n,) int64`` crossing signs read from a PD code, and raise ``ValueError`` where they are not fixed.

    Each edge runs from the crossing where it is outgoing to the one where it is incoming;
    the under strand fixes this at every crossing (``i`` in, ``k`` out), and each edge
    passes it to its other end and each over strand from one end to the other.  A
    component never under anything is left unoriented by the code; it lies above the
    rest, unlinked from it, so either orientation gives the same Jones polynomial: its
    edges then run as their labels increase.
    """
    n = len(pd)
    incoming = np.full((n, 4), -1, np.int64)  # 1 where the edge of that slot ends, 0 where it starts
    incoming[:, 0] = 1
    incoming[:, 2] = 0
    ends: dict[int, list[tuple[int, int]]] = {}
    for c in range(n):
        for s in range(4):
            ends.setdefault(int(pd[c, s]), []).append((c, s))
    todo = [(c, s) for c in range(n) for s in (0, 2)]
    while True:
        while todo:
            c, s = todo.pop()
            for other_c, other_s in ends[int(pd[c, s])]:
                if (other_c, other_s) != (c, s) and incoming[other_c, other_s] < 0:
                    incoming[other_c, other_s] = 1 - incoming[c, s]
                    todo.append((other_c, other_s))
            opposite = (s + 2) % 4
            if incoming[c, opposite] < 0:
                incoming[c, opposite] = 1 - incoming[c, s]
                todo.append((c, opposite))
        open_slots = [(c, s) for c in range(n) for s in (1, 3) if incoming[c, s] < 0]
        if not open_slots:
            break
        c, s = open_slots[0]
        label, other = int(pd[c, s]), int(pd[c, 4 - s])
        incoming[c, s] = 1 if other == label + 1 or (other < label - 1) else 0
        todo.append((c, s))
    return np.where(incoming[:, 3] == 1, 1, -1).astype(np.int64)


def pd_components(pd: np.ndarray) -> int:
    """Return the number of components of the link a PD code draws (edges joined through crossings)."""
    labels, ends = np.unique(np.asarray(pd, np.int64).reshape(-1, 4), return_inverse=True)
    ends = ends.reshape(-1, 4)
    pieces = UnionFind(len(labels))
    pieces.join_pairs(np.concatenate([ends[:, [0, 2]], ends[:, [1, 3]]]))
    return pieces.pieces
