"""Escape rounds of a relaxation: a converged shape shaken smoothly, to be relaxed again.

The rope flow of :mod:`~lkspace.geometry.relax` stops in a local minimum of the
ropelength that depends on where it started.  An **escape round** moves every point of
the tightest shape found by a smooth, low-frequency displacement and relaxes the result
again; the relaxation keeps whichever is tighter.  The displacement of a curve is

    d(s) = c * sum over k = 1..MODES of (a_k cos 2 pi k s + b_k sin 2 pi k s) / k,

with ``s`` in ``[0, 1)`` its arc position (a thread class of a periodic design: up to the
point its period moves the first to), ``a_k, b_k`` ``(3,)`` standard normal draws of a
seeded generator, and ``c`` scaling the largest ``|d|`` to :data:`AMPLITUDE` rope radii
``r``, or less where ``d`` would then differ between neighbouring points by more than
:data:`RATE` times their distance (it never does on the curves of a relaxed design,
tens of rope radii long: the modes are slow).

**The link type is kept.**  Every point moves along a straight path to its displaced
position.  Two points of distinct pieces (at least a rope diameter ``2 r`` apart, as the
flow leaves them) close in by at most ``2 x 0.3 r``, so they stay more than ``r`` apart.
Two points of one piece ``a`` apart along it are at least ``a / 1.5`` apart in space (else
they would be distinct pieces, :data:`~lkspace.geometry.flow.FOLD`) and their
displacements differ by at most ``RATE * a = a / 2``, so they never meet either.  The
relaxation after it is the flow, an isotopy.
"""

from __future__ import annotations

import numpy as np

AMPLITUDE = 0.3
"""Largest displacement of an escape round, in rope radii."""

MODES = 3
"""Fourier modes of the displacement along each curve (the lowest ones: 1, 2, 3 turns)."""

RATE = 0.5
"""Most change of the displacement between neighbouring points, per unit of their distance."""


def shaken(
    curves: list[np.ndarray], radius: float, rng: np.random.Generator, offsets: np.ndarray | None = None
) -> list[np.ndarray]:
    """Return ``curves`` displaced smoothly by at most :data:`AMPLITUDE` ``* radius`` (module docstring).

    Parameters
    ----------
    curves : list of (n_k, 3) float64
        Closed polylines (first point not repeated).
    radius : float
        The rope radius the curves carry.
    rng : numpy.random.Generator
        Draws the coefficients, ``(MODES, 2, 3)`` per curve in order.
    offsets : (n_curves, 3) float64 or None
        Each curve closes on its first point moved by its row (thread classes); ``None``: on its first point.

    Examples
    --------
    >>> t = np.linspace(0, 2 * np.pi, 100, endpoint=False)
    >>> ring = np.column_stack([np.cos(t), np.sin(t), 0 * t])
    >>> moved = shaken([ring], 0.5, np.random.default_rng(0))[0]
    >>> bool(np.isclose(np.linalg.norm(moved - ring, axis=1).max(), AMPLITUDE * 0.5))
    True
    """
    out = []
    turns = np.arange(1, MODES + 1)
    for k, curve in enumerate(curves):
        end = curve[:1] if offsets is None else curve[:1] + offsets[k]
        seg = np.linalg.norm(np.diff(np.vstack([curve, end]), axis=0), axis=1)
        s = np.concatenate([[0.0], np.cumsum(seg)[:-1]]) / seg.sum()
        coeffs = rng.standard_normal((MODES, 2, 3)) / turns[:, None, None]
        angles = 2 * np.pi * np.outer(s, turns)
        d = np.cos(angles) @ coeffs[:, 0] + np.sin(angles) @ coeffs[:, 1]
        d *= AMPLITUDE * radius / np.linalg.norm(d, axis=1).max()
        rate = (np.linalg.norm(np.diff(np.vstack([d, d[:1]]), axis=0), axis=1) / seg).max()
        out.append(curve + d * min(1.0, RATE / rate))
    return out
