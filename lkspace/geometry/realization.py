"""Strand geometry: every strand of a labelled scaffold as a 3D polyline.

Construction
------------
Let ``ell`` be the shortest edge length (the **scale**).  Every face-side ``s`` (face
``f`` on edge ``e``) owns a **track**: the line parallel to the edge at the offset
``w_s = rho * r_s + h * n_f``, where ``r_s`` is the unit direction from the edge toward
``f``'s centroid perpendicular to the edge axis (the direction that defines the radial
order, ``docs/model.md``) and ``n_f`` is the face's unit normal (right-hand rule over its corner
order), made perpendicular to the axis.  The normal offset ``h`` separates faces that lie
in one plane (a two-sided polygon, the figure-eight mesh).

* **Along an edge** of degree ``K`` and twist ``t``, every strand leaves its track a
  ``margin`` away from each end and winds about the edge axis: at parameter ``sigma`` in
  ``[0, 1]`` the strand that started in slot ``i`` at end ``a`` sits at the slot
  coordinate ``x = i + t * G(sigma)``.  Near the ends its angle is ``Phi(x)``, interpolated
  between the slots' own track angles; in the middle the ``K`` strands sit evenly spaced,
  ``2 pi / K`` apart at the helix radius, and ``G`` turns them at a constant rate: a
  regular helix of ``t / K`` turns (:mod:`~lkspace.geometry.helix` gives the smooth
  transitions and the proof that strands of one edge never meet).  Angles increase with
  ``x``, so positive ``t`` turns counter-clockwise about the axis ``a -> b``:
  right-handed.  At ``sigma = 1`` a strand arrives on the track of slot ``(i + t) mod K``
  — exactly the twist rule of :mod:`lkspace.strands.ports`.  (On a boundary edge,
  ``K = 1``, the ``t`` full turns about an empty axis are isotopic to a straight run and
  are drawn straight.)
* **Across a face corner** the strand turns inside its face, from the end of one side's
  track to the start of the next, along a quadratic Bézier curve whose control point is
  where the two tracks meet.

Because the tracks follow the scaffold closely (``rho``, ``h`` and the margins are small
against the edge lengths), the curves stay in a thin neighbourhood of the scaffold and
realize the link the labels define.  :func:`realize` checks the embedding numerically
(:func:`check_embedding`) and refuses, naming the place, when distinct pieces come closer
than ``min_separation``.

Periodic scaffolds: a strand is unrolled through the face copies it visits (an edge link
from side ``s`` to side ``s'`` moves to the copy shifted by ``side_translation[s] -
side_translation[s']``); a strand with a non-zero period is realized over one period as
an open polyline.  :class:`~lkspace.geometry.params.RealizeOptions` ``translations``
realizes a block of lattice translates at once.

The construction itself (corner turns and edge helices) is in
:mod:`~lkspace.geometry.construction`; the parameters, resolved once per mesh, in
:mod:`~lkspace.geometry.params`; the bounds checked before anything is built in
:mod:`~lkspace.geometry.limits`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from ..errors import GeometryError
from ..model.scaffold import Scaffold
from ..strands.tracing import Trace, trace
from .clearance import Closest, check_embedding, closest_json, tightest_bend
from .construction import Curves, Ports, build_curves, edge_counts
from .flow import smooth_curves
from .limits import check_points, check_samples, check_winding
from .params import (
    TUBE,
    TUBE_BEND_SHARE,
    TUBE_GAP_SHARE,
    EmbeddingCheck,
    GeometryParams,
    RealizeOptions,
    Resolved,
    smooth_diameter,
)
from .tracks import Tracks, lattice_shift, place_name, side_tracks

if TYPE_CHECKING:
    from .block import CellBlock
    from .relax import Relaxation


@dataclass(frozen=True, eq=False, repr=False)
class Realization:
    """Realized strands.

    Attributes
    ----------
    curves : list of (n_k, 3) float64
        One polyline per strand (and per translate, see ``copy_of``).  A closed strand
        does not repeat its first point; ``closed[k]`` says to join the ends.
    closed : (n_curves,) bool
    strand_of : (n_curves,) int64
        Strand of the trace each curve realizes.
    copy_of : (n_curves,) int64
        Index into ``translations`` of the copy.
    scale, radius, normal_offset, margin, tube_radius, min_separation : float
        The parameters used.
    min_distance : float
        Smallest sampled distance between distinct pieces (non-adjacent stretches).
    closest : Closest or None
        Where it occurs: the two curves and the nearest scaffold element (``None`` when not measured).
    translations : (n_copies, dim) int64
        Lattice translations of the copies (one zero row for a single copy).
    block : CellBlock or None
        Set by :func:`lkspace.geometry.block.realize_block`: the block of cells the
        curves were cut to (threads end on its faces; closed loops are whole).
    relaxation : Relaxation or None
        Set by :func:`lkspace.geometry.relax.relax`: steps run and whether it converged.
    construction : list of (n_k, 3) float64, or None
        The curves as constructed, when ``curves`` are them smoothed (or were too many
        points to smooth): :func:`~lkspace.geometry.relax.relax` starts from them.
    """

    scaffold: Scaffold
    trace: Trace
    curves: list[np.ndarray]
    closed: np.ndarray
    strand_of: np.ndarray
    copy_of: np.ndarray
    scale: float
    radius: float
    normal_offset: float
    margin: float
    tube_radius: float
    min_separation: float
    min_distance: float
    closest: Closest | None = None
    translations: np.ndarray | None = None
    block: CellBlock | None = None
    relaxation: Relaxation | None = None
    construction: list[np.ndarray] | None = None

    def __repr__(self) -> str:
        points = sum(len(c) for c in self.curves)
        return (
            f"Realization({self.scaffold.name}: {self.n_curves} curves, {points} points, "
            f"min distance {self.min_distance:.3g} (>= {self.min_separation:.3g}))"
        )

    @property
    def n_curves(self) -> int:
        """Number of polylines (strands times copies)."""
        return len(self.curves)

    def summary(self) -> dict[str, object]:
        """Return a JSON-ready description of the realization (``"relaxation"`` when relaxed)."""
        out: dict[str, object] = {
            "curves": self.n_curves,
            "points": int(sum(len(c) for c in self.curves)),
            "closed": self.closed.tolist(),
            "scale": self.scale,
            "radius": self.radius,
            "normal_offset": self.normal_offset,
            "tube_radius": self.tube_radius,
            "min_distance": self.min_distance,
            "min_separation": self.min_separation,
            "closest": closest_json(self.closest),
        }
        if self.relaxation is not None:
            out["relaxation"] = self.relaxation.to_json()
        return out


def realize(
    scaffold: Scaffold,
    labels: ArrayLike | None = None,
    nulls: ArrayLike | None = None,
    params: GeometryParams | None = None,
    *,
    relax: bool = False,
    options: RealizeOptions | None = None,
) -> Realization:
    """Realize the strands of ``scaffold`` under twist ``labels`` as 3D polylines.

    The steps: resolve the parameters once (:class:`~lkspace.geometry.params.Resolved`),
    trace, lay the tracks, refuse what cannot be built (twists too tight, too many
    points, an embedding check beyond bounds), build the curves (corner turns and edge
    helices, cut into strands), smooth them, measure their clearance, relax them.

    Parameters
    ----------
    scaffold : Scaffold
        ``lkspace.realize`` also takes a path or a built-in name (:func:`lkspace.load`).
    labels, nulls : as for :func:`lkspace.trace` (default: the scaffold's own).
    params : GeometryParams, optional
        The shape: distances, sampling, smoothing.
    relax : bool
        Relax the curves toward a tight shape (:func:`~lkspace.geometry.relax.relax`, its
        default limits: until it converges; call it directly to set ``steps`` or ``time_limit``).
    options : RealizeOptions, optional
        How to go about it: the embedding check (``"refuse"`` by default), lattice
        translations of a block of copies, a trace to reuse, the point bound ``max_points``.

    Raises
    ------
    GeometryError
        Distinct pieces closer than ``min_separation`` (unless ``options.embedding`` says
        otherwise), or parameters that are not usable (a usage error naming the parameter).
    TooLargeError
        More curve points than ``options.max_points`` (the message starts ``max_points:``).

    Returns
    -------
    Realization

    Examples
    --------
    >>> import lkspace
    >>> r = lkspace.realize("dihedron:3", 1)
    >>> r.n_curves, bool(r.closed[0]), r.min_distance > r.min_separation
    (1, True, True)
    >>> lkspace.realize("dihedron:3", 1, options=lkspace.RealizeOptions(embedding="later")).min_distance
    inf
    """
    shape = Resolved.of(scaffold, params or GeometryParams())
    how = options or RealizeOptions()
    how.check()
    tr = how.trace if how.trace is not None else trace(scaffold, labels, nulls)
    built = _built(scaffold, tr, shape, how)
    smoothed = replace(built, curves=_smoothed(scaffold, tr, built, shape, how.embedding))
    real = _measured(scaffold, tr, smoothed, shape, how)
    if shape.smooth and tr.closed.all():
        real = replace(real, construction=built.curves)
    if relax:
        from .relax import relax as relax_curves

        real = relax_curves(real)
    return real


def realize_reusing(
    scaffold: Scaffold, tr: Trace, known: Mapping[bytes, StrandCurve], options: RealizeOptions | None = None
) -> tuple[Realization, dict[bytes, StrandCurve]]:
    """Realize the trace ``tr`` as :func:`realize` does, building only the curves not in ``known``.

    The answer is the one of ``realize(scaffold, options=replace(options, trace=tr,
    embedding="later"))``, default parameters: a curve depends only on its strand's steps,
    their edges' labels and the strand's period (its **key**), so a curve kept under its key
    is the curve realize would build.  The caller keeps the curves between calls (an edit
    changes the strands through one edge; the others keep theirs).  A finite scaffold whose
    strands all close is smoothed as a whole (every curve moves), and so are a periodic
    one's thread classes in the periodic cell: it is realized in full.

    Returns
    -------
    Realization, and every curve of it under its key (``known`` is not changed).
    """
    how = replace(options or RealizeOptions(), trace=tr, embedding="later")
    how.check()
    shape = Resolved.of(scaffold, GeometryParams())
    if shape.smooth and tr.closed.all():
        real = realize(scaffold, options=how)
        return real, {}
    fr, ports, counts, translations = _prepared(scaffold, tr, shape, how)
    edges = scaffold.side_edge[ports.y // 2]
    keys = [_strand_key(tr, ports, edges, s) for s in range(tr.components)]
    shifts = lattice_shift(scaffold, translations)
    wanted = [(keys[s] + t.tobytes(), s, c) for c, t in enumerate(translations) for s in range(tr.components)]
    missing = sorted({s for key, s, _ in wanted if key not in known})
    made: dict[bytes, StrandCurve] = {}
    if missing:
        base = build_curves(scaffold, fr, tr, ports, counts, shape, np.zeros_like(translations[:1]), np.array(missing))
        for curve, cl, s in zip(base.curves, base.closed, missing, strict=True):
            for c, t in enumerate(translations):
                moved = curve + shifts[c]  # as realize moves its copies
                made[keys[s] + t.tobytes()] = StrandCurve(
                    moved, bool(cl), tightest_bend([moved], np.array([cl])).radius
                )
    entries = {key: made[key] if key in made else known[key] for key, _, _ in wanted}
    chosen = [entries[key] for key, _, _ in wanted]
    built = Curves(
        [e.curve for e in chosen],
        np.array([e.closed for e in chosen], bool),
        np.array([s for _, s, _ in wanted], np.int64),
        np.array([c for _, _, c in wanted], np.int64),
        translations,
    )
    return _measured(scaffold, tr, built, shape, how, min((e.bend for e in chosen), default=np.inf)), entries


@dataclass(frozen=True, eq=False)
class StrandCurve:
    """One curve of :func:`realize_reusing`: its points, closed or not, and its tightest bend (for the tube radius)."""

    curve: np.ndarray
    closed: bool
    bend: float


def _strand_key(tr: Trace, ports: Ports, edges: np.ndarray, s: int) -> bytes:
    """Bytes that determine strand ``s``'s curve: its ports (cuts included), its edges' labels, closed and period."""
    steps = slice(tr.strand_starts[s], tr.strand_starts[s + 1])
    parts = [ports.x[steps], ports.z[steps], tr.labels[edges[steps]], tr.closed[s : s + 1], tr.periods[s]]
    return b"|".join(np.ascontiguousarray(p, np.int64).tobytes() for p in parts)


def _built(scaffold: Scaffold, tr: Trace, shape: Resolved, how: RealizeOptions) -> Curves:
    """Lay the tracks, refuse what cannot be built (twists too tight, too many points), build the curves."""
    fr, ports, counts, translations = _prepared(scaffold, tr, shape, how)
    return build_curves(scaffold, fr, tr, ports, counts, shape, translations)


def _prepared(
    scaffold: Scaffold, tr: Trace, shape: Resolved, how: RealizeOptions
) -> tuple[Tracks, Ports, np.ndarray, np.ndarray]:
    """Lay the tracks and refuse what cannot be built (twists too tight, too many points): tracks, ports, counts, translations."""
    fr = side_tracks(scaffold, shape.radius, shape.normal_offset, shape.margin, shape.near_angle)
    if how.embedding != "measure":
        check_winding(scaffold, fr.pa, fr.pb, fr.margin, tr.labels, shape.min_separation)
    translations = _translations(scaffold, how.translations)
    ports = Ports.of(scaffold, tr)
    counts = edge_counts(scaffold, tr.labels, ports, shape)
    check_points(
        scaffold.name, (counts.sum() + len(ports.x) * shape.corner_samples) * len(translations), how.max_points
    )
    if how.embedding != "later":
        check_samples(scaffold, tr.labels, shape.radius, shape.min_separation)
    return fr, ports, counts, translations


def _translations(scaffold: Scaffold, translations: ArrayLike | None) -> np.ndarray:
    """``(n_copies, dim) int64``: the lattice translations of the copies (one zero row by default)."""
    dim = scaffold.dim
    if translations is None:
        return np.zeros((1, dim), np.int64)
    if not dim:
        raise GeometryError(
            f"translations: copies need a periodic scaffold; {scaffold.name} is finite",
            usage=True,
            parameter="translations",
        )
    return np.asarray(translations, np.int64).reshape(-1, dim)


def _smoothed(
    scaffold: Scaffold, tr: Trace, built: Curves, shape: Resolved, embedding: EmbeddingCheck
) -> list[np.ndarray]:
    """Return the closed curves of a finite scaffold smoothed (``shape.smooth``), else ``curves`` as built.

    The flow keeps the link type of an embedding: unless the check is off
    (``"measure"``), the construction is proved one first.  A periodic scaffold's
    thread classes are smoothed in the periodic cell (:func:`smoothed_classes`).
    """
    if shape.smooth and scaffold.dim and tr.closed.all():
        from .threads import smoothed_classes

        return smoothed_classes(scaffold, tr, built, smooth_diameter(scaffold, shape.radius), embedding != "measure")
    if not shape.smooth or scaffold.dim or not built.closed.all():
        return built.curves
    if embedding != "measure":
        _clearance(scaffold, built.curves, built.closed, shape, "refuse", measure=False)
    return smooth_curves(built.curves, smooth_diameter(scaffold, shape.radius))


def _measured(
    scaffold: Scaffold, tr: Trace, built: Curves, shape: Resolved, how: RealizeOptions, bend: float | None = None
) -> Realization:
    """Measure the clearance (refusing a self-intersection under ``"refuse"``), choose the tube radius.

    ``bend``: the tightest bend of the curves, when known.
    """
    curves, closed = built.curves, built.closed
    min_dist, closest = (
        (float("inf"), None) if how.embedding == "later" else _clearance(scaffold, curves, closed, shape, how.embedding)
    )
    return Realization(
        scaffold,
        tr,
        curves,
        closed,
        built.strand_of,
        built.copy_of,
        shape.scale,
        shape.radius,
        shape.normal_offset,
        shape.margin,
        _tube_radius(shape, min_dist, tightest_bend(curves, closed).radius if bend is None else bend),
        shape.min_separation,
        float(min_dist),
        closest,
        built.translations,
    )


def _tube_radius(shape: Resolved, min_dist: float, bend: float) -> float:
    """Return the tube radius given, or one clear of the other strands that does not fold where the curves bend most (``bend``)."""
    if shape.tube_radius is not None:
        return float(shape.tube_radius)
    return float(min(TUBE * shape.scale, TUBE_GAP_SHARE * min_dist, TUBE_BEND_SHARE * bend))


def _clearance(
    scaffold: Scaffold,
    curves: list[np.ndarray],
    closed: np.ndarray,
    shape: Resolved,
    embedding: EmbeddingCheck,
    measure: bool = True,
) -> tuple[float, Closest | None]:
    """Smallest distance between distinct pieces and where; refuse a self-intersection when ``embedding == "refuse"``.

    ``measure=False``: only pieces closer than ``min_separation`` are looked for (the refusal).
    """
    min_sep = shape.min_separation
    min_dist, closest = check_embedding(curves, closed, min_sep, shape.scale, measure)
    if closest is not None:
        closest = closest.named(place_name(scaffold, closest.point))
    if embedding == "refuse" and min_dist < min_sep:
        assert closest is not None  # a distance below min_separation was measured somewhere
        raise GeometryError(
            f"{scaffold.name}: strands {closest.curves[0]} and {closest.curves[1]} come within "
            f"{min_dist:.3g} (< min_separation {min_sep:.3g}) near {closest.place}; the geometry would "
            "self-intersect (try a smaller `radius` or `normal_offset`)"
        )
    return min_dist, closest
