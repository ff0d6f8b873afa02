"""The Jones polynomial of a PD code in compiled code: a Kauffman-bracket state sum.

PD convention (KnotTheory, spherogram, regina, :mod:`lkspace.knots.diagram`): ``X[i, j, k, l]``
lists the four edge labels around a crossing counter-clockwise, starting with the incoming
under edge ``i`` (``k`` is the outgoing under edge); labels run over ``1..2n``, consecutively
along each component in its direction.  Signs are +1 for a right-handed (positive) crossing.

The result is regina's ``Link.jones()`` bit for bit: a Laurent polynomial in ``x = t^(1/2)``,
``V(unknot) = 1``, the unlink of ``c`` components ``(-x - 1/x)^(c - 1)``, the positive Hopf
link ``-x - x^5``, the positive (right-handed) trefoil ``x^2 + x^6 - x^8``; ``V = 0`` for the
empty link.

Algorithm: ``V = (-A^3)^(-writhe) <D>`` at ``A = x^(-1/2)``, the bracket smoothing
``X[a, b, c, d]`` to ``A P[a, b] P[c, d] + A^-1 P[a, d] P[b, c]``, each closed loop counting
``d = -A^2 - A^-2`` (one divided out at the end).  Crossings are smoothed one at a time in a
greedy order (next, the one with most edges on the frontier); the *frontier*, the edges with
one end smoothed, is the same for every state, and a state (its pairing by the arcs smoothed
so far, an int64 with 4 bits per frontier position) carries a Laurent polynomial in ``A``.
Past :data:`MAX_FRONTIER` open edges (or :data:`MAX_STATE_WORDS`), length is -1 and the caller
takes a slower path.  Coefficients are int64 with wrap-around: the state sum and the exact
division by ``A^4 + 1`` are ring operations, valid modulo ``2^64``, and the final
coefficients are small, so the answer is exact.
"""

from __future__ import annotations

import numpy as np

from ..kernels import helper, kernel
from .pd_code import pd_components, pd_signs

MAX_FRONTIER = 16
"""Open edge ends a state may pair (4 bits each in an int64 key; the last one is implied)."""

MAX_STATE_WORDS = 1 << 23
"""Cap on states x coefficients held at once (64 MB of int64): beyond it, length -1."""


@helper
def jones_buffer_size(n_crossings: int, n_free: int = 0) -> int:
    """Coefficients :func:`jones_into` may write for ``n_crossings`` crossings and ``n_free`` free circles.

    The span of the bracket of a diagram is at most ``4n`` in ``A`` per connected piece, plus
    4 per extra piece or free circle, so the Jones polynomial spans at most ``4n + 2 n_free``
    powers of ``x``.
    """
    return 4 * n_crossings + 2 * n_free + 1


@helper
def _state_hash(key: int, mask: int) -> int:
    return (key ^ (key >> 11) ^ (key >> 23) ^ (key >> 37) ^ (key >> 49)) & mask


@helper
def _times_d(poly: np.ndarray, lo: int, hi: int) -> None:
    """Multiply ``poly`` (zero outside ``lo..hi``, steps of 2, room 2 on each side) by ``-A^2 - A^-2`` in place."""
    before = 0  # the old coefficient of index i - 2
    for i in range(lo - 2, hi + 3, 2):
        here = poly[i]
        after = poly[i + 2] if i + 2 <= hi else 0
        poly[i] = -(before + after)
        before = here


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
def _smoothing_order(pd: np.ndarray, end_crossing: np.ndarray, order: np.ndarray) -> int:
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
def jones_into(pd: np.ndarray, signs: np.ndarray, n_free: int, out: np.ndarray) -> tuple[int, int]:
    """Write the Jones polynomial of a PD code into ``out``; return ``(lowest, length)``.

    Parameters
    ----------
    pd : (n, 4) int64
        PD code, labels ``1..2n`` (see the module docstring); ``n`` may be 0.
    signs : (n,) int64
        +1 / -1 per crossing (:func:`~lkspace.knots.pd_code.pd_signs` reads them from a code).
    n_free : int
        Components without any crossing (split unknotted circles).
    out : (jones_buffer_size(n, n_free),) int64
        Receives the coefficients of ``x^lowest .. x^(lowest + length - 1)``.

    Returns
    -------
    lowest : int
        Exponent of ``x`` in ``out[0]``.
    length : int
        Coefficients written, no zero at either end; 0 for the empty link; -1 when the
        diagram is beyond the state sum's capacity (frontier wider than
        :data:`MAX_FRONTIER`), -2 for a malformed PD code or ``out`` too short.
    """
    n = pd.shape[0]
    if len(signs) != n or n_free < 0:
        return 0, -2
    if n == 0 and n_free == 0:
        return 0, 0
    end_crossing = np.full((2 * n, 2), -1, np.int64)
    for c in range(n):
        for s in range(4):
            e = pd[c, s] - 1
            if e < 0 or e >= 2 * n or end_crossing[e, 1] >= 0:
                return 0, -2
            end_crossing[e, 1 if end_crossing[e, 0] >= 0 else 0] = c
    order = np.zeros(n, np.int64)
    if _smoothing_order(pd, end_crossing, order) > MAX_FRONTIER:
        return 0, -1
    offset = 5 * n + 2 * n_free + 8  # index of A^0: every partial exponent is within +-5n
    width = 2 * offset + 1
    cap = 4
    keys = np.zeros(cap, np.int64)
    polys = np.empty((cap, width), np.int64)  # row i read on lo..hi only, zeroed around it when made
    next_keys = np.zeros(cap, np.int64)
    next_polys = np.empty((cap, width), np.int64)
    table = np.full(16, -1, np.int64)
    slot_of_state = np.zeros(cap, np.int64)
    n_states = 1
    polys[0, offset] = 1
    lo = hi = offset
    front = np.zeros(MAX_FRONTIER + 4, np.int64)
    next_front = np.zeros(MAX_FRONTIER + 4, np.int64)
    position = np.full(2 * n, -1, np.int64)
    slot_of_position = np.full(MAX_FRONTIER, -1, np.int64)
    renumber = np.full(MAX_FRONTIER, -1, np.int64)
    partner = np.zeros(MAX_FRONTIER, np.int64)
    kind = np.zeros(4, np.int64)  # 0 on the frontier, 1 both ends here, 2 new
    static = np.zeros(4, np.int64)  # frontier position, other slot, or new position
    outer_slot = np.zeros(4, np.int64)
    outer_end = np.zeros(4, np.int64)
    width_now = 0
    for step in range(n):
        c = int(order[step])
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
        if 2 * n_states * width > MAX_STATE_WORDS:
            return 0, -1
        for s in range(4):
            if kind[s] == 0:
                position[pd[c, s] - 1] = -1
        for q in range(width_next):
            front[q] = next_front[q]
            position[front[q]] = q
        if 2 * n_states > cap:
            cap = 4 * n_states
            keys2 = np.zeros(cap, np.int64)
            polys2 = np.empty((cap, width), np.int64)
            for si in range(n_states):
                keys2[si] = keys[si]
                for i in range(lo, hi + 1):
                    polys2[si, i] = polys[si, i]
            keys = keys2
            polys = polys2
            next_keys = np.zeros(cap, np.int64)
            next_polys = np.empty((cap, width), np.int64)
            size = 16
            while size < 2 * cap:
                size *= 2
            table = np.full(size, -1, np.int64)  # a power of 2, at most half full
            slot_of_state = np.zeros(cap, np.int64)
        mask = len(table) - 1
        keep_mask = (1 << (4 * (width_next - 1))) - 1 if width_next > 0 else 0
        n_next = 0
        next_lo = width
        next_hi = -1
        for si in range(n_states):
            key = keys[si]
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
            for flip in (1, 3):  # A P[a, b] P[c, d] (slot s meets s ^ 1), A^-1 P[a, d] P[b, c] (s ^ 3)
                new_key, loops = _smoothed(flip, outer_slot, outer_end, base)
                new_key &= keep_mask
                h = _state_hash(new_key, mask)
                while table[h] >= 0 and next_keys[table[h]] != new_key:
                    h = (h + 1) & mask
                t = table[h]
                if t < 0:
                    t = n_next
                    n_next += 1
                    table[h] = t
                    slot_of_state[t] = h
                    next_keys[t] = new_key
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
    bracket = np.zeros(width, np.int64)
    if n > 0:  # divide by d: bracket * (A^2 + A^-2) = -polys[0]
        for i in range(hi - 2, lo + 1, -2):
            bracket[i] = -polys[0, i + 2] - bracket[i + 4]
        lo += 2
        hi -= 2
        times = n_free
    else:
        bracket[offset] = 1
        times = n_free - 1
    for _ in range(times):
        _times_d(bracket, lo, hi)
        lo -= 2
        hi += 2
    while lo <= hi and bracket[lo] == 0:
        lo += 2
    while lo <= hi and bracket[hi] == 0:
        hi -= 2
    length = (hi - lo) // 2 + 1
    if length > len(out) or lo > hi:
        return 0, -2
    writhe = 0
    for c in range(n):
        writhe += signs[c]
    sign = -1 if writhe % 2 else 1
    for j in range(length):
        out[j] = sign * bracket[hi - 2 * j]
    return -((hi - offset - 3 * writhe) // 2), length


@kernel
def jones_kernel(pd: np.ndarray, signs: np.ndarray, n_free: int, out: np.ndarray) -> tuple[int, int]:
    """:func:`jones_into` as a compiled kernel of its own (what :func:`jones` calls)."""
    return jones_into(pd, signs, n_free, out)


def jones(pd: object, signs: object = None, n_components: int | None = None) -> tuple[int, tuple[int, ...]]:
    """Return the Jones polynomial of a PD code as ``(lowest exponent of x, coefficients)``.

    Parameters
    ----------
    pd : (n, 4) int
        PD code (module docstring); ``[]`` for no crossing.
    signs : (n,) int, optional
        Crossing signs; read from the code when not given (see :func:`pd_signs`).
    n_components : int, optional
        Components of the link, counting those without crossings (default: those of ``pd``).

    Examples
    --------
    >>> jones([[1, 5, 2, 4], [3, 1, 4, 6], [5, 3, 6, 2]])  # right-handed trefoil: x^2 + x^6 - x^8
    (2, (1, 0, 0, 0, 1, 0, -1))
    >>> jones([], n_components=2)  # unlink of two circles: -x^-1 - x
    (-1, (-1, 0, -1))
    """
    code = np.asarray(pd, np.int64).reshape(-1, 4)
    n = len(code)
    if n and sorted(code.ravel().tolist()) != sorted(2 * list(range(1, 2 * n + 1))):
        raise ValueError(f"PD code of {n} crossings: every label 1..{2 * n} must appear exactly twice")
    crossing_signs = pd_signs(code) if signs is None else np.asarray(signs, np.int64)
    if crossing_signs.shape != (n,) or not np.isin(crossing_signs, (-1, 1)).all():
        raise ValueError(f"signs: expected {n} values +1 or -1, got {crossing_signs.tolist()}")
    drawn = pd_components(code) if n else 0
    n_free = 0 if n_components is None else n_components - drawn
    if n_free < 0:
        raise ValueError(f"n_components={n_components}, but the PD code draws {drawn} components")
    out = np.zeros(jones_buffer_size(n, n_free), np.int64)
    lowest, length = jones_kernel(code, crossing_signs, n_free, out)
    if length == -1:
        raise ValueError(f"PD code of {n} crossings: too wide for the state sum (frontier over {MAX_FRONTIER} edges)")
    return int(lowest), tuple(int(v) for v in out[:length])
