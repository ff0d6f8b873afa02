"""Thread classes of a periodic design: closed curves in the periodic cell, up to lattice translation.

A strand of a periodic scaffold's quotient is one **thread class**: a closed loop (period 0)
or one period of an infinite thread, whose point after the last is its first point moved by
the period.  A :class:`Cell` carries the lattice (held fixed) and every class's period, so
that the rope flow (:mod:`~lkspace.geometry.flow`) can smooth and relax the classes with
periodic boundary conditions: neighbours across the curve's end are taken with the period,
and distances between points are taken to every lattice image (:func:`image_pairs`).
:func:`classes_of` takes the classes from a realization's copies and :func:`placed` puts
them back at every copy.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import product
from typing import TYPE_CHECKING

import numpy as np

from .flow_steps import image_shares, point_pairs

if TYPE_CHECKING:
    from ..model.scaffold import Scaffold
    from ..strands.tracing import Trace

__all__ = ["Cell", "cell_of", "classes_of", "image_candidates", "image_pairs", "placed"]


@dataclass(frozen=True, eq=False)
class Cell:
    """The fixed lattice and the periods of the curves flowing in it.

    Attributes
    ----------
    basis : (dim, 3) float64
        Lattice vectors (``dim`` 2 or 3).
    periods : (n_curves, dim) int64
        Lattice translation from each curve's first point to the point after its last
        (0 for a closed loop).
    """

    basis: np.ndarray
    periods: np.ndarray

    def offsets(self) -> np.ndarray:
        """(n_curves, 3) the periods in space."""
        return np.asarray(self.periods, np.float64) @ self.basis


def image_pairs(points: np.ndarray, basis: np.ndarray, radius: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pairs of ``points`` ``(n, 3)`` within ``radius`` of each other's lattice images.

    Returns ``(i, j, m)``: ``(k,)`` int64 twice and ``(k, dim)`` int64, one row per pair
    ``|p_i - p_j - m @ basis| <= radius`` (each unordered pair of images once; ``i == j``
    with ``m != 0`` is a point and its own translate).  The points are wrapped into the
    unit cell and compared with the cell's neighbours as far as ``radius`` reaches.
    """
    inv = np.linalg.pinv(basis)  # (3, dim)
    f = points @ inv
    k = np.floor(f)
    frac, wrapped = f - k, points - k @ basis
    rho = radius * np.linalg.norm(inv, axis=0)  # (dim,) radius in cells along each lattice vector
    reach = (np.floor(rho) + 1).astype(np.int64)
    n, dim = len(points), len(reach)
    # the points and their translates by every t whose first non-zero entry is positive ((i, j, -t) is (j, i, t)),
    # each translate only near the faces t crosses (|frac_i - frac_j - t| <= rho for a pair that meets)
    placed, source, moved = [wrapped], [np.arange(n)], [np.zeros((n, dim), np.int64)]
    for t in product(*[range(-r, r + 1) for r in reach.tolist()]):
        nonzero = [x for x in t if x]
        if not nonzero or nonzero[0] < 0:
            continue
        tt = np.asarray(t, np.float64)
        jj = np.flatnonzero(np.all((frac >= -tt - rho) & (frac <= 1 - tt + rho), axis=1))
        placed.append(wrapped[jj] + tt @ basis)
        source.append(jj)
        moved.append(np.broadcast_to(np.asarray(t, np.int64), (len(jj), dim)))
    i, b = point_pairs(np.vstack(placed), float(radius), n)  # a point with a point or a translate, not two translates
    j = np.concatenate(source)[b]
    m = (k[i] - k[j]).astype(np.int64) + np.vstack(moved)[b]
    return i, j, m


def image_candidates(
    points: np.ndarray, cell: Cell, owner: np.ndarray, index: np.ndarray, sizes: np.ndarray, radius: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Candidate pairs of flow points within ``radius`` of each other's images (:func:`image_pairs`).

    ``owner`` and ``index`` ``(n,)``: each point's curve and place along it; ``sizes``:
    points per curve.  Returns ``(i, j, owner of i, share, shift)``: ``share`` is the
    pair's separation along their thread as a share of its period (``inf`` on distinct
    threads), ``shift`` ``(k, 3)`` the translation of ``j``'s image.  The image
    ``p_j + m @ basis`` is on ``p_i``'s own thread when ``m`` is a whole number ``q`` of
    its period: ``q`` periods further along it (for a loop, ``m = 0``).
    """
    i, j, m = image_pairs(points, cell.basis, radius)
    periods = np.ascontiguousarray(cell.periods, np.int64)
    return (i, j, *image_shares(i, j, m, owner, index, sizes, periods, np.ascontiguousarray(cell.basis, np.float64)))


def classes_of(
    curves: list[np.ndarray], closed: np.ndarray, strand_of: np.ndarray, copy_of: np.ndarray, shifts: np.ndarray
) -> tuple[list[np.ndarray], np.ndarray]:
    """Return the thread classes of copy 0, moved back to translation 0: ``(curves, is_thread)``.

    ``shifts`` ``(n_copies, 3)``: the copies' translations in space.  A thread's curve
    (open, its last point the first moved by the period) loses its last point.
    """
    mine = np.flatnonzero(copy_of == 0)
    order = mine[np.argsort(strand_of[mine], kind="stable")]
    out = [curves[k] - shifts[0] for k in order]
    thread = ~np.asarray(closed, bool)[order]
    return [c[:-1] if t else c for c, t in zip(out, thread.tolist(), strict=True)], thread


def placed(
    classes: list[np.ndarray],
    thread: np.ndarray,
    cell: Cell,
    strand_of: np.ndarray,
    copy_of: np.ndarray,
    shifts: np.ndarray,
) -> list[np.ndarray]:
    """Curves of every copy from the classes: class ``strand_of[k]`` moved by ``shifts[copy_of[k]]``.

    A thread's curve gets its last point back (its first moved by the period), as the
    construction draws one period.
    """
    offsets = cell.offsets()
    whole = [np.vstack([c, c[:1] + offsets[s]]) if thread[s] else c for s, c in enumerate(classes)]
    return [whole[s] + shifts[c] for s, c in zip(strand_of.tolist(), copy_of.tolist(), strict=True)]


def cell_of(scaffold: Scaffold, tr: Trace) -> Cell:
    """Return the :class:`Cell` of a periodic scaffold's lattice and the periods of the trace's strands."""
    assert scaffold.lattice is not None
    return Cell(scaffold.lattice.basis, np.asarray(tr.periods, np.int64))
