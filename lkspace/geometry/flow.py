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
   (found on a grid within ``max(D, 4 h)``).  Two points of distinct
   pieces ``d`` apart then move less than ``2 d / 3`` toward each other, and points of one
   piece stay more than ``h / 2`` apart, so along the straight path from old to new
   positions no two segments meet: the flow is an isotopy and cannot change the link type.

Points are resampled uniformly by arc length (onto the current polyline) every few
iterations.  With ``grow`` > 0 the diameter grows by that factor whenever the rope fits
(no overlap, no tight bend): the curves tighten toward a **relaxed** shape of low
ropelength (length / thickness) in the manner of Pierański's SONO algorithm; with
``grow`` = 0 the flow only **smooths** (rounds corners and separates strands to ``D``).

Given a :class:`~lkspace.geometry.cell.Cell` (a fixed lattice and every curve's period),
the curves are the thread classes of a periodic design: a curve's point after its last is
its first moved by its period, and distances are taken to every lattice image (periodic
boundary conditions); without one, the curves are closed polylines in space.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace
from typing import Literal, NamedTuple

import numpy as np

from ..runtime.progress import task
from .cell import Cell, image_candidates
from .flow_steps import flow_candidates, flow_iteration, load_kernels, resample_ring

FOLD = 1.5
"""Points on one curve are distinct pieces when farther apart along it than ``FOLD`` times their distance."""

RESAMPLE_EVERY = 5
"""Iterations between uniform resamplings."""

RESAMPLE_LEAST = 12
"""Fewest points a curve is resampled to."""

WINDOW = 400
"""A growing flow has converged when its best ropelength dropped by less than :data:`TOLERANCE` over this many iterations."""

TOLERANCE = 1e-3
"""Relative drop of the best ropelength over :data:`WINDOW` iterations below which a growing flow has converged."""

Stop = Literal["converged", "steps", "time"]
"""Why a flow stopped: its ropelength converged, or it reached its step or time limit first."""


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
        Seconds after which the flow stops early (``None``: none, the default, so that
        the result depends on the input only, never on the machine's load).
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
    stopped : {"converged", "steps", "time"}
        Why the flow stopped (:data:`Stop`; a flow without growth runs all its iterations: ``"steps"``).
    """

    curves: list[np.ndarray]
    diameter: float
    ropelength: float
    iterations: int
    stopped: Stop = "steps"


def resample_closed(
    curve: np.ndarray, spacing: float, least: int = RESAMPLE_LEAST, offset: np.ndarray | None = None
) -> np.ndarray:
    """``(m, 3)`` points about ``spacing`` apart, evenly by arc length, along the closed polyline ``curve``.

    ``offset`` ``(3,)``: the curve closes on its first point moved by it (a thread's period).
    """
    length = float(closed_lengths([curve], None if offset is None else offset[None])[0])
    return resample_count(curve, max(least, int(round(length / spacing))), offset)


def resample_count(curve: np.ndarray, n: int, offset: np.ndarray | None = None) -> np.ndarray:
    """``(n, 3)`` points evenly spaced by arc length along the closed polyline ``curve`` (``offset``: as above)."""
    pts = np.vstack([curve, curve[:1] if offset is None else curve[:1] + offset])
    cum = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    s = np.linspace(0.0, cum[-1], max(n, 3), endpoint=False)
    return np.column_stack([np.interp(s, cum, pts[:, i]) for i in range(3)])


@dataclass(frozen=True)
class Ring:
    """Concatenated closed curves: neighbours, owner and arc position of every point (``cell``: thread classes)."""

    prev: np.ndarray
    next: np.ndarray
    owner: np.ndarray
    index: np.ndarray
    sizes: np.ndarray
    starts: np.ndarray
    cell: Cell | None = None
    before: np.ndarray | None = None
    """(n, 3): added to a point's previous neighbour (minus the period at a thread's first point)"""
    after: np.ndarray | None = None
    """(n, 3): added to a point's next neighbour (the period at a thread's last point)"""

    @staticmethod
    def of(curves: list[np.ndarray], cell: Cell | None = None) -> Ring:
        """Ring of the closed ``curves`` (``cell``: thread classes in it)."""
        return Ring.of_sizes(np.array([len(c) for c in curves], np.int64), cell)

    @staticmethod
    def of_sizes(sizes: np.ndarray, cell: Cell | None = None) -> Ring:
        """Ring of closed curves of ``sizes`` points, concatenated (``cell``: thread classes in it)."""
        starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
        owner = np.repeat(np.arange(len(sizes)), sizes)
        index = np.arange(int(sizes.sum())) - starts[owner]
        prev = starts[owner] + (index - 1) % sizes[owner]
        nxt = starts[owner] + (index + 1) % sizes[owner]
        if cell is None:
            return Ring(prev, nxt, owner, index, sizes, starts)
        before, after = np.zeros((len(owner), 3)), np.zeros((len(owner), 3))
        offsets = cell.offsets()
        before[starts] = -offsets
        after[starts + sizes - 1] = offsets
        return Ring(prev, nxt, owner, index, sizes, starts, cell, before, after)

    def frame(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """``(prev, next, before, after, owner)`` for :func:`~lkspace.geometry.flow_steps.flow_iteration` (zero periods without a cell)."""
        zeros = np.zeros((len(self.prev), 3))
        before = zeros if self.before is None else self.before
        after = zeros if self.after is None else self.after
        return self.prev, self.next, before, after, self.owner

    def neighbours(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Previous and next neighbour of every point, ``(n, 3)`` each (across a thread's period)."""
        if self.before is None or self.after is None:
            return points[self.prev], points[self.next]
        return points[self.prev] + self.before, points[self.next] + self.after


def circumradii(points: np.ndarray, ring: Ring) -> np.ndarray:
    """Radius of the circle through every point and its two neighbours, ``(n,)`` (``inf`` if straight)."""
    (a, c), b = ring.neighbours(points), points
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
    shift: np.ndarray | None = None
    """(n_pairs, 3) float64: the lattice translation of ``j``'s image (``None`` without a cell)"""


class _Near(NamedTuple):
    """Candidate pairs of flow points, with what tells distinct pieces apart (:meth:`within`)."""

    i: np.ndarray
    j: np.ndarray
    owner: np.ndarray
    """(m,) int64: the curve of ``i``"""
    share: np.ndarray
    """(m,) float64: the points' separation along their curve as a share of its length (``inf``: two curves)"""
    shift: np.ndarray | None = None
    """(m, 3) float64: the lattice translation of ``j``'s image (``None`` without a cell)"""

    def arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """``(i, j, owner, share, shift)`` for :func:`~lkspace.geometry.flow_steps.flow_iteration` (``shift`` ``(0, 3)`` if none)."""
        shift = np.zeros((0, 3)) if self.shift is None else self.shift
        return self.i, self.j, self.owner, self.share, shift

    def within(self, points: np.ndarray, lengths: np.ndarray, radius: float) -> Pairs:
        """Return the candidates on distinct pieces within ``radius`` (:class:`Pairs`); ``lengths``: of the curves."""
        diff = points[self.i] - points[self.j]
        if self.shift is not None:
            diff -= self.shift
        d2 = np.einsum("ij,ij->i", diff, diff)
        m = d2 <= radius * radius
        d = np.sqrt(d2[m])
        keep = self.share[m] * lengths[self.owner[m]] > FOLD * d
        shift = None if self.shift is None else self.shift[m][keep]
        return Pairs(self.i[m][keep], self.j[m][keep], d[keep], shift)


def _candidates(points: np.ndarray, ring: Ring, radius: float) -> _Near:
    """Pairs of ``points`` within ``radius`` (of each other's lattice images, with a cell) as :class:`_Near`."""
    if ring.cell is not None:
        return _Near(*image_candidates(points, ring.cell, ring.owner, ring.index, ring.sizes, radius))
    return _Near(*flow_candidates(points, radius, ring.owner, ring.index, ring.sizes))


def distinct_pairs(points: np.ndarray, ring: Ring, lengths: np.ndarray, radius: float) -> Pairs:
    """Return the pairs of points on distinct pieces within ``radius`` (:class:`Pairs`)."""
    return _candidates(points, ring, radius).within(points, lengths, radius)


def closed_lengths(curves: list[np.ndarray], offsets: np.ndarray | None = None) -> np.ndarray:
    """Length of every closed curve ``(n,)``; ``offsets`` ``(n, 3)``: each closes on its first point moved by it."""
    ends = [c[:1] if offsets is None else c[:1] + offsets[k] for k, c in enumerate(curves)]
    return np.array([np.linalg.norm(np.diff(np.vstack([c, e]), axis=0), axis=1).sum() for c, e in zip(curves, ends)])


def _ring_lengths(points: np.ndarray, ring: Ring) -> np.ndarray:
    """Length of every closed curve of the concatenated ``points`` ``(n_curves,)``."""
    seg = ring.neighbours(points)[1] - points
    return np.bincount(ring.owner, np.sqrt(np.einsum("ij,ij->i", seg, seg)), minlength=len(ring.sizes))


def _neighbour_list(points: np.ndarray, ring: Ring, reach: float, steps: int, h: float, grow: float) -> _Near:
    """Return the pairs of ``points`` that may come within ``reach`` in the next ``steps`` steps.

    A step moves a point at most ``h / 4`` (the cap of :func:`~lkspace.geometry.flow_steps.flow_iteration`), so two points close
    in by at most ``h / 2`` per step; the reach itself grows with the diameter, by at
    most ``(1 + grow)`` per step.
    """
    return _candidates(points, ring, reach * (1 + grow) ** steps + 0.5 * h * steps)


def rope_flow(
    curves: list[np.ndarray],
    options: FlowOptions,
    label: Literal["relaxing", "smoothing"] = "relaxing",
    cell: Cell | None = None,
) -> FlowResult:
    """Run the rope flow (module docstring) on closed ``curves``; return the best rope found.

    ``label`` names the task in the progress lines; ``cell``: the curves are thread
    classes in it (module docstring; the lattice stays fixed).

    With ``grow`` > 0 the result is the iterate of lowest ropelength among those where
    the rope fitted, and the flow stops when it has **converged**: its best ropelength
    dropped by less than :data:`TOLERANCE` (relative) over the last :data:`WINDOW`
    iterations; else at ``options.iterations`` or ``options.time_limit`` (``stopped``
    says which).  With ``grow`` = 0 the last iterate after all the iterations.  The
    result depends on the curves and options only (a time limit only stops early).
    """
    diameter = float(options.diameter)
    h = diameter / options.points_per_diameter
    offsets = np.zeros((len(curves), 3)) if cell is None else np.ascontiguousarray(cell.offsets(), np.float64)
    given = Ring.of(curves, cell)
    points, sizes = resample_ring(
        np.vstack(curves).astype(np.float64), given.starts, given.sizes, offsets, h, RESAMPLE_LEAST
    )
    ring = Ring.of_sizes(sizes, cell)
    best: FlowResult | None = None
    anchor, anchored = np.inf, 0  # the best ropelength when it last dropped by TOLERANCE, and the iteration
    stopped: Stop = "steps"
    deadline = None if options.time_limit is None else time.monotonic() + options.time_limit
    it = 0
    load_kernels()
    with task(label, total=options.iterations) as step:
        while it < options.iterations:
            if it and deadline is not None and time.monotonic() > deadline:  # a step at least
                stopped = "time"
                break
            if it % RESAMPLE_EVERY == 0:
                h = diameter / options.points_per_diameter
                points, sizes = resample_ring(points, ring.starts, ring.sizes, offsets, h, RESAMPLE_LEAST)
                ring = Ring.of_sizes(sizes, cell)
                lengths = _ring_lengths(points, ring)
                # the list serves this iteration and the next RESAMPLE_EVERY - 1: as many steps
                candidates = _neighbour_list(
                    points, ring, max(diameter, 4 * h), RESAMPLE_EVERY - 1, h, options.grow
                ).arrays()
                frame = ring.frame()
            moved, moved_lengths, gap, thick, grown = flow_iteration(
                points,
                *frame,
                lengths,
                *candidates,
                max(diameter, 4 * h),
                diameter,
                h,
                options.pull,
                options.grow,
                FOLD,
            )
            if options.grow > 0:
                rope = float(lengths.sum()) / thick
                if best is None or rope < best.ropelength:
                    best = FlowResult(np.split(points.copy(), ring.starts[1:]), 2 * thick, rope, it)
                if rope < (1 - TOLERANCE) * anchor:
                    anchor, anchored = rope, it
                if it - anchored >= WINDOW:
                    stopped = "converged"
                    break
            points, lengths, diameter = moved, moved_lengths, grown
            it += 1
            step.advance()
            if it % 50 == 0:
                step.note(f"ropelength {(best.ropelength if best else lengths.sum() / (0.5 * diameter)):.1f}")
    if best is not None:
        return replace(best, iterations=it, stopped=stopped)
    curves_out = np.split(points, ring.starts[1:])
    return FlowResult(curves_out, diameter, float(lengths.sum()) / (0.5 * diameter), it, stopped)


class Smoothing(NamedTuple):
    """How :func:`smooth_curves` smooths: its flow's iterations and curve-shortening weight, and the most flow points."""

    iterations: int
    pull: float
    max_points: int


SMOOTHING = Smoothing(90, 0.5, 33_000)
"""The default smoothing: enough iterations at the full curve-shortening weight to round the
construction's corners and curls at the rope's diameter
(:func:`~lkspace.geometry.params.smooth_diameter`), too few to draw the strands off their
faces.  Curves that would need more flow points are left as constructed (the flow would take
seconds; the work of 50,000 points at 60 iterations)."""


def smooth_curves(
    curves: list[np.ndarray], diameter: float, cell: Cell | None = None, how: Smoothing = SMOOTHING
) -> list[np.ndarray]:
    """Round the corners of closed ``curves`` and spread their distinct pieces to ``diameter``.

    A short :func:`rope_flow` without growth (``how``): an isotopy (the link type is
    kept), and the curves move less than ``how.iterations * diameter / 32`` (mostly far
    less) from the construction, so each strand still follows its face.  The curves come
    back evenly spaced at ``diameter / 8`` (the construction's sampling is not kept: finer
    points on the flow's polyline would show its vertices as kinks); curves needing more
    than ``how.max_points`` flow points in all are returned unchanged.  ``cell``: the
    curves are thread classes in it (module docstring).
    """
    options = FlowOptions(diameter=diameter, pull=how.pull, iterations=how.iterations)
    offsets = None if cell is None else cell.offsets()
    if float(closed_lengths(curves, offsets).sum()) * options.points_per_diameter / diameter > how.max_points:
        return curves
    return rope_flow(curves, options, "smoothing", cell).curves


def rope_thickness(curves: list[np.ndarray], points: int = 100, cell: Cell | None = None) -> float:
    """Rope radius closed ``curves`` carry: the smaller of their least bend and half-gap.

    The curves are resampled at ``points`` per curve on average; the gap is between
    distinct pieces (module docstring; ``cell``: the curves are thread classes in it).
    """
    offsets = None if cell is None else cell.offsets()
    h = float(closed_lengths(curves, offsets).sum()) / (points * max(len(curves), 1))
    pts_list = [resample_closed(c, h, offset=None if offsets is None else offsets[k]) for k, c in enumerate(curves)]
    ring = Ring.of(pts_list, cell)
    points_all = np.vstack(pts_list)
    radius = float(circumradii(points_all, ring).min())
    d = distinct_pairs(points_all, ring, closed_lengths(pts_list, offsets), 2 * radius).d
    return min(radius, 0.5 * float(d.min())) if len(d) else radius
