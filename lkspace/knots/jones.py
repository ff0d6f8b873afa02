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
Past :data:`MAX_FRONTIER` open edges (or :data:`~lkspace.knots.bracket.MAX_STATE_WORDS`), length is -1 and the caller
takes a slower path.  Coefficients are int64 with wrap-around: the state sum and the exact
division by ``A^4 + 1`` are ring operations, valid modulo ``2^64``, and the final
coefficients are small, so the answer is exact.
"""

from __future__ import annotations

import numpy as np

from ..compiled.kernels import helper, kernel
from .bracket import MAX_FRONTIER, read_ends, smoothing_order, state_sum
from .pd_code import pd_components, pd_signs


@helper
def jones_buffer_size(n_crossings: int, n_free: int = 0) -> int:
    """Coefficients :func:`jones_into` may write for ``n_crossings`` crossings and ``n_free`` free circles.

    The span of the bracket of a diagram is at most ``4n`` in ``A`` per connected piece, plus
    4 per extra piece or free circle, so the Jones polynomial spans at most ``4n + 2 n_free``
    powers of ``x``.
    """
    return 4 * n_crossings + 2 * n_free + 1


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
def _jones_of_bracket(
    top: np.ndarray, lo: int, hi: int, offset: int, signs: np.ndarray, n_free: int, out: np.ndarray
) -> tuple[int, int]:
    """Write the Jones polynomial from the state sum's ``top`` (nonzero on ``lo..hi``) into ``out``, as :func:`jones_into`.

    Divides one loop ``d`` out (or, without crossings, starts from 1), multiplies by ``d``
    per free circle and by ``(-A^3)^(-writhe)``, and turns powers of ``A`` into ``x``.
    """
    n = len(signs)
    bracket = np.zeros(2 * offset + 1, np.int64)
    if n > 0:  # divide by d: bracket * (A^2 + A^-2) = -top
        for i in range(hi - 2, lo + 1, -2):
            bracket[i] = -top[i + 2] - bracket[i + 4]
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
    if not read_ends(pd, end_crossing):
        return 0, -2
    order = np.zeros(n, np.int64)
    if smoothing_order(pd, end_crossing, order) > MAX_FRONTIER:
        return 0, -1
    offset = 5 * n + 2 * n_free + 8  # index of A^0: every partial exponent is within +-5n
    if n == 0:
        return _jones_of_bracket(np.zeros(0, np.int64), offset, offset, offset, signs, n_free, out)
    top, lo, hi = state_sum(pd, end_crossing, order, offset)
    if lo < 0:
        return 0, -1
    return _jones_of_bracket(top, lo, hi, offset, signs, n_free, out)


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
