"""One rope-flow iteration in plain numpy (tests only), the reference of the compiled one.

This is the iteration :func:`lkspace.geometry.flow.rope_flow` ran before it was compiled
(:func:`lkspace.geometry.flow_steps.flow_iteration`), array by array: curvature radii,
the distinct pieces within reach, the rope's growth, the capped step.  It shares the
flow's :class:`~lkspace.geometry.flow.Ring` and candidate lists, not its arithmetic.
"""

from __future__ import annotations

import numpy as np

from lkspace.geometry.flow import Ring, _Near, circumradii


def flow_iteration_numpy(
    points: np.ndarray,
    ring: Ring,
    lengths: np.ndarray,
    near: _Near,
    reach: float,
    diameter: float,
    h: float,
    pull: float,
    grow: float,
) -> tuple[np.ndarray, np.ndarray, float, float, float]:
    """``(new points, new lengths, gap, thickness, diameter)`` as the compiled iteration returns them."""
    radius = circumradii(points, ring)
    pairs = near.within(points, lengths, reach)
    gap = float(pairs.d.min()) if len(pairs.d) else reach
    thick = min(0.5 * gap, float(radius.min()))
    if grow > 0 and gap >= 0.98 * diameter and thick >= 0.49 * diameter:
        diameter *= 1 + grow
    i, j, d = pairs.i, pairs.j, pairs.d
    before, after = ring.neighbours(points)
    move = np.where(radius < 0.5 * diameter, 0.5, pull)[:, None] * (0.5 * (before + after) - points)
    n = len(points)
    nearest = np.full(n, max(diameter, 4 * h))
    close = d < 0.75 * h
    np.minimum.at(nearest, i[close], d[close])
    np.minimum.at(nearest, j[close], d[close])
    over = d < diameter
    oi, oj, od = i[over], j[over], d[over]
    apart = points[oi] - points[oj] - (0 if pairs.shift is None else pairs.shift[over])
    push = (0.5 * (diameter - od) / np.maximum(od, 1e-300))[:, None] * apart
    both = np.concatenate([oi, oj])
    count = np.bincount(both, minlength=n).astype(np.float64)
    signed = np.concatenate([push, -push])
    total = np.column_stack([np.bincount(both, signed[:, k], minlength=n) for k in range(3)])
    move += total / np.maximum(count, 1.0)[:, None]
    cap = np.minimum(0.25 * h, nearest / 3.0)
    size = np.sqrt(np.einsum("ij,ij->i", move, move))
    moved = points + move * np.where(size > cap, cap / np.maximum(size, 1e-300), 1.0)[:, None]
    seg = ring.neighbours(moved)[1] - moved
    new_lengths = np.bincount(ring.owner, np.sqrt(np.einsum("ij,ij->i", seg, seg)), minlength=len(ring.sizes))
    return moved, new_lengths, gap, thick, diameter
