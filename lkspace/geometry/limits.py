"""Bounds of a realization, checked before any geometry is built.

:func:`~lkspace.geometry.realization.realize` refuses parameters that cannot give a
sensible picture (lengths beyond the mesh, twists too tight to embed) and realizations
too large to build, each with one message naming the value and the bound.
"""

from __future__ import annotations

import numpy as np

from ..errors import GeometryError, TooLargeError
from ..model.scaffold import Scaffold
from .helix import RAMP

__all__ = [
    "MAX_CHECK_SAMPLES",
    "MAX_POINTS",
    "MAX_RELATIVE",
    "MAX_SAMPLES",
    "check_lengths",
    "check_points",
    "check_samples",
    "check_winding",
]

MAX_POINTS = 4_000_000
"""Most polyline points :func:`~lkspace.geometry.realization.realize` builds (all curves and copies together).

Every point costs about 1 kB in the intermediate arrays and the embedding check, so the
bound keeps a realization under a few GB.  The estimate is made from the trace before
any geometry: ``edge_samples + samples_per_turn * |t| / K`` per edge piece plus
``corner_samples`` per corner turn, times the copies of ``translations``.
"""

MAX_RELATIVE = 1.0
"""Largest ``radius``, ``normal_offset``, ``margin`` and ``tube_radius``, in shortest edge lengths."""

MIN_RELATIVE = 1e-9
"""Smallest nonzero ``radius``, ``normal_offset``, ``tube_radius``, ``helix_radius`` and ``pitch``, in shortest edge lengths."""

MAX_SAMPLES = 1000
"""Largest ``samples_per_turn``, ``edge_samples`` and ``corner_samples``."""


MAX_CHECK_SAMPLES = 10_000_000
"""Most samples the embedding check (:func:`~lkspace.geometry.clearance.check_embedding`) may take.

It samples every ``min_separation / 2`` along the strands, about the total length of the
face sides plus ``2 pi x radius`` per unit of twist; a mesh whose sides are long next to
its shortest edge (a 100,000-gon, a needle-thin face) would need billions.
"""


def check_points(name: str, estimate: float, max_points: int) -> None:
    """Refuse curves of about ``estimate`` points past ``max_points`` on scaffold ``name`` (:class:`~lkspace.errors.TooLargeError`).

    The error names the parameter ``max_points``; a program that sets it from a bound of
    its own (the command line: :data:`MAX_POINTS`) says that bound instead.
    """
    if estimate > max_points:
        raise TooLargeError(
            f"max_points: the curves of {name} would have about {estimate:,.0f} points > {max_points:,}; "
            "use smaller twists (or a smaller block)",
            parameter="max_points",
        )


def check_samples(scaffold: Scaffold, labels: np.ndarray, radius: float, min_sep: float) -> None:
    """Refuse strands too long for the embedding check at ``min_sep`` (:class:`~lkspace.errors.TooLargeError`).

    The strands run along every face side once (their length is about the sum of the
    side lengths) and wind ``|t|`` turns of radius about ``radius`` around an edge of twist ``t``.
    """
    corners = scaffold.corner_positions
    starts = scaffold.face_starts
    nxt = np.arange(len(corners)) + 1
    nxt[starts[1:] - 1] = starts[:-1]  # each face's last corner closes onto its first
    sides = float(np.linalg.norm(corners[nxt] - corners, axis=1).sum())
    multi = scaffold.edge_degrees > 1
    turns = float(np.abs(np.asarray(labels, np.float64))[multi].sum())
    samples = (sides + 2 * np.pi * radius * turns) / (0.5 * min_sep)
    if not samples <= MAX_CHECK_SAMPLES:
        raise TooLargeError(
            f"{scaffold.name}: strands about {sides:.4g} long checked every {0.5 * min_sep:.3g} need about "
            f"{samples:.3g} samples > {MAX_CHECK_SAMPLES:,} (MAX_CHECK_SAMPLES): the sides are too long next to "
            "the shortest edge; use a coarser mesh"
        )


def check_small(name: str, lengths: dict[str, float | None], scale: float) -> None:
    """Refuse (a usage error) any nonzero of ``lengths`` below :data:`MIN_RELATIVE` x ``scale`` on scaffold ``name``.

    Such lengths vanish next to the mesh (a pitch of 5e-324 divided to infinity).
    """
    for what, value in lengths.items():
        if value is not None and 0 < value < MIN_RELATIVE * scale:
            raise GeometryError(
                f"{what}: {value:g} is below {MIN_RELATIVE:g} x the shortest edge of "
                f"{name} ({MIN_RELATIVE * scale:.4g}); too small to draw",
                usage=True,
                parameter=what,
            )


def check_lengths(name: str, lengths: dict[str, float], scale: float) -> None:
    """Refuse (a usage error) any of ``lengths`` beyond :data:`MAX_RELATIVE` x ``scale`` on scaffold ``name``."""
    for what, value in lengths.items():
        if value > MAX_RELATIVE * scale:
            raise GeometryError(
                f"{what}: {value:g} exceeds {MAX_RELATIVE:g} x the shortest edge of "
                f"{name} ({MAX_RELATIVE * scale:.4g}); strands that far from their edge leave the scaffold",
                usage=True,
                parameter=what,
            )


def check_winding(
    scaffold: Scaffold, pa: np.ndarray, pb: np.ndarray, margins: np.ndarray, labels: np.ndarray, min_sep: float
) -> None:
    """Refuse, before any geometry, twists that wind the strands of an edge too tightly to embed.

    On an edge of degree K >= 2 with twist t the strands advance ``|t| / (1 - RAMP)`` slots
    over the helix span where the twist profile of :mod:`~lkspace.geometry.helix` is
    steepest, so neighbouring passes lie about ``span (1 - RAMP) / |t|`` apart along the
    axis.  Below half of ``min_separation`` the
    embedding check would fail anyway (after building and sampling every turn, at great
    cost for huge twists); the factor 2 keeps this test from refusing any embeddable design.
    """
    k = scaffold.edge_degrees
    twist = np.abs(np.where(k > 1, np.asarray(labels, np.float64), 0.0))  # floats: -2**63 has no int64 abs
    span = (1 - margins[:, 0] - margins[:, 1]) * np.linalg.norm(pb - pa, axis=1)
    gap = span * (1 - RAMP) / np.maximum(twist, 1e-300)
    bad = np.flatnonzero((twist > 0) & (gap < 0.5 * min_sep))
    if len(bad):
        e = int(bad[np.argmin(gap[bad])])
        raise GeometryError(
            f"{scaffold.name}: twist {int(labels[e])} on edge {scaffold.edge_name(e)} winds its strands about "
            f"{gap[e]:.3g} apart (< min_separation {min_sep:.3g}); the geometry would self-intersect (use smaller twists)"
        )
