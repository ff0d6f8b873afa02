"""A rope flow on closed polylines that never lets strands pass through each other.

The curves are a rope of diameter ``D``: two points of **distinct pieces** (on different
curves, or on one curve farther apart along it than 1.5 times their distance: a fold
back, never a gentle bend) should be at least ``D`` apart, and the curvature radius
(circumradius of consecutive point triples) at least ``D / 2``.  Every iteration

1. pulls each point toward the midpoint of its neighbours (curve shortening: smooths
   corners and tightens the rope), more strongly where the curvature radius is below ``D/2``;
2. pushes the points of distinct pieces closer than ``D`` apart along their join;
3. **caps** every point's step to ``min(h / 4, d_i / 3)``, where ``h`` is the point
   spacing and ``d_i`` the distance from the point to the nearest distinct piece
   (found with ``scipy.spatial.cKDTree`` within ``max(D, 4 h)``).  Two points of distinct
   pieces ``d`` apart then move less than ``2 d / 3`` toward each other, and points of one
   piece stay more than ``h / 2`` apart, so along the straight path from old to new
   positions no two segments meet: the flow is an isotopy and cannot change the link type.

Points are resampled uniformly by arc length (onto the current polyline) every few
iterations.  With ``grow`` > 0 the diameter grows by that factor whenever the rope fits
(no overlap, no tight bend): the curves tighten toward a **relaxed** shape of low
ropelength (length / thickness) in the manner of Pierański's SONO algorithm; with
``grow`` = 0 the flow only **smooths** (rounds corners and separates strands to ``D``).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Literal, NamedTuple

import numpy as np
from scipy.spatial import cKDTree

from ..runtime.progress import task

FOLD = 1.5
"""Points on one curve are distinct pieces when farther apart along it than ``FOLD`` times their distance."""

RESAMPLE_EVERY = 5
"""Iterations between uniform resamplings."""

PATIENCE = 400
"""A growing flow stops when its best ropelength has not dropped by 0.1 % in this many iterations."""


@dataclass(frozen=True)
class FlowOptions:
    """Parameters of :func:`rope_flow`.

    Attributes
    ----------
    diameter : float
        Starting rope diameter ``D``.
    points_per_diameter : float
        Resampling density: spacing ``h = D / points_per_diameter``.
    pull : float
        Weight in ``[0, 0.5]`` of the curve-shortening step.
    grow : float
        Relative growth of ``D`` when the rope fits (0: smoothing only).
    iterations : int
        Most iterations.
    time_limit : float or None
        Seconds after which the flow stops (``None``: none).
    """

    diameter: float
    points_per_diameter: float = 8.0
    pull: float = 0.25
    grow: float = 0.0
    iterations: int = 100
    time_limit: float | None = None


@dataclass(frozen=True)
class FlowResult:
    """Curves after :func:`rope_flow` and the rope they carry.

    Attributes
    ----------
    curves : list of (n_k, 3) float64
        Closed polylines (first point not repeated).
    diameter : float
        The rope diameter reached: distinct pieces at least this far apart (sampled)
        and curvature radius at least half of it.
    ropelength : float
        Total length / (``diameter`` / 2).
    iterations : int
        Iterations run.
    """

    curves: list[np.ndarray]
    diameter: float
    ropelength: float
    iterations: int


def resample_closed(curve: np.ndarray, spacing: float, least: int = 12) -> np.ndarray:
    """``(m, 3)`` points about ``spacing`` apart, evenly by arc length, along the closed polyline ``curve``."""
    length = float(_lengths([curve])[0])
    return resample_count(curve, max(least, int(round(length / spacing))))


def resample_count(curve: np.ndarray, n: int) -> np.ndarray:
    """``(n, 3)`` points evenly spaced by arc length along the closed polyline ``curve``."""
    pts = np.vstack([curve, curve[:1]])
    cum = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    s = np.linspace(0.0, cum[-1], max(n, 3), endpoint=False)
    return np.column_stack([np.interp(s, cum, pts[:, i]) for i in range(3)])


@dataclass(frozen=True)
class _Ring:
    """Concatenated closed curves: neighbours, owner and arc position of every point."""

    prev: np.ndarray
    next: np.ndarray
    owner: np.ndarray
    index: np.ndarray
    sizes: np.ndarray
    starts: np.ndarray

    @staticmethod
    def of(curves: list[np.ndarray]) -> _Ring:
        sizes = np.array([len(c) for c in curves], np.int64)
        starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
        owner = np.repeat(np.arange(len(curves)), sizes)
        index = np.arange(int(sizes.sum())) - starts[owner]
        prev = starts[owner] + (index - 1) % sizes[owner]
        nxt = starts[owner] + (index + 1) % sizes[owner]
        return _Ring(prev, nxt, owner, index, sizes, starts)


def circumradii(points: np.ndarray, ring: _Ring) -> np.ndarray:
    """Radius of the circle through every point and its two neighbours, ``(n,)`` (``inf`` if straight)."""
    a, b, c = points[ring.prev], points, points[ring.next]
    ab, bc, ca = (np.linalg.norm(x, axis=1) for x in (b - a, c - b, a - c))
    area2 = np.linalg.norm(np.cross(b - a, c - a), axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(area2 > 1e-14 * ab * bc, ab * bc * ca / (2.0 * area2), np.inf)


class Pairs(NamedTuple):
    """Pairs of flow points on distinct pieces (:func:`distinct_pairs`)."""

    i: np.ndarray
    """(n_pairs,) int64: the first point of each pair"""
    j: np.ndarray
    """(n_pairs,) int64: the second point"""
    d: np.ndarray
    """(n_pairs,) float64: their distance"""


def distinct_pairs(points: np.ndarray, ring: _Ring, lengths: np.ndarray, radius: float) -> Pairs:
    """Return the pairs of points on distinct pieces within ``radius`` (:class:`Pairs`)."""
    pairs = cKDTree(points).query_pairs(radius, output_type="ndarray")
    if not len(pairs):
        return Pairs(np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0))
    i, j = pairs[:, 0], pairs[:, 1]
    d = np.linalg.norm(points[i] - points[j], axis=1)
    oi = ring.owner[i]
    steps = np.abs(ring.index[i] - ring.index[j])
    steps = np.minimum(steps, ring.sizes[oi] - steps)
    along = steps * lengths[oi] / ring.sizes[oi]
    keep = (oi != ring.owner[j]) | (along > FOLD * d)
    return Pairs(i[keep], j[keep], d[keep])


def _lengths(curves: list[np.ndarray]) -> np.ndarray:
    return np.array([np.linalg.norm(np.diff(np.vstack([c, c[:1]]), axis=0), axis=1).sum() for c in curves])


def rope_flow(
    curves: list[np.ndarray], options: FlowOptions, label: Literal["relaxing", "smoothing"] = "relaxing"
) -> FlowResult:
    """Run the rope flow (module docstring) on closed ``curves``; return the best rope found.

    ``label`` names the task in the progress lines.

    With ``grow`` > 0 the result is the iterate of lowest ropelength among those where
    the rope fitted; with ``grow`` = 0 the last iterate.
    """
    diameter = float(options.diameter)
    h = diameter / options.points_per_diameter
    pts_list = [resample_closed(np.asarray(c, np.float64), h) for c in curves]
    best: FlowResult | None = None
    improved = 0
    started = time.monotonic()
    it = 0
    with task(label, total=options.iterations) as step:
        while it < options.iterations:
            if options.time_limit is not None and time.monotonic() - started > options.time_limit:
                break
            if it % RESAMPLE_EVERY == 0:
                h = diameter / options.points_per_diameter
                pts_list = [resample_closed(c, h) for c in pts_list]
                ring = _Ring.of(pts_list)
                points = np.vstack(pts_list)
                lengths = _lengths(pts_list)
            radius = circumradii(points, ring)
            near = distinct_pairs(points, ring, lengths, max(diameter, 4 * h))
            gap = float(near.d.min()) if len(near.d) else max(diameter, 4 * h)
            thick = min(0.5 * gap, float(radius.min()))
            if options.grow > 0:
                rope = float(lengths.sum()) / thick
                if best is None or rope < best.ropelength:
                    if best is None or rope < 0.999 * best.ropelength:
                        improved = it
                    best = FlowResult([p.copy() for p in pts_list], 2 * thick, rope, it)
                if it - improved > PATIENCE:
                    break
                if gap >= 0.98 * diameter and thick >= 0.49 * diameter:
                    diameter *= 1 + options.grow
            move = _step(points, ring, radius, near, diameter, h, options.pull)
            points = points + move
            pts_list = np.split(points, ring.starts[1:])
            lengths = _lengths(pts_list)
            it += 1
            step.advance()
            if it % 50 == 0:
                step.note(f"ropelength {lengths.sum() / (0.5 * diameter):.1f}")
    if best is not None:
        return best
    return FlowResult(pts_list, diameter, float(lengths.sum()) / (0.5 * diameter), it)


def _step(
    points: np.ndarray,
    ring: _Ring,
    radius: np.ndarray,
    pairs: Pairs,
    diameter: float,
    h: float,
    pull: float,
) -> np.ndarray:
    """One capped step ``(n, 3)``: curve shortening, curvature relief and overlap pushes (``pairs``: the close ones)."""
    i, j, d = pairs
    mid = 0.5 * (points[ring.prev] + points[ring.next]) - points
    weight = np.where(radius < 0.5 * diameter, 0.5, pull)
    move = weight[:, None] * mid
    near = np.full(len(points), max(diameter, 4 * h))
    if len(d):
        np.minimum.at(near, i, d)
        np.minimum.at(near, j, d)
        over = d < diameter
        if over.any():
            oi, oj, od = i[over], j[over], d[over]
            unit = (points[oi] - points[oj]) / np.maximum(od, 1e-300)[:, None]
            push = 0.5 * (diameter - od)[:, None] * unit
            count = np.bincount(np.concatenate([oi, oj]), minlength=len(points)).astype(np.float64)
            total = np.zeros_like(points)
            np.add.at(total, oi, push)
            np.add.at(total, oj, -push)
            move += total / np.maximum(count, 1.0)[:, None]
    cap = np.minimum(0.25 * h, near / 3.0)
    size = np.linalg.norm(move, axis=1)
    scale = np.where(size > cap, cap / np.maximum(size, 1e-300), 1.0)
    return move * scale[:, None]


SMOOTH_ITERATIONS, SMOOTH_PULL = 60, 0.1
"""Iterations and curve-shortening weight of the default smoothing (a light touch: the strands keep to their faces)."""


SMOOTH_MAX_POINTS = 50_000
"""Curves that would need more flow points than this are left as constructed (the flow would take seconds)."""


def smooth_curves(curves: list[np.ndarray], diameter: float) -> list[np.ndarray]:
    """Round the corners of closed ``curves`` and spread their distinct pieces to ``diameter``.

    A short :func:`rope_flow` without growth: an isotopy (the link type is kept), and
    the curves move less than ``SMOOTH_ITERATIONS * diameter / 32`` (mostly far less)
    from the construction, so each strand still follows its face.  The curves come back
    evenly spaced at ``diameter / 8`` (the construction's sampling is not kept: finer
    points on the flow's polyline would show its vertices as kinks); curves needing more
    than :data:`SMOOTH_MAX_POINTS` flow points in all are returned unchanged.
    """
    options = FlowOptions(diameter=diameter, pull=SMOOTH_PULL, iterations=SMOOTH_ITERATIONS)
    if float(_lengths(curves).sum()) * options.points_per_diameter / diameter > SMOOTH_MAX_POINTS:
        return curves
    return rope_flow(curves, options, "smoothing").curves


def rope_thickness(curves: list[np.ndarray], points: int = 100) -> float:
    """Rope radius closed ``curves`` carry: the smaller of their least bend and half-gap.

    The curves are resampled at ``points`` per curve on average; the gap is between
    distinct pieces (module docstring).
    """
    h = float(_lengths(curves).sum()) / (points * max(len(curves), 1))
    pts_list = [resample_closed(c, h) for c in curves]
    ring = _Ring.of(pts_list)
    points_all = np.vstack(pts_list)
    radius = float(circumradii(points_all, ring).min())
    d = distinct_pairs(points_all, ring, _lengths(pts_list), 2 * radius).d
    return min(radius, 0.5 * float(d.min())) if len(d) else radius
