"""The Kauffman bracket's state sum in compiled code: the heart of :mod:`lkspace.knots.jones`.

Crossings are smoothed one at a time in a greedy order (:func:`smoothing_order`: next, the
one with most edges on the frontier); the *frontier*, the edges with one end smoothed, is
the same for every state, and a state (its pairing by the arcs smoothed so far, an int64
with 4 bits per frontier position) carries a Laurent polynomial in ``A``
(:func:`state_sum`).  Each smoothing ``X[a, b, c, d] -> A P[a, b] P[c, d] + A^-1 P[a, d]
P[b, c]`` closes loops counting ``d = -A^2 - A^-2``.  Past :data:`MAX_FRONTIER` open edges
(or :data:`MAX_STATE_WORDS`) the sum gives up.
"""

from __future__ import annotations

import numpy as np

from ..compiled.kernels import helper

MAX_FRONTIER = 16
"""Open edge ends a state may pair (4 bits each in an int64 key; the last one is implied)."""

MAX_STATE_WORDS = 1 << 23
"""Cap on states x coefficients held at once (64 MB of int64): beyond it, length -1."""


@helper
def _state_hash(key: int, mask: int) -> int:
    return (key ^ (key >> 11) ^ (key >> 23) ^ (key >> 37) ^ (key >> 49)) & mask


@helper
def _column_is_zero(polys: np.ndarray, n_states: int, i: int) -> bool:
    for si in range(n_states):
        if polys[si, i] != 0:
            return False
    return True


@helper
def _smoothed(flip: int, outer_slot: np.ndarray, outer_end: np.ndarray, key: int) -> tuple[int, int]:
    """Smooth a crossing: return the state key with the new pairs added, and the loops closed.

    Slot ``s`` meets slot ``s ^ flip`` inside the crossing (``flip`` 1: ``P[a, b] P[c, d]``;
    3: ``P[a, d] P[b, c]``); outside, it meets slot ``outer_slot[s]``, or it ends at frontier
    position ``outer_end[s]`` when that is -1.  Paths between two ends pair them in ``key``
    (4 bits per position); the cycles left are closed loops.
    """
    visited = 0
    for s in range(4):
        if (visited >> s) & 1 or outer_slot[s] >= 0:
            continue
        cur = s
        while True:
            visited |= 1 << cur
            nxt = cur ^ flip
            visited |= 1 << nxt
            if outer_slot[nxt] < 0:
                break
            cur = outer_slot[nxt]
        a = outer_end[s]
        b = outer_end[nxt]
        key |= (b << (4 * a)) | (a << (4 * b))
    loops = 0
    for s in range(4):
        if (visited >> s) & 1:
            continue
        loops += 1
        cur = s
        while not (visited >> cur) & 1:
            visited |= 1 << cur
            nxt = cur ^ flip
            visited |= 1 << nxt
            cur = outer_slot[nxt]
    return key, loops


@helper
def _add_smoothed(dst: np.ndarray, src: np.ndarray, lo: int, hi: int, shift: int, loops: int) -> None:
    """Add ``A^shift d^loops src`` to ``dst`` (``src`` nonzero on ``lo..hi`` in steps of 2, ``loops`` <= 2)."""
    if loops == 0:
        for i in range(lo, hi + 1, 2):
            dst[i + shift] += src[i]
    elif loops == 1:
        for i in range(lo, hi + 1, 2):
            dst[i + shift + 2] -= src[i]
            dst[i + shift - 2] -= src[i]
    else:
        for i in range(lo, hi + 1, 2):
            dst[i + shift + 4] += src[i]
            dst[i + shift] += 2 * src[i]
            dst[i + shift - 4] += src[i]


@helper
def smoothing_order(pd: np.ndarray, end_crossing: np.ndarray, order: np.ndarray) -> int:
    """Fill ``order`` (n,) with the crossings in greedy order; return the widest frontier met.

    Next comes the crossing with most edges on the frontier, then with fewest new ones (an
    edge with both ends at one crossing is neither); the count stops past :data:`MAX_FRONTIER`.
    """
    n = pd.shape[0]
    is_open = np.zeros(2 * n, np.bool_)
    done = np.zeros(n, np.bool_)
    n_open = 0
    widest = 0
    for step in range(n):
        best = -1
        best_score = -100
        for c in range(n):
            if done[c]:
                continue
            score = 0
            for s in range(4):
                e = pd[c, s] - 1
                if is_open[e]:
                    score += 5
                elif end_crossing[e, 0] != end_crossing[e, 1]:
                    score -= 1
            if score > best_score:
                best_score = score
                best = c
        order[step] = best
        done[best] = True
        for s in range(4):
            e = pd[best, s] - 1
            if is_open[e]:
                is_open[e] = False
                n_open -= 1
            elif end_crossing[e, 0] != end_crossing[e, 1]:
                is_open[e] = True
                n_open += 1
        widest = max(widest, n_open)
        if widest > MAX_FRONTIER:
            break
    return widest


@helper
def read_ends(pd: np.ndarray, end_crossing: np.ndarray) -> bool:
    """Fill ``end_crossing`` ``(2n, 2)`` with the crossings at both ends of each edge; ``False`` for a malformed code."""
    n = pd.shape[0]
    for c in range(n):
        for s in range(4):
            e = pd[c, s] - 1
            if e < 0 or e >= 2 * n or end_crossing[e, 1] >= 0:
                return False
            end_crossing[e, 1 if end_crossing[e, 0] >= 0 else 0] = c
    return True


@helper
def _frontier_step(
    pd: np.ndarray,
    c: int,
    end_crossing: np.ndarray,
    front: np.ndarray,
    next_front: np.ndarray,
    position: np.ndarray,
    slot_of_position: np.ndarray,
    renumber: np.ndarray,
    kind: np.ndarray,
    static: np.ndarray,
    width_now: int,
) -> int:
    """Classify the slots of crossing ``c`` and move the frontier past it; return the new frontier's width.

    ``front`` and ``position`` become the new frontier; ``slot_of_position``, ``renumber``,
    ``kind`` and ``static`` describe the step for the states (:func:`state_sum`).
    """
    for q in range(width_now):
        slot_of_position[q] = -1
    for s in range(4):
        e = pd[c, s] - 1
        if position[e] >= 0:
            kind[s] = 0
            static[s] = position[e]
            slot_of_position[position[e]] = s
        elif end_crossing[e, 0] == end_crossing[e, 1]:
            kind[s] = 1
            for r in range(4):
                if r != s and pd[c, r] - 1 == e:
                    static[s] = r
        else:
            kind[s] = 2
    width_next = 0
    for q in range(width_now):
        renumber[q] = -1
        if slot_of_position[q] < 0:
            renumber[q] = width_next
            next_front[width_next] = front[q]
            width_next += 1
    for s in range(4):
        if kind[s] == 2:
            static[s] = width_next
            next_front[width_next] = pd[c, s] - 1
            width_next += 1
    for s in range(4):
        if kind[s] == 0:
            position[pd[c, s] - 1] = -1
    for q in range(width_next):
        front[q] = next_front[q]
        position[front[q]] = q
    return width_next


@helper
def _outer_links(
    key: int,
    width_now: int,
    partner: np.ndarray,
    renumber: np.ndarray,
    slot_of_position: np.ndarray,
    kind: np.ndarray,
    static: np.ndarray,
    outer_slot: np.ndarray,
    outer_end: np.ndarray,
) -> int:
    """Read a state's pairing ``key`` around the crossing: fill ``outer_slot``, ``outer_end``; return the kept pairs.

    The kept pairs are those between positions that stay on the frontier, renumbered (a key).
    """
    if width_now > 0:
        partner[width_now - 1] = -1
        for q in range(width_now - 1):
            partner[q] = (key >> (4 * q)) & 15
            if partner[q] == width_now - 1:
                partner[width_now - 1] = q
    base = 0
    for q in range(width_now):
        r = partner[q]
        if renumber[q] >= 0 and renumber[r] >= 0:
            base |= renumber[r] << (4 * renumber[q])
    for s in range(4):
        if kind[s] == 2:
            outer_slot[s] = -1
            outer_end[s] = static[s]
        elif kind[s] == 1:
            outer_slot[s] = static[s]
        else:
            r = partner[static[s]]
            outer_slot[s] = slot_of_position[r]
            outer_end[s] = renumber[r]
    return base


@helper
def _row_of(table: np.ndarray, keys: np.ndarray, slot_of_state: np.ndarray, key: int, n_rows: int) -> tuple[int, int]:
    """Return the row of state ``key`` (in the open-addressing ``table`` over ``keys``) and the rows now used.

    A new key takes row ``n_rows`` (the caller zeroes its polynomial); ``slot_of_state``
    keeps its slot in ``table``, to clear it.
    """
    mask = len(table) - 1
    h = _state_hash(key, mask)
    while table[h] >= 0 and keys[table[h]] != key:
        h = (h + 1) & mask
    t = table[h]
    if t >= 0:
        return t, n_rows
    table[h] = n_rows
    slot_of_state[n_rows] = h
    keys[n_rows] = key
    return n_rows, n_rows + 1


@helper
def _grown(
    keys: np.ndarray, polys: np.ndarray, n_states: int, lo: int, hi: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Return room for ``4 n_states`` states: ``keys`` and ``polys`` copied, empty next ones, a hash table, its slots.

    The table's size is a power of 2, at most half full.
    """
    cap = 4 * n_states
    width = polys.shape[1]
    keys2 = np.zeros(cap, np.int64)
    polys2 = np.empty((cap, width), np.int64)
    for si in range(n_states):
        keys2[si] = keys[si]
        for i in range(lo, hi + 1):
            polys2[si, i] = polys[si, i]
    size = 16
    while size < 2 * cap:
        size *= 2
    next_keys = np.zeros(cap, np.int64)
    next_polys = np.empty((cap, width), np.int64)
    return keys2, polys2, next_keys, next_polys, np.full(size, -1, np.int64), np.zeros(cap, np.int64)


@helper
def state_sum(pd: np.ndarray, end_crossing: np.ndarray, order: np.ndarray, offset: int) -> tuple[np.ndarray, int, int]:
    """Smooth the crossings in ``order``: return the one state's polynomial in ``A`` (``A^0`` at ``offset``), ``lo, hi``.

    Nonzero on ``lo..hi`` in steps of 2; ``lo`` is -1 past :data:`MAX_STATE_WORDS`.

    The frontier: ``front[q]`` the edge at position ``q`` (``next_front`` after the step),
    ``position[e]`` the position of edge ``e`` (-1 off the frontier); per position,
    ``slot_of_position`` (the crossing's slot on it, -1), ``renumber`` (its position after
    the step, -1 if it closes), ``partner`` (the position a state pairs it with); per slot
    of the crossing, ``kind`` (0 on the frontier, 1 both ends here, 2 new), ``static``
    (frontier position, other slot, or new position), ``outer_slot`` and ``outer_end``
    (:func:`_smoothed`).  They are arrays apart, not a NamedTuple: a tuple passed to a
    helper per state cost twice the time (reference counts of its arrays at every call).
    """
    n = pd.shape[0]
    width = 2 * offset + 1
    keys = np.zeros(4, np.int64)
    polys = np.empty((4, width), np.int64)  # row i read on lo..hi only, zeroed around it when made
    next_keys = np.zeros(4, np.int64)
    next_polys = np.empty((4, width), np.int64)
    table = np.full(16, -1, np.int64)
    slot_of_state = np.zeros(4, np.int64)
    n_states = 1
    polys[0, offset] = 1
    lo = hi = offset
    front = np.zeros(MAX_FRONTIER + 4, np.int64)
    next_front = np.zeros(MAX_FRONTIER + 4, np.int64)
    position = np.full(2 * n, -1, np.int64)
    slot_of_position = np.full(MAX_FRONTIER, -1, np.int64)
    renumber = np.full(MAX_FRONTIER, -1, np.int64)
    partner = np.zeros(MAX_FRONTIER, np.int64)
    kind = np.zeros(4, np.int64)
    static = np.zeros(4, np.int64)
    outer_slot = np.zeros(4, np.int64)
    outer_end = np.zeros(4, np.int64)
    width_now = 0
    for step in range(n):
        if 2 * n_states * width > MAX_STATE_WORDS:
            return polys[0], -1, -1
        c = int(order[step])
        width_next = _frontier_step(
            pd, c, end_crossing, front, next_front, position, slot_of_position, renumber, kind, static, width_now
        )
        if 2 * n_states > len(keys):
            keys, polys, next_keys, next_polys, table, slot_of_state = _grown(keys, polys, n_states, lo, hi)
        keep_mask = (1 << (4 * (width_next - 1))) - 1 if width_next > 0 else 0
        n_next = 0
        next_lo = width
        next_hi = -1
        for si in range(n_states):
            base = _outer_links(
                keys[si], width_now, partner, renumber, slot_of_position, kind, static, outer_slot, outer_end
            )
            for flip in (1, 3):  # A P[a, b] P[c, d] (slot s meets s ^ 1), A^-1 P[a, d] P[b, c] (s ^ 3)
                new_key, loops = _smoothed(flip, outer_slot, outer_end, base)
                t, n_used = _row_of(table, next_keys, slot_of_state, new_key & keep_mask, n_next)
                if n_used > n_next:
                    n_next = n_used
                    for i in range(max(lo - 6, 0), min(hi + 7, width)):
                        next_polys[t, i] = 0
                shift = 2 - flip
                _add_smoothed(next_polys[t], polys[si], lo, hi, shift, loops)
                next_lo = min(next_lo, lo + shift - 2 * loops)
                next_hi = max(next_hi, hi + shift + 2 * loops)
        for t in range(n_next):
            table[slot_of_state[t]] = -1
        keys, next_keys = next_keys, keys
        polys, next_polys = next_polys, polys
        n_states = n_next
        width_now = width_next
        lo = next_lo
        hi = next_hi
        while lo <= hi and _column_is_zero(polys, n_states, lo):
            lo += 2
        while lo <= hi and _column_is_zero(polys, n_states, hi):
            hi -= 2
    return polys[0], lo, hi
