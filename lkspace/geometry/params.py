"""Realization parameters: what the user sets (:class:`GeometryParams`), resolved once per mesh (:class:`Resolved`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import GeometryError
from ..model.scaffold import Scaffold
from .limits import MAX_SAMPLES, check_lengths, check_small
from .tracks import default_scale

NEAR_ANGLE = np.pi / 6
"""Faces meeting at an edge at less than this angle get the default normal offset."""

RADIUS, MARGIN, MIN_SEPARATION, TUBE = 0.12, 0.28, 0.01, 0.03
"""Default inset, straight margin, least separation and tube radius, in units of the mesh scale."""

NORMAL_OFFSET = 0.35
"""Default normal offset where faces nearly coincide, in units of the inset."""

SMOOTH_DIAMETER = 1.5
"""Rope diameter of the default smoothing (:func:`~lkspace.geometry.flow.smooth_curves`), in insets."""


@dataclass(frozen=True)
class GeometryParams:
    """Realization parameters; ``None`` entries are scaled from the mesh.

    Attributes
    ----------
    radius : float or None
        The **inset**: in-face distance ``rho`` of the tracks from their edge (default
        ``0.12 * scale``); a strand follows its face as the polygon inset by ``rho``.
    normal_offset : float or None
        Offset ``h`` of the tracks along the face normal.  Default ``0.35 * radius`` on
        edges where two faces meet at less than :data:`NEAR_ANGLE` (a two-sided polygon),
        0 elsewhere; a value given applies on every edge.
    margin : float or None
        Length at each edge end kept straight for the corner turns (default
        ``0.28 * scale``; longer at acute corners, at most ``0.42`` of the edge).
    tube_radius : float or None
        Radius of exported tubes (default ``0.03 * scale``, shrunk to ``0.45`` of the
        minimum separation found and to ``0.9`` of the tightest bend of a curve).
    min_separation : float or None
        Refuse geometry whose distinct pieces come closer (default ``0.01 * scale``).
    helix_radius : float or None
        Distance of the evenly spaced helix strands from the edge axis (default: the
        mean distance of the edge's tracks, about ``radius``); see :mod:`~lkspace.geometry.helix`.
    pitch : float or None
        Axial length of one full turn of an edge's helix (default: the twist spreads
        over the whole edge).
    samples_per_turn : int
        Polyline points per full helix turn.
    edge_samples : int
        Points on an edge piece besides those of the turns.
    corner_samples : int
        Points on each corner turn.
    smooth : bool
        Smooth the closed strands of a finite scaffold (default): corners rounded, strands
        spread to 1.5 insets apart, by a flow that cannot change the link type
        (:func:`~lkspace.geometry.flow.smooth_curves`).  ``False`` keeps the construction
        polylines (faster; what :func:`lkspace.identify` projects).
    """

    radius: float | None = None
    normal_offset: float | None = None
    margin: float | None = None
    tube_radius: float | None = None
    min_separation: float | None = None
    helix_radius: float | None = None
    pitch: float | None = None
    samples_per_turn: int = 32
    edge_samples: int = 24
    corner_samples: int = 12
    smooth: bool = True

    def check(self) -> None:
        """Raise :class:`GeometryError` (a usage error) naming a parameter that is not usable.

        Lengths must be finite; ``radius``, ``margin``, ``tube_radius`` and
        ``min_separation`` positive, ``normal_offset`` at least 0; the sample counts
        integers in ``1..MAX_SAMPLES`` (``corner_samples`` from 2).
        """
        for name in ("radius", "normal_offset", "margin", "tube_radius", "min_separation", "helix_radius", "pitch"):
            value = getattr(self, name)
            if value is None:
                continue
            low = 0.0 if name == "normal_offset" else None
            if not np.isfinite(value) or (value < 0 if low is not None else value <= 0):
                wanted = "a finite number >= 0" if low is not None else "a finite number > 0"
                raise GeometryError(f"geometry parameter {name} must be {wanted}, got {value}", usage=True)
        for name, least in (("samples_per_turn", 1), ("edge_samples", 1), ("corner_samples", 2)):
            value = getattr(self, name)
            if not isinstance(value, int | np.integer) or not least <= value <= MAX_SAMPLES:
                raise GeometryError(
                    f"geometry parameter {name} must be an integer in {least}..{MAX_SAMPLES}", usage=True
                )


@dataclass(frozen=True)
class Resolved:
    """Parameters of one realization, resolved once from :class:`GeometryParams` and the mesh.

    Attributes
    ----------
    scale, radius, normal_offset, margin, min_separation : float
        As in :class:`GeometryParams`, defaults filled in (lengths in mesh units).
    near_angle : float or None
        Faces meeting at less than this get the default normal offset (``None`` when
        ``normal_offset`` was given: it applies everywhere).
    corner_samples : int
    """

    scale: float
    radius: float
    normal_offset: float
    margin: float
    min_separation: float
    near_angle: float | None
    corner_samples: int

    @staticmethod
    def of(scaffold: Scaffold, params: GeometryParams) -> Resolved:
        """Fill the defaults of ``params`` from ``scaffold``'s scale; check the lengths."""
        params.check()
        scale = default_scale(scaffold)
        rho = params.radius if params.radius is not None else RADIUS * scale
        h = params.normal_offset if params.normal_offset is not None else NORMAL_OFFSET * rho
        margin = params.margin if params.margin is not None else MARGIN * scale
        min_sep = params.min_separation if params.min_separation is not None else MIN_SEPARATION * scale
        for name, value in (("radius", rho), ("margin", margin), ("min_separation", min_sep)):
            if not np.isfinite(value) or value <= 0:
                raise GeometryError(f"geometry parameter {name} must be positive, got {value}")
        lengths = {"radius": rho, "normal_offset": h, "margin": margin, "tube_radius": params.tube_radius or 0.0}
        lengths["helix_radius"] = params.helix_radius or 0.0
        check_lengths(scaffold.name, lengths, scale)
        check_small(scaffold.name, {**lengths, "pitch": params.pitch}, scale)
        near = NEAR_ANGLE if params.normal_offset is None else None
        return Resolved(scale, float(rho), float(h), float(margin), float(min_sep), near, max(2, params.corner_samples))
