"""Relaxation: the strands of a realization drawn tight, without changing the link type.

:func:`relax` runs the rope flow of :mod:`~lkspace.geometry.flow` with a growing rope
diameter (Pierański's SONO: shrink on no overlaps): the curves shorten while their distinct
pieces are kept a rope's width apart, and every step is capped so that no strand passes
through another.  The flow runs until it **converges** (its best ropelength drops by less
than 0.1% over 400 steps), or stops early at a step or time limit, which
:class:`Relaxation` records.  A **fine** relaxation then runs the flow on from the
converged shape at twice the resolution until it converges again, twice (the second time
with gentler curve shortening): the first flow's minimum is partly an artefact of its
sampling, and the refined one is tighter (by 0.3-3%); ``points`` samples the last fine
pass more finely still.  **Escape rounds** (:mod:`~lkspace.geometry.escape`) then shake the
tightest shape found smoothly, relax it again the same way and keep it if it came out
tighter: the flow's minimum depends on where it starts.  Without a time limit the result
depends on the design (and the escape rounds' seed) only: the same bytes at any load.  The result is scaled back to the realization's size and
centre; its tube radius is the rope's (the tube fills the space the relaxation found).

A periodic scaffold's thread classes (:mod:`~lkspace.geometry.cell`) are relaxed in the
periodic cell with the lattice fixed: every copy of a class takes its relaxed shape, the
rope grows as far as the fixed cell lets it, and nothing is rescaled.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from ..errors import GeometryError
from .clearance import check_embedding
from .flow import FlowOptions, FlowResult, Smoothing, Stop, rope_flow, rope_thickness, smooth_curves

if TYPE_CHECKING:
    from .cell import Cell
    from .realization import Realization

START, START_DIAMETER = Smoothing(60, 0.1, 50_000), 1.5
"""A relaxation starts from the construction smoothed lightly: a rope of 1.5 insets, 60 steps at
curve-shortening weight 0.1 (the default smoothing before issue 34).  The flow's minimum depends
on its start, and the shipped ideal shapes (:mod:`~lkspace.linktypes.ideal_shapes`) were found
from this one; the default smoothing's rounder curves relax to other minima (10_3: 1.12 x its
ideal ropelength instead of 1.04 x)."""

RELAX_STEPS = 50_000
"""Default most steps: far beyond what the designs of the atlas need to converge (hundreds to a few thousand)."""

GROW = 0.004
"""Relative growth of the rope diameter per fitting iteration."""

TUBE_FILL = 0.9
"""Tube radius of the relaxed curves, in rope radii."""

FINE_PASSES = ((16.0, 0.25), (16.0, 0.1))
"""The fine passes: flow points per rope diameter (the first pass: 8) and curve-shortening
weight (the first pass: 0.25) of each."""

FINE_START = 0.95
"""A fine pass starts at this share of the rope diameter the pass before it reached."""

FINE_POINTS = (16, 64)
"""Least and most flow points per rope diameter of the last fine pass (``points``; the least is the default)."""


@dataclass(frozen=True)
class Relaxation:
    """How a relaxation ended (``Realization.relaxation``).

    Attributes
    ----------
    steps : int
        Flow steps run.
    stopped : {"converged", "steps", "time"}
        ``"converged"``: the ropelength settled; ``"steps"`` or ``"time"``: the step or time
        limit stopped it first (the curves are tighter than before, not as tight as they get).
    ropelength : float
        Length / rope radius of the relaxed curves, as the flow measured it (sampled).
    """

    steps: int
    stopped: Stop
    ropelength: float

    @property
    def converged(self) -> bool:
        """Whether the ropelength settled before any limit."""
        return self.stopped == "converged"

    def to_json(self) -> dict[str, object]:
        """Return ``{"steps", "converged", "stopped", "ropelength"}``."""
        return {
            "steps": self.steps,
            "converged": self.converged,
            "stopped": self.stopped,
            "ropelength": self.ropelength,
        }

    def note(self) -> str | None:
        """One line saying the relaxation stopped at a limit before converging; ``None`` when it converged."""
        if self.converged:
            return None
        return (
            f"relax stopped at its {'step' if self.stopped == 'steps' else 'time'} limit after {self.steps:,} steps, "
            f"before converging (ropelength {self.ropelength:.1f})"
        )


def relax(
    realization: Realization,
    steps: int = RELAX_STEPS,
    time_limit: float | None = None,
    fine: bool = False,
    points: int | None = None,
    escape: int = 0,
    seed: int = 0,
) -> Realization:
    """Return ``realization`` with its curves relaxed toward a tight shape (module docstring).

    Parameters
    ----------
    realization : Realization
        Of a finite scaffold with closed strands.
    steps : int
        Most flow steps (default :data:`RELAX_STEPS`), at least 1.
    time_limit : float or None
        Seconds after which to stop early (``None``, the default: none; a run stopped by
        it depends on the machine's speed and load).
    fine : bool
        Refine the converged shape at twice the resolution (module docstring): tighter,
        more work.  ``steps`` and ``time_limit`` bound all the passes together.
    points : int or None
        Flow points per rope diameter of the last fine pass, from 16 (``None``, the
        default) to 64 (:data:`FINE_POINTS`): finer sampling, tighter (needs ``fine``).
    escape : int
        Escape rounds after the relaxation (module docstring), at least 0 (the default):
        each relaxes a shaken copy of the tightest shape as the first relaxation ran and
        keeps it if tighter; ``steps`` and ``time_limit`` bound them too.
    seed : int
        Seed of the escape rounds' displacements (default 0).

    Returns
    -------
    Realization
        With ``relaxation`` (:class:`Relaxation`) saying whether it converged.

    Raises
    ------
    GeometryError
        For open strands or limits out of range (a usage error).

    Examples
    --------
    >>> from lkspace import realize
    >>> r = relax(realize("dihedron:3", 1), steps=200)
    >>> r.n_curves, r.min_distance > r.min_separation, r.relaxation.stopped
    (1, True, 'steps')
    """
    _check_limits(steps, time_limit)
    passes = _fine_passes(fine, points)
    _check_escape(escape, seed)
    name = realization.scaffold.name
    if not realization.trace.closed.all():
        raise GeometryError(f"{name}: relax needs closed strands (null edge-sides leave open ones)", usage=True)
    realization = replace(realization, curves=_start(realization), construction=None)
    if realization.scaffold.dim:
        return _relax_periodic(realization, steps, time_limit, Plan(passes, escape, seed))
    curves = realization.curves
    centre = np.vstack(curves).mean(axis=0)
    size = _spread(curves, centre)
    flowed = _escaped(curves, steps, time_limit, Plan(passes, escape, seed))
    new_centre = np.vstack(flowed.curves).mean(axis=0)
    factor = size / _spread(flowed.curves, new_centre)
    relaxed = [(c - new_centre) * factor + centre for c in flowed.curves]
    rope = 0.5 * flowed.diameter * factor
    # the pieces of a tight rope sit about a rope diameter apart, which may pass the design's
    # scale: the coarse pass reaches 0.3 x the scale given, so give it at least 10 rope radii
    reach = max(realization.scale, 10 * rope)
    min_dist, closest = check_embedding(relaxed, realization.closed, realization.min_separation, reach)
    return replace(
        realization,
        curves=relaxed,
        tube_radius=float(TUBE_FILL * rope),
        min_distance=float(min_dist),
        closest=closest,
        relaxation=Relaxation(flowed.iterations, flowed.stopped, flowed.ropelength),
    )


def _start(real: Realization) -> list[np.ndarray]:
    """Return the curves a relaxation starts from: the construction smoothed as :data:`START` says, else the curves given."""
    if real.construction is None:
        return real.curves
    diameter = START_DIAMETER * real.radius
    if not real.scaffold.dim:
        return smooth_curves(real.construction, diameter, how=START)
    from .construction import Curves
    from .threads import smoothed_classes

    assert real.translations is not None  # realize sets them
    built = Curves(real.construction, real.closed, real.strand_of, real.copy_of, real.translations)
    return smoothed_classes(real.scaffold, real.trace, built, diameter, True, START)


class Plan(NamedTuple):
    """What a relaxation runs after its first pass (:func:`relax`'s ``fine``, ``points``, ``escape``, ``seed``)."""

    passes: tuple[tuple[float, float], ...]
    """(points per rope diameter, curve-shortening weight) of every fine pass"""
    escape: int
    """escape rounds"""
    seed: int
    """seed of the escape rounds' displacements"""


def _fine_passes(fine: bool, points: int | None) -> tuple[tuple[float, float], ...]:
    """Return the fine passes :func:`relax` runs (none without ``fine``); refuse ``points`` out of range or without ``fine``."""
    if points is None:
        return FINE_PASSES if fine else ()
    low, high = FINE_POINTS
    if isinstance(points, bool) or not isinstance(points, (int, np.integer)) or not low <= points <= high:
        raise GeometryError(
            f"points: must be a whole number from {low} to {high}, got {points!r}", usage=True, parameter="points"
        )
    if not fine:
        raise GeometryError("points: samples the last fine pass, so it needs fine=True", usage=True, parameter="points")
    return (*FINE_PASSES[:-1], (float(points), FINE_PASSES[-1][1]))


def _escaped(
    curves: list[np.ndarray], steps: int, time_limit: float | None, plan: Plan, cell: Cell | None = None
) -> FlowResult:
    """Relax ``curves`` by :func:`_passes`, then run the escape rounds of ``plan`` (module docstring).

    ``steps`` and ``time_limit`` bound the passes of every round together; the result is
    the tightest rope found, its ``iterations`` count every round's, its ``stopped`` is
    the last round's (``"converged"`` when every round converged).
    """
    from .escape import shaken

    start = time.monotonic()
    best = _passes(curves, steps, time_limit, plan.passes, cell)
    used, stopped = best.iterations, best.stopped
    rng = np.random.default_rng(plan.seed)
    offsets = None if cell is None else cell.offsets()
    for _ in range(plan.escape if stopped == "converged" else 0):
        left = None if time_limit is None else time_limit - (time.monotonic() - start)
        if used >= steps or (left is not None and left <= 0):
            stopped = "steps" if used >= steps else "time"  # the next round did not run
            break
        trial = _passes(shaken(best.curves, 0.5 * best.diameter, rng, offsets), steps - used, left, plan.passes, cell)
        used, stopped = used + trial.iterations, trial.stopped
        if trial.ropelength < best.ropelength:
            best = trial
        if stopped != "converged":
            break
    return replace(best, iterations=used, stopped=stopped)


def _passes(
    curves: list[np.ndarray],
    steps: int,
    time_limit: float | None,
    passes: tuple[tuple[float, float], ...],
    cell: Cell | None = None,
) -> FlowResult:
    """Run the growing rope flow on ``curves`` to convergence, then the fine ``passes`` (module docstring).

    ``steps`` and ``time_limit`` bound the passes together; the result's ``iterations``
    count them all, its ``stopped`` is the last pass's.
    """
    start = time.monotonic()
    first = FlowOptions(
        diameter=2 * rope_thickness(curves, cell=cell), grow=GROW, iterations=steps, time_limit=time_limit
    )
    flowed = rope_flow(curves, first, cell=cell)
    for points, pull in passes:
        if flowed.stopped != "converged":
            break
        left = None if time_limit is None else time_limit - (time.monotonic() - start)
        if left is not None and left <= 0:
            return replace(flowed, stopped="time")  # the next pass did not run
        options = FlowOptions(
            diameter=FINE_START * flowed.diameter,
            points_per_diameter=points,
            pull=pull,
            grow=GROW,
            iterations=steps - flowed.iterations,
            time_limit=left,
        )
        refined = rope_flow(flowed.curves, options, cell=cell)
        flowed = replace(refined, iterations=flowed.iterations + refined.iterations)
    return flowed


def _relax_periodic(realization: Realization, steps: int, time_limit: float | None, plan: Plan) -> Realization:
    """Relax the thread classes in the fixed periodic cell (module docstring) and place them at every copy."""
    from .cell import cell_of, classes_of, placed
    from .tracks import lattice_shift

    real = realization
    assert real.translations is not None  # realize sets them
    shifts = lattice_shift(real.scaffold, real.translations)
    classes, thread = classes_of(real.curves, real.closed, real.strand_of, real.copy_of, shifts)
    cell = cell_of(real.scaffold, real.trace)
    flowed = _escaped(classes, steps, time_limit, plan, cell)
    curves = placed(flowed.curves, thread, cell, real.strand_of, real.copy_of, shifts)
    rope = 0.5 * flowed.diameter
    reach = max(real.scale, 10 * rope)
    min_dist, closest = check_embedding(curves, real.closed, real.min_separation, reach)
    return replace(
        real,
        curves=curves,
        tube_radius=float(TUBE_FILL * rope),
        min_distance=float(min_dist),
        closest=closest,
        relaxation=Relaxation(flowed.iterations, flowed.stopped, flowed.ropelength),
    )


def _check_limits(steps: int, time_limit: float | None) -> None:
    """Refuse a step count below 1 or a time limit that is not a positive number of seconds."""
    if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 1:
        raise GeometryError(f"steps: must be a whole number at least 1, got {steps!r}", usage=True, parameter="steps")
    if time_limit is not None and not (isinstance(time_limit, (int, float)) and 0 < time_limit < float("inf")):
        raise GeometryError(
            f"time_limit: must be a positive number of seconds or None, got {time_limit!r}",
            usage=True,
            parameter="time_limit",
        )


def _check_escape(escape: int, seed: int) -> None:
    """Refuse a negative or non-integer number of escape rounds, or a seed that is not a non-negative integer."""
    for name, value in (("escape", escape), ("seed", seed)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 0:
            raise GeometryError(f"{name}: must be a whole number at least 0, got {value!r}", usage=True, parameter=name)


def _spread(curves: list[np.ndarray], centre: np.ndarray) -> float:
    """Root mean square distance of the points from ``centre``."""
    return float(np.sqrt(((np.vstack(curves) - centre) ** 2).sum(axis=1).mean()))
