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
an open polyline.  ``translations`` realizes a block of lattice translates at once.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from ..errors import GeometryError, TooLargeError
from ..model.scaffold import Scaffold
from ..strands.ports import port_model
from ..strands.tracing import Trace, trace
from .clearance import check_embedding, tightest_bend
from .flow import smooth_curves
from .helix import edge_angles, even_offsets, helix_windows, twist_profile
from .limits import MAX_POINTS, check_samples, check_winding
from .params import SMOOTH_DIAMETER, TUBE, GeometryParams, Resolved
from .tracks import Tracks, bezier_controls, lattice_shift, place_name, side_tracks

if TYPE_CHECKING:
    from .block import CellBlock


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
    closest : dict
        Where it occurs: the two curves and the nearest scaffold element.
    translations : (n_copies, dim) int64
        Lattice translations of the copies (one zero row for a single copy).
    block : CellBlock or None
        Set by :func:`lkspace.geometry.block.realize_block`: the block of cells the
        curves were cut to (threads end on its faces; closed loops are whole).
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
    closest: dict[str, Any] = field(default_factory=dict)
    translations: np.ndarray | None = None
    block: CellBlock | None = None

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

    def summary(self) -> dict[str, Any]:
        """Return a JSON-ready description of the realization."""
        return {
            "curves": self.n_curves,
            "points": int(sum(len(c) for c in self.curves)),
            "closed": self.closed.tolist(),
            "scale": self.scale,
            "radius": self.radius,
            "normal_offset": self.normal_offset,
            "tube_radius": self.tube_radius,
            "min_distance": self.min_distance,
            "min_separation": self.min_separation,
            "closest": self.closest,
        }


def realize(
    scaffold: Scaffold,
    labels: ArrayLike | None = None,
    nulls: ArrayLike | None = None,
    params: GeometryParams | None = None,
    translations: ArrayLike | None = None,
    check: bool = True,
    result: Trace | None = None,
    max_points: int = MAX_POINTS,
    bound: str = "MAX_POINTS",
    measure: bool = True,
    relax: bool = False,
) -> Realization:
    """Realize the strands of ``scaffold`` under twist ``labels`` as 3D polylines.

    Parameters
    ----------
    scaffold : Scaffold
        ``lkspace.realize`` also takes a path or a built-in name (:func:`lkspace.load`).
    labels, nulls : as for :func:`lkspace.trace` (default: the scaffold's own).
    params : GeometryParams, optional
    translations : (n_copies, dim) int, optional
        Lattice translations of a block of copies (periodic scaffolds); default one copy.
    check : bool
        Verify the embedding (:func:`check_embedding`) and raise :class:`GeometryError`
        when distinct pieces come closer than ``min_separation``.
    result : Trace, optional
        A trace already computed for these labels.
    max_points : int
        Refuse (:class:`~lkspace.errors.TooLargeError`, before building anything) when
        the curves would have more points (default :data:`MAX_POINTS`); ``bound`` names
        the limit in the message.
    measure : bool
        Measure the clearance (:func:`check_embedding`); ``False`` skips it and the check
        (``min_distance`` is ``inf``), for previews that measure later.
    relax : bool
        Relax the curves toward a tight shape (:func:`~lkspace.geometry.relax.relax`).

    Returns
    -------
    Realization

    Examples
    --------
    >>> import lkspace
    >>> r = lkspace.realize("dihedron:3", 1)
    >>> r.n_curves, bool(r.closed[0]), r.min_distance > r.min_separation
    (1, True, True)
    """
    opts = Resolved.of(scaffold, params or GeometryParams())
    params = params or GeometryParams()
    tr = result if result is not None else trace(scaffold, labels, nulls)
    fr = side_tracks(scaffold, opts.radius, opts.normal_offset, opts.margin, opts.near_angle)
    if check:
        check_winding(scaffold, fr.pa, fr.pb, fr.margin, tr.labels, opts.min_separation)
    if translations is not None and not scaffold.dim:
        raise GeometryError(f"{scaffold.name}: translated copies need a periodic scaffold")
    dim = scaffold.dim
    translations = (
        np.zeros((1, dim), np.int64) if translations is None else np.asarray(translations, np.int64).reshape(-1, dim)
    )
    ports = _Ports.of(scaffold, tr)
    counts = _edge_counts(scaffold, tr, ports, params)
    estimate = (float(counts.sum()) + len(ports.x) * opts.corner_samples) * len(translations)
    if estimate > max_points:
        raise TooLargeError(
            f"{scaffold.name}: the curves would have about {estimate:,.0f} points > {max_points:,} ({bound}); "
            "use smaller twists (or a smaller block)"
        )
    if measure:
        check_samples(scaffold, tr.labels, opts.radius, opts.min_separation)
    edges = _edge_plan(counts)
    corners, a_pt, c_pt = _corner_turns(fr, ports, opts.corner_samples)
    points = _assemble(corners, _edge_points(scaffold, fr, tr, ports, edges, params), edges)
    curves, closed, strand_of, copy_of = _strand_curves(scaffold, tr, points, edges, a_pt, c_pt, translations)
    if params.smooth and not dim and closed.all():
        if check:  # the flow keeps the link type of an embedding: the construction must be one
            _clearance(scaffold, curves, closed, opts, check)
        curves = smooth_curves(curves, SMOOTH_DIAMETER * opts.radius)
    real = _measured(scaffold, tr, curves, closed, strand_of, copy_of, opts, params, check, measure, translations)
    if relax:
        from .relax import relax as relax_curves

        real = relax_curves(real)
    return real


@dataclass(frozen=True, eq=False)
class _Ports:
    """Per step of the trace: the ports it joins and the lattice shift of its copy."""

    x: np.ndarray  # (n_steps,) port where the corner turn starts
    y: np.ndarray  # (n_steps,) port where it ends and the edge piece starts
    z: np.ndarray  # (n_steps,) port where the edge piece ends (-1 at a cut)
    shift: np.ndarray  # (n_steps, 3)

    @staticmethod
    def of(scaffold: Scaffold, tr: Trace) -> _Ports:
        model = port_model(scaffold)
        x = tr.steps
        y = model.corner_partner[x]
        z = tr.edge_partner[y]
        if not scaffold.dim:
            return _Ports(x, y, z, np.zeros((len(x), 3)))
        # lattice copy of every step: accumulate the translation of each edge link
        strand_of_step = np.repeat(np.arange(tr.components), np.diff(tr.strand_starts))
        st = scaffold.side_translation
        delta = np.where((z >= 0)[:, None], st[y // 2] - st[np.maximum(z, 0) // 2], 0)
        before = np.cumsum(delta, axis=0) - delta
        base = before[tr.strand_starts[:-1]]
        return _Ports(x, y, z, lattice_shift(scaffold, before - base[strand_of_step]))


def _corner_turns(fr: Tracks, ports: _Ports, nc: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Bézier turns from each port x's track end to port y's track start: ``(n_steps, nc, 3)``, ends a, c."""
    a_pt = fr.port_point[ports.x] + ports.shift
    c_pt = fr.port_point[ports.y] + ports.shift
    q_pt = bezier_controls(a_pt, fr.port_dir[ports.x], c_pt, -fr.port_dir[ports.y])
    u = np.arange(nc) / nc
    b0, b1, b2 = (1 - u) ** 2, 2 * u * (1 - u), u**2
    pts = b0[None, :, None] * a_pt[:, None] + b1[None, :, None] * q_pt[:, None] + b2[None, :, None] * c_pt[:, None]
    return pts, a_pt, c_pt


@dataclass(frozen=True, eq=False)
class _EdgePlan:
    """Sampling of the edge pieces: points per step and, per point, its step and parameter."""

    n_edge: np.ndarray  # (n_steps,) int64
    piece: np.ndarray  # (n_points,) step of each edge point
    offsets: np.ndarray  # (n_steps + 1,)
    sigma: np.ndarray  # (n_points,) in [0, 1)


def _edge_counts(scaffold: Scaffold, tr: Trace, ports: _Ports, params: GeometryParams) -> np.ndarray:
    """Points on each step's edge piece, ``(n_steps,) float64`` (floats: huge twists are refused, not cast)."""
    e = scaffold.side_edge[ports.y // 2]
    k = scaffold.edge_degrees[e]
    t = np.where(k > 1, tr.labels[e], 0)
    turns = np.abs(t.astype(np.float64)) / k  # floats: -2**63 has no int64 abs
    return np.where(ports.z >= 0, params.edge_samples + np.ceil(params.samples_per_turn * turns), 0.0)


def _edge_plan(counts: np.ndarray) -> _EdgePlan:
    n_edge = counts.astype(np.int64)
    piece = np.repeat(np.arange(len(n_edge)), n_edge)
    offsets = np.concatenate([[0], np.cumsum(n_edge)])
    sigma = (np.arange(len(piece)) - offsets[piece]) / np.maximum(n_edge[piece], 1)
    return _EdgePlan(n_edge, piece, offsets, sigma)


def _edge_points(
    scaffold: Scaffold, fr: Tracks, tr: Trace, ports: _Ports, plan: _EdgePlan, params: GeometryParams
) -> np.ndarray:
    """Return the helices from port y to port z of every step, ``(n_points, 3)`` (module docstring)."""
    ys = ports.y // 2
    e = scaffold.side_edge[ys]
    degrees = scaffold.edge_degrees
    t = np.where(degrees[e] > 1, tr.labels[e], 0)  # a lone strand's full turns about an empty axis: drawn straight
    piece, sig = plan.piece, plan.sigma
    fwd = ((ports.y % 2 == 0) == scaffold.side_forward[ys])[piece]  # port y at end a
    ep = e[piece]
    slot = scaffold.radial.side_slot[ys][piece]
    start, width = helix_windows(scaffold, fr, tr.labels, params.pitch)
    g = twist_profile((sig - start[ep]) / width[ep])
    xs = np.where(fwd, slot + t[piece] * g, slot - t[piece] * g)
    fa, fb = fr.margin[ep, 0], fr.margin[ep, 1]
    span = 1 - fa - fb
    par = np.where(fwd, fa + span * sig, 1 - fb - span * sig)
    theta0 = even_offsets(scaffold, fr)
    if params.helix_radius is not None:
        helix_radius = np.full(scaffold.n_edges, float(params.helix_radius))
    else:
        helix_radius = np.bincount(
            scaffold.side_edge[scaffold.radial.edge_sides], fr.slot_radius, minlength=scaffold.n_edges
        ) / np.maximum(degrees, 1)
    phi, rad = edge_angles(fr, scaffold, ep, xs, sig, theta0, helix_radius)
    return (
        fr.pa[ep]
        + par[:, None] * (fr.pb[ep] - fr.pa[ep])
        + fr.side_shift[ys][piece]
        + ports.shift[piece]
        + rad[:, None] * (np.cos(phi)[:, None] * fr.u1[ep] + np.sin(phi)[:, None] * fr.u2[ep])
    )


def _assemble(corners: np.ndarray, edge_pts: np.ndarray, plan: _EdgePlan) -> np.ndarray:
    """All points in trace order: per step, its corner turn then its edge piece, ``(n, 3)``."""
    n_steps, nc = corners.shape[:2]
    pos = np.concatenate([[0], np.cumsum(nc + plan.n_edge)])
    points = np.empty((int(pos[-1]), 3))
    points[(pos[:-1, None] + np.arange(nc)[None, :]).reshape(-1)] = corners.reshape(-1, 3)
    points[pos[plan.piece] + nc + (np.arange(len(plan.piece)) - plan.offsets[plan.piece])] = edge_pts
    return points


def _strand_curves(
    scaffold: Scaffold,
    tr: Trace,
    points: np.ndarray,
    plan: _EdgePlan,
    a_pt: np.ndarray,
    c_pt: np.ndarray,
    translations: np.ndarray,
) -> tuple[list[np.ndarray], np.ndarray, np.ndarray, np.ndarray]:
    """Cut the points into one polyline per strand and copy: ``(curves, closed, strand_of, copy_of)``."""
    nc = (len(points) - int(plan.n_edge.sum())) // max(len(plan.n_edge), 1)  # points per corner turn
    pos = np.concatenate([[0], np.cumsum(nc + plan.n_edge)])
    periods = tr.periods if scaffold.dim else np.zeros((tr.components, 0), np.int64)
    curves, closed_flags, strand_of, copy_of = [], [], [], []
    for c_i, shift in enumerate(lattice_shift(scaffold, translations)):
        for s_i in range(tr.components):
            first, last = tr.strand_starts[s_i], tr.strand_starts[s_i + 1] - 1
            pts = points[pos[first] : pos[last + 1]]
            is_closed = bool(tr.closed[s_i]) and not np.any(periods[s_i] != 0)
            if not tr.closed[s_i]:
                pts = np.vstack([pts, c_pt[last]])
            elif not is_closed:  # one period of an infinite thread
                pts = np.vstack([pts, a_pt[first] + lattice_shift(scaffold, periods[s_i][None])[0]])
            curves.append(pts + shift)
            closed_flags.append(is_closed)
            strand_of.append(s_i)
            copy_of.append(c_i)
    return curves, np.array(closed_flags, bool), np.array(strand_of, np.int64), np.array(copy_of, np.int64)


def _measured(
    scaffold: Scaffold,
    tr: Trace,
    curves: list[np.ndarray],
    closed: np.ndarray,
    strand_of: np.ndarray,
    copy_of: np.ndarray,
    opts: Resolved,
    params: GeometryParams,
    check: bool,
    measure: bool,
    translations: np.ndarray,
) -> Realization:
    """Measure the clearance, refuse a self-intersection (``check``), choose the tube radius."""
    min_dist, closest = _clearance(scaffold, curves, closed, opts, check) if measure else (float("inf"), {})
    if params.tube_radius is not None:
        tube = params.tube_radius
    else:  # thin enough to stay clear of the other strands and not to fold where a curve bends
        tube = min(TUBE * opts.scale, 0.45 * min_dist, 0.9 * tightest_bend(curves, closed)[0])
    return Realization(
        scaffold,
        tr,
        curves,
        closed,
        strand_of,
        copy_of,
        opts.scale,
        opts.radius,
        opts.normal_offset,
        opts.margin,
        float(tube),
        opts.min_separation,
        float(min_dist),
        closest,
        translations,
    )


def _clearance(
    scaffold: Scaffold, curves: list[np.ndarray], closed: np.ndarray, opts: Resolved, check: bool
) -> tuple[float, dict[str, Any]]:
    """Smallest distance between distinct pieces and where; refuse a self-intersection when ``check``."""
    min_sep = opts.min_separation
    min_dist, closest = check_embedding(curves, closed, min_sep, opts.scale)
    if closest:
        closest["place"] = place_name(scaffold, closest["point"])
    if check and min_dist < min_sep:
        raise GeometryError(
            f"{scaffold.name}: strands {closest['curves'][0]} and {closest['curves'][1]} come within "
            f"{min_dist:.3g} (< min_separation {min_sep:.3g}) near {closest['place']}; the geometry would "
            "self-intersect (try a smaller --radius or --normal-offset)"
        )
    return min_dist, closest
