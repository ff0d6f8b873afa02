"""Strand colours: 24 well-separated colours, given to strands by a stable key.

A strand's key is the smallest face it visits (:func:`strand_keys`):
strands take the palette's colours in the order of their keys, so the colours do not
depend on how the tracer numbered the strands, and an edit that leaves the strands'
order of keys alone leaves their colours alone.  Past 24 strands, golden-ratio hues.
"""

from __future__ import annotations

import colorsys
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ..geometry.realization import Realization

PALETTE = np.array(
    [
        [0.89, 0.10, 0.11],
        [0.12, 0.47, 0.71],
        [0.20, 0.63, 0.17],
        [1.00, 0.50, 0.00],
        [0.42, 0.24, 0.60],
        [0.00, 0.00, 1.00],
        [1.00, 0.70, 0.70],
        [1.00, 0.00, 0.60],
        [0.40, 0.30, 0.00],
        [0.50, 0.80, 0.70],
        [1.00, 0.00, 1.00],
        [0.50, 0.10, 0.20],
        [0.80, 0.80, 0.00],
        [0.00, 0.30, 0.20],
        [1.00, 0.60, 1.00],
        [0.00, 0.90, 0.00],
        [0.00, 0.40, 1.00],
        [0.80, 0.70, 0.40],
        [0.50, 0.40, 0.40],
        [0.50, 0.10, 0.80],
        [1.00, 0.40, 0.50],
        [0.00, 0.80, 1.00],
        [0.80, 0.70, 0.90],
        [0.60, 0.20, 0.00],
    ]
)
"""(24, 3) RGB in ``[0, 1]``: five ColorBrewer colours, then each next colour the farthest (CIELAB) from
those chosen, among an 11-step RGB grid of lightness 25..80 (readable on white): every pair differs by
a CIELAB distance of at least 32."""


def colors(n: int) -> np.ndarray:
    """(n, 3) float64 distinct colours in ``[0, 1]`` (the palette, then golden-ratio hues)."""
    if n <= len(PALETTE):
        return PALETTE[:n].copy()
    extra = [colorsys.hsv_to_rgb((0.618034 * k) % 1.0, 0.75, 0.9) for k in range(n - len(PALETTE))]
    return np.vstack([PALETTE, np.array(extra)])


def keyed_colors(keys: np.ndarray) -> np.ndarray:
    """(n, 3) colours for strands with integer ``keys`` (module docstring): stable across edits."""
    keys = np.asarray(keys, np.int64)
    rank = np.empty(len(keys), np.int64)
    rank[np.argsort(keys, kind="stable")] = np.arange(len(keys))
    return colors(len(keys))[rank]


def arc_colors(fractions: np.ndarray) -> np.ndarray:
    """(n, 3) colours cycling through the hues along a strand (``fractions`` of its length in ``[0, 1)``)."""
    hues = np.asarray(fractions, np.float64) % 1.0
    return np.array([colorsys.hsv_to_rgb(h, 0.8, 0.85) for h in hues]).reshape(-1, 3)


def strand_keys(real: Realization) -> np.ndarray:
    """(n_strands,) int64: the smallest face each strand visits (its stable colour key)."""
    tr = real.trace
    faces = real.scaffold.corner_face[tr.steps // 2]
    starts = tr.strand_starts[:-1]
    return np.minimum.reduceat(faces, starts) if len(faces) else np.zeros(0, np.int64)


def curve_colors(real: Realization) -> np.ndarray:
    """(max(n_curves, 1), 3) one colour per curve; in a block, per thread class.

    Every copy and cut run of a block's thread class (a strand of the quotient) takes
    its class's colour (by its stable key), so that one thread reads as one colour
    across the cells.
    """
    if real.block is None or not real.n_curves:
        return colors(max(real.n_curves, 1))
    return keyed_colors(strand_keys(real))[real.strand_of]
