"""Smoothing of a periodic design's thread classes in the periodic cell (:mod:`~lkspace.geometry.cell`)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .cell import Cell, cell_of, classes_of, placed
from .flow import SMOOTHING, Ring, Smoothing, closed_lengths, distinct_pairs, resample_closed, smooth_curves
from .tracks import lattice_shift

if TYPE_CHECKING:
    from ..model.scaffold import Scaffold
    from ..strands.tracing import Trace
    from .construction import Curves

__all__ = ["least_gap", "smoothed_classes"]


def least_gap(classes: list[np.ndarray], cell: Cell, spacing: float, radius: float) -> float:
    """Least distance between distinct pieces of the thread classes (to every image), sampled at ``spacing``.

    ``inf`` when none come within ``radius``.
    """
    offsets = cell.offsets()
    pts = [resample_closed(c, spacing, offset=o) for c, o in zip(classes, offsets, strict=True)]
    d = distinct_pairs(np.vstack(pts), Ring.of(pts, cell), closed_lengths(pts, offsets), radius).d
    return float(d.min()) if len(d) else float("inf")


def smoothed_classes(
    scaffold: Scaffold, tr: Trace, built: Curves, diameter: float, check: bool, how: Smoothing = SMOOTHING
) -> list[np.ndarray]:
    """Return the curves of every copy in ``built`` with their thread classes smoothed in the periodic cell.

    :func:`~lkspace.geometry.flow.smooth_curves` (``how``) with the lattice fixed.  With ``check``,
    classes closer than ``diameter / 8`` to themselves or to an image (no embedding to
    start the isotopy from) are left as constructed.
    """
    shifts = lattice_shift(scaffold, built.translations)
    classes, thread = classes_of(built.curves, built.closed, built.strand_of, built.copy_of, shifts)
    cell = cell_of(scaffold, tr)
    if check and least_gap(classes, cell, diameter / 8, diameter) < diameter / 8:
        return built.curves
    smooth = smooth_curves(classes, diameter, cell, how)
    return placed(smooth, thread, cell, built.strand_of, built.copy_of, shifts)
