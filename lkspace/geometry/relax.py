"""Relaxation: the strands of a realization drawn tight, without changing the link type.

:func:`relax` runs the rope flow of :mod:`~lkspace.geometry.flow` with a growing rope
diameter (Pierański's SONO: shrink on no overlaps): the curves shorten while their distinct
pieces are kept a rope's width apart, and every step is capped so that no strand passes
through another.  The result is scaled back to the realization's size and centre; its tube
radius is the rope's (the tube fills the space the relaxation found).

Periodic scaffolds are refused: a thread's period is fixed by the lattice, which the flow
does not keep.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from ..errors import GeometryError
from .clearance import check_embedding
from .flow import FlowOptions, rope_flow, rope_thickness

if TYPE_CHECKING:
    from .realization import Realization

RELAX_TIME = 10.0
"""Default seconds of relaxation."""

RELAX_ITERATIONS = 4000
"""Default most iterations."""

GROW = 0.004
"""Relative growth of the rope diameter per fitting iteration."""

TUBE_FILL = 0.9
"""Tube radius of the relaxed curves, in rope radii."""


def relax(
    realization: Realization, time_limit: float | None = RELAX_TIME, iterations: int = RELAX_ITERATIONS
) -> Realization:
    """Return ``realization`` with its curves relaxed toward a tight shape (module docstring).

    Parameters
    ----------
    realization : Realization
        Of a finite scaffold with closed strands.
    time_limit : float or None
        Seconds of relaxation (default :data:`RELAX_TIME`; ``None``: no limit).
    iterations : int
        Most iterations of the flow.

    Raises
    ------
    GeometryError
        For a periodic scaffold or open strands (a usage error).

    Examples
    --------
    >>> from lkspace import realize
    >>> r = relax(realize("dihedron:3", 1), iterations=200)
    >>> r.n_curves, r.min_distance > r.min_separation
    (1, True)
    """
    name = realization.scaffold.name
    if realization.scaffold.dim:
        raise GeometryError(
            f"{name}: relax works on finite scaffolds only (a periodic thread keeps its lattice period)", usage=True
        )
    if not realization.closed.all():
        raise GeometryError(f"{name}: relax needs closed strands (null edge-sides leave open ones)", usage=True)
    curves = realization.curves
    centre = np.vstack(curves).mean(axis=0)
    size = _spread(curves, centre)
    start = 2 * rope_thickness(curves)
    flowed = rope_flow(curves, FlowOptions(diameter=start, grow=GROW, iterations=iterations, time_limit=time_limit))
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
    )


def _spread(curves: list[np.ndarray], centre: np.ndarray) -> float:
    """Root mean square distance of the points from ``centre``."""
    return float(np.sqrt(((np.vstack(curves) - centre) ** 2).sum(axis=1).mean()))
