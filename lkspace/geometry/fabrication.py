"""Printable pieces: strands as solid tubes of a given thickness, checked for clearance.

:func:`printable` turns a :class:`~lkspace.geometry.realization.Realization` into the
pieces a printer gets: the periods of one infinite thread joined into one polyline
(a block cut by :func:`~lkspace.geometry.block.realize_block` is already one piece per
thread run), scaled by ``scale`` into output units.  It then proves, on the polylines
the tube meshes are built around, that

* every tube of radius ``r = thickness / 2`` stays clear of itself: the centreline bends
  nowhere tighter than ``r`` (else the tube folds into itself), and
* any two distinct pieces (different pieces, or one piece farther apart along it than a
  few thicknesses) keep a surface gap of at least ``clearance``.

The gap is measured conservatively: the centrelines are sampled every ``spacing`` and
``gap >= (sampled distance) - spacing - 2 r`` (every point of a polyline lies within
``spacing / 2`` of a sample, and every point of a tube mesh within ``r`` of its
centreline), so the printed surfaces are at least ``clearance`` apart.  Anything that
cannot be met is refused with one :class:`~lkspace.errors.GeometryError` naming the two
pieces and the nearest scaffold vertex or edge.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal, TypeGuard, get_args

import numpy as np

from ..errors import GeometryError
from .block import JOIN, join_curves
from .clearance import pieces_apart, sample_tree, samples, tightest_bend
from .params import TUBE_BEND_SHARE
from .realization import Realization
from .tracks import place_name

Units = Literal["um", "mm", "cm", "m", "in", "ft"]
"""What one output unit is."""

UNITS: dict[Units, tuple[str, float]] = {
    "um": ("micron", 1e-6),
    "mm": ("millimeter", 1e-3),
    "cm": ("centimeter", 1e-2),
    "m": ("meter", 1.0),
    "in": ("inch", 0.0254),
    "ft": ("foot", 0.3048),
}
"""Per :data:`Units` choice: the 3MF unit name and the length in metres of one unit."""

MAX_SCALE = 1e9
"""Largest ``scale``: coordinates stay far inside float32 (the STL and 3MF precision)."""
MIN_SCALE = 1 / MAX_SCALE
"""Smallest ``scale``: smaller coordinates lose their digits in float32 (5e-324 made every point 0)."""

RELAXED_PRINT_SHARE = 0.7
"""A relaxed (tight) rope's tube touches itself: a print's default thickness is this share of it, for a gap."""
MAX_GAP_SAMPLES = 3_000_000
"""Most centreline samples the clearance check takes (coarser sampling beyond)."""
MAX_GAP_PAIRS = 5_000_000
"""The search for the smallest gap (to report it) stops widening past this many sample pairs."""
REACH_STEPS = 30
"""The sampling step is at least 1 / REACH_STEPS of thickness + clearance (a tiny clearance or a huge one)."""


@dataclass(frozen=True, eq=False)
class Printable:
    """Pieces ready for a mesh writer, in output units.

    Attributes
    ----------
    curves : list of (n_k, 3) float64
        Centrelines, scaled; ``closed[k]`` joins the ends, an open piece gets flat caps.
    closed : (n_pieces,) bool
    strand_of : (n_pieces,) int64
        The strand of the trace each piece realizes.
    first : (n_pieces,) int64
        The realization's curve each piece begins with (its colour:
        :func:`lkspace.formats.colors.curve_colors`).
    radius : float
        Tube radius (half the thickness), output units.
    clearance : float
        The gap that was asked for and proved.
    min_gap : float or None
        The smallest surface gap measured (a lower bound), or ``None`` if every gap
        exceeds ``clearance + radius``.
    units : {"um", "mm", "cm", "m", "in", "ft"}
        What one output unit is (:data:`Units`).
    scale : float
        Output units per scaffold unit.
    """

    curves: list[np.ndarray]
    closed: np.ndarray
    strand_of: np.ndarray
    first: np.ndarray
    radius: float
    clearance: float
    min_gap: float | None
    units: Units
    scale: float

    def summary(self) -> dict[str, object]:
        """JSON-ready facts of the pieces."""
        return {
            "pieces": len(self.curves),
            "open_pieces": int((~self.closed).sum()),
            "thickness": 2 * self.radius,
            "clearance": self.clearance,
            "min_gap": self.min_gap,
            "units": self.units,
            "scale": self.scale,
        }


def is_units(units: object) -> TypeGuard[Units]:
    """Whether ``units`` is one of :data:`Units`."""
    return units in get_args(Units)


def check_options(thickness: float | None, clearance: float | None, units: str, scale: float) -> None:
    """Refuse unusable fabrication options (usage errors naming the parameter)."""
    if thickness is not None and not (np.isfinite(thickness) and thickness > 0):
        raise GeometryError(
            f"thickness: must be a finite number > 0, got {thickness}", usage=True, parameter="thickness"
        )
    if clearance is not None and not (np.isfinite(clearance) and clearance >= 0):
        raise GeometryError(
            f"clearance: must be a finite number >= 0, got {clearance}", usage=True, parameter="clearance"
        )
    if not is_units(units):
        raise GeometryError(f"units: {units!r} is not one of {', '.join(UNITS)}", usage=True, parameter="units")
    if not (np.isfinite(scale) and MIN_SCALE <= scale <= MAX_SCALE):
        raise GeometryError(
            f"scale: must be a number in [{MIN_SCALE:g}, {MAX_SCALE:g}], got {scale}", usage=True, parameter="scale"
        )


def printable(
    real: Realization,
    thickness: float | None = None,
    clearance: float | None = None,
    units: Units = "mm",
    scale: float = 1.0,
) -> Printable:
    """Return the :class:`Printable` pieces of ``real`` (``thickness``, ``clearance`` in output units).

    ``thickness`` defaults to twice the realization's tube radius (scaled; for a relaxed
    realization, whose tube touches itself, :data:`RELAXED_PRINT_SHARE` of it), ``clearance``
    to 0 (tubes must not touch).  Raises :class:`GeometryError` when a tube would fold
    into itself or two pieces come closer than ``clearance``.

    Examples
    --------
    >>> from lkspace import realize
    >>> p = printable(realize("tetrahedron", 1), thickness=0.1, clearance=0.05)
    >>> len(p.curves), p.radius, p.min_gap is None or p.min_gap >= 0.05
    (3, 0.05, True)
    """
    clearance = 0.0 if clearance is None else float(clearance)
    check_options(thickness, clearance, units, scale)
    curves, closed, members = join_curves(real.curves, real.closed, JOIN * real.scale)
    first = np.array([m[0] for m in members], np.int64)
    strand_of = real.strand_of[first] if members else np.zeros(0, np.int64)
    scaled = [np.asarray(c, np.float64) * scale for c in curves]
    bend, piece, point = tightest_bend(scaled, closed)
    if thickness is None:  # the picture's tube, thinned where the curves bend tighter
        share = RELAXED_PRINT_SHARE if real.relaxation is not None else 1.0
        radius = min(share * real.tube_radius * scale, TUBE_BEND_SHARE * bend)
    else:
        radius = 0.5 * thickness
    if bend < radius:
        raise GeometryError(
            f"{real.scaffold.name}: `thickness` {2 * radius:.4g} exceeds twice the bend radius {bend:.4g} of piece "
            f"{piece} near {place_name(real.scaffold, point / scale)}; the tube would fold into itself "
            "(use a smaller `thickness` or a larger `scale`)",
            parameter="thickness",
        )
    min_gap = check_gaps(real, scaled, closed, radius, clearance, scale)
    return Printable(scaled, closed, np.asarray(strand_of, np.int64), first, radius, clearance, min_gap, units, scale)


def check_gaps(
    real: Realization, curves: list[np.ndarray], closed: np.ndarray, radius: float, clearance: float, scale: float
) -> float | None:
    """Prove a surface gap of ``clearance`` between distinct pieces; return the smallest gap found."""
    if not curves:
        return None
    want = 2 * radius + clearance
    total = sum(float(np.linalg.norm(np.diff(np.vstack([c, c[:1]]) if cl else c, axis=0), axis=1).sum())
                for c, cl in zip(curves, closed, strict=True))  # fmt: skip
    pts_all = np.vstack(curves)
    span = float(np.linalg.norm(pts_all.max(axis=0) - pts_all.min(axis=0))) + 2 * radius
    near = min(want, span)  # no two points are farther apart: a clearance past the pieces' span measures as it
    # at most REACH_STEPS samples per search radius: the pairs grow with samples, not with want / spacing
    spacing = max(min(radius, clearance if clearance > 0 else radius) / 3, near / REACH_STEPS, total / MAX_GAP_SAMPLES)
    pts, arc, owner, lengths = samples(curves, closed, spacing)
    tree = sample_tree(pts)
    reach = near + spacing + radius
    exclusion = max(4 * near, np.pi * (radius + spacing))
    while True:  # widen the search until a gap is found (a number to report), within bounds
        pairs = tree.query_pairs(reach, output_type="ndarray")
        keep = np.zeros(0, bool)
        if len(pairs):
            keep = pieces_apart(owner, arc, lengths, closed, pairs[:, 0], pairs[:, 1], exclusion)
        if np.any(keep) or reach > 0.5 * max(lengths.max(), near) or 8 * len(pairs) > MAX_GAP_PAIRS:
            break  # (doubling the radius may multiply the pairs by 8)
        reach *= 2
    if not np.any(keep):
        return None
    i, j = pairs[keep, 0], pairs[keep, 1]
    d = np.linalg.norm(pts[i] - pts[j], axis=1)
    b = int(np.argmin(d))
    gap = float(d[b] - spacing - 2 * radius)
    if gap < clearance:
        mid = 0.5 * (pts[i[b]] + pts[j[b]]) / scale
        what = f"pieces {owner[i[b]]} and {owner[j[b]]}" if owner[i[b]] != owner[j[b]] else f"piece {owner[i[b]]}"
        raise GeometryError(
            f"{real.scaffold.name}: {what} leave a gap of {max(gap, 0.0):.4g} < clearance {clearance:.4g} "
            f"(thickness {2 * radius:.4g}) near {place_name(real.scaffold, mid)}; "
            + gap_fixes(gap + 2 * radius, 2 * radius, clearance, scale),
            parameter="clearance",
        )
    return gap


def gap_fixes(centre: float, thickness: float, clearance: float, scale: float) -> str:
    """Say which parameters can open a gap: ``centre`` is the distance of the two centrelines.

    The gap is ``centre - thickness`` and ``centre`` grows with ``scale``, so a thinner tube
    helps only while ``centre > clearance``; a larger scale or a smaller clearance always can.
    Parameters are named in backquotes (the command line shows their flags).

    >>> gap_fixes(0.3, 0.1, 0.5, 1.0)
    'no `thickness` reaches clearance 0.5 at `scale` 1 (the centrelines are 0.3 apart); use `scale` 2 or more, or `clearance` 0.2 or less'
    """
    ratio = scale * (clearance + thickness) / max(centre, 1e-12)  # inf for a clearance near the float limit
    fits = math.floor(100 * max(centre - thickness, 0.0)) / 100  # rounded down: it must still fit
    if ratio <= MAX_SCALE:
        other = f"`scale` {math.ceil(100 * ratio) / 100:g} or more, or `clearance` {fits:g} or less"
    else:  # no allowed scale reaches it
        other = f"`clearance` {fits:g} or less (no `scale` up to {MAX_SCALE:g} reaches clearance {clearance:g})"
    if centre <= clearance:
        return (
            f"no `thickness` reaches clearance {clearance:g} at `scale` {scale:g} "
            f"(the centrelines are {centre:.2g} apart); use {other}"
        )
    return f"use `thickness` {math.floor(100 * (centre - clearance)) / 100:g} or less, {other}"
