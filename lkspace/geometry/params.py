"""Realization parameters and options.

:class:`GeometryParams` is the shape the user asks for (distances, sampling, smoothing);
:class:`RealizeOptions` is how :func:`~lkspace.geometry.realization.realize` goes about it
(copies, clearance checking, a trace to reuse, the point bound); :class:`Resolved` is the
shape resolved once per mesh, defaults filled in from its scale, which every step of the
realization reads.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import ArrayLike

from ..errors import GeometryError
from ..model.scaffold import Scaffold
from .limits import MAX_POINTS, MAX_SAMPLES, check_lengths, check_small
from .tracks import default_scale

if TYPE_CHECKING:
    from ..strands.tracing import Trace

NEAR_ANGLE = np.pi / 6
"""Faces meeting at an edge at less than this angle get the default normal offset."""

RADIUS, MARGIN, MIN_SEPARATION, TUBE = 0.12, 0.28, 0.01, 0.03
"""Default inset, straight margin, least separation and tube radius, in units of the mesh scale."""

NORMAL_OFFSET = 0.35
"""Default normal offset where faces nearly coincide, in units of the inset."""

SMOOTH_DIAMETER = 2.0, 1.5
"""Most and least rope diameter of the default smoothing (:func:`smooth_diameter`), in insets."""

TUBE_GAP_SHARE = 0.45
"""The default tube radius is at most this share of the smallest distance between distinct pieces."""

TUBE_BEND_SHARE = 0.9
"""The default tube radius is at most this share of the tightest bend radius of a curve (else it folds)."""

MIN_CORNER_SAMPLES = 2
"""Fewest points on a corner turn: its two ends."""

EmbeddingCheck = Literal["refuse", "measure", "later"]
"""What :func:`~lkspace.geometry.realization.realize` does about the embedding of the curves.

``"refuse"``
    Measure the smallest distance between distinct pieces and raise
    :class:`~lkspace.errors.GeometryError` below ``min_separation`` (the default).
``"measure"``
    Measure it (``min_distance``, ``closest``) but never refuse: geometry to look at.
``"later"``
    Skip the measurement (``min_distance`` is ``inf``), for previews that measure later;
    twists too tight to embed are still refused, and so is a construction the smoothing
    would start from.
"""
EMBEDDING_CHECKS: tuple[EmbeddingCheck, ...] = ("refuse", "measure", "later")


@dataclass(frozen=True, eq=False)
class RealizeOptions:
    """How :func:`~lkspace.geometry.realization.realize` works, beyond the shape of :class:`GeometryParams`.

    Attributes
    ----------
    embedding : {"refuse", "measure", "later"}
        What to do about the embedding check (:data:`EmbeddingCheck`).
    translations : (n_copies, dim) int, optional
        Lattice translations of a block of copies (periodic scaffolds); default one copy.
    trace : Trace, optional
        A trace already computed for these labels and nulls (it is not traced again).
    max_points : int
        Refuse (:class:`~lkspace.errors.TooLargeError` naming ``max_points``, before
        building anything) when the curves would have more points (default :data:`MAX_POINTS`).
    """

    embedding: EmbeddingCheck = "refuse"
    translations: ArrayLike | None = None
    trace: Trace | None = None
    max_points: int = MAX_POINTS

    def check(self) -> None:
        """Raise :class:`~lkspace.errors.GeometryError` (a usage error) naming an option that is not usable."""
        if self.embedding not in EMBEDDING_CHECKS:
            raise GeometryError(
                f"embedding: expected one of {', '.join(EMBEDDING_CHECKS)}, got {self.embedding!r}",
                usage=True,
                parameter="embedding",
            )
        if not isinstance(self.max_points, int | np.integer) or self.max_points < 1:
            raise GeometryError(
                f"max_points: must be an integer >= 1, got {self.max_points!r}", usage=True, parameter="max_points"
            )


def smooth_diameter(scaffold: Scaffold, radius: float) -> float:
    """Rope diameter of the default smoothing (:func:`~lkspace.geometry.flow.smooth_curves`) for inset ``radius``.

    The spacing the helices of the scaffold's busiest edge already have, ``2 radius
    sin(pi / K)`` (two strands on opposite sides of an edge: ``2 radius``), kept within
    :data:`SMOOTH_DIAMETER`: a rope that thick needs no strand to leave its edge's helix
    radius, so each still follows its face.
    """
    most, least = SMOOTH_DIAMETER
    busiest = max(2, int(scaffold.edge_degrees.max(initial=2)))
    return float(radius * np.clip(2 * np.sin(np.pi / busiest), least, most))


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
        Smooth the closed strands (default): corners rounded, strands spread to the
        spacing of the busiest edge's helices (:func:`smooth_diameter`: 2 insets where
        edges join two faces), by a flow that cannot change the link type
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
                raise GeometryError(f"{name}: must be {wanted}, got {value}", usage=True, parameter=name)
        for name, least in (("samples_per_turn", 1), ("edge_samples", 1), ("corner_samples", MIN_CORNER_SAMPLES)):
            value = getattr(self, name)
            if not isinstance(value, int | np.integer) or not least <= value <= MAX_SAMPLES:
                raise GeometryError(
                    f"{name}: must be an integer in {least}..{MAX_SAMPLES}, got {value!r}", usage=True, parameter=name
                )


@dataclass(frozen=True)
class Resolved:
    """The shape of one realization, resolved once from :class:`GeometryParams` and the mesh.

    Every step of :func:`~lkspace.geometry.realization.realize` reads these, never the
    parameters as given.

    Attributes
    ----------
    scale, radius, normal_offset, margin, min_separation : float
        As in :class:`GeometryParams`, defaults filled in (lengths in mesh units).
    near_angle : float or None
        Faces meeting at less than this get the default normal offset (``None`` when
        ``normal_offset`` was given: it applies everywhere).
    helix_radius, pitch, tube_radius : float or None
        As given (``None``: from the mesh, see :class:`GeometryParams`).
    samples_per_turn, edge_samples, corner_samples : int
    smooth : bool
    """

    scale: float
    radius: float
    normal_offset: float
    margin: float
    min_separation: float
    near_angle: float | None
    helix_radius: float | None
    pitch: float | None
    tube_radius: float | None
    samples_per_turn: int
    edge_samples: int
    corner_samples: int
    smooth: bool

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
                raise GeometryError(f"{name}: must be positive, got {value}", parameter=name)
        lengths = {"radius": rho, "normal_offset": h, "margin": margin, "tube_radius": params.tube_radius or 0.0}
        lengths["helix_radius"] = params.helix_radius or 0.0
        check_lengths(scaffold.name, lengths, scale)
        check_small(scaffold.name, {**lengths, "pitch": params.pitch}, scale)
        return Resolved(
            scale=scale,
            radius=float(rho),
            normal_offset=float(h),
            margin=float(margin),
            min_separation=float(min_sep),
            near_angle=NEAR_ANGLE if params.normal_offset is None else None,
            helix_radius=params.helix_radius,
            pitch=params.pitch,
            tube_radius=params.tube_radius,
            samples_per_turn=int(params.samples_per_turn),
            edge_samples=int(params.edge_samples),
            corner_samples=int(params.corner_samples),
            smooth=params.smooth,
        )
