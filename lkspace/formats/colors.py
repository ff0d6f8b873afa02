"""Strand colours: a fixed palette of 12, then golden-ratio hues."""

from __future__ import annotations

import colorsys

import numpy as np

PALETTE = np.array(
    [
        [0.89, 0.10, 0.11],
        [0.12, 0.47, 0.71],
        [0.20, 0.63, 0.17],
        [1.00, 0.50, 0.00],
        [0.42, 0.24, 0.60],
        [0.09, 0.75, 0.81],
        [0.90, 0.67, 0.00],
        [0.65, 0.34, 0.16],
        [0.97, 0.51, 0.75],
        [0.40, 0.40, 0.40],
        [0.55, 0.80, 0.20],
        [0.00, 0.30, 0.55],
    ]
)


def colors(n: int) -> np.ndarray:
    """(n, 3) float64 distinct colours in ``[0, 1]`` (a fixed palette, then golden-ratio hues)."""
    if n <= len(PALETTE):
        return PALETTE[:n].copy()
    extra = [colorsys.hsv_to_rgb((0.618034 * k) % 1.0, 0.75, 0.9) for k in range(n - len(PALETTE))]
    return np.vstack([PALETTE, np.array(extra)])
