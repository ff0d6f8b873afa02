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
from ..io.sources import ScaffoldSource, load
from ..model.scaffold import Scaffold
from ..strands.ports import port_model
from ..strands.tracing import Trace, trace
from .clearance import check_embedding, tightest_bend
from .helix import edge_angles, even_offsets, helix_windows, twist_profile
from .limits import MAX_POINTS, MAX_SAMPLES, check_lengths, check_samples, check_small, check_winding
from .tracks import bezier_controls, default_scale, lattice_shift, place_name, side_tracks

if TYPE_CHECKING:
    from .block import Block


NEAR_ANGLE = np.pi / 6
"""Faces meeting at an edge at less than this angle get the default normal offset."""


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
    block : Block or None
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
    block: Block | None = None

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
    scaffold: ScaffoldSource,
    labels: ArrayLike | None = None,
    nulls: ArrayLike | None = None,
    params: GeometryParams | None = None,
    translations: ArrayLike | None = None,
    check: bool = True,
    result: Trace | None = None,
    max_points: int = MAX_POINTS,
    bound: str = "MAX_POINTS",
    measure: bool = True,
) -> Realization:
    """Realize the strands of ``scaffold`` under twist ``labels`` as 3D polylines.

    Parameters
    ----------
    scaffold : Scaffold, path or built-in name
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

    Returns
    -------
    Realization

    Examples
    --------
    >>> r = realize("dihedron:3", 1)
    >>> r.n_curves, bool(r.closed[0]), r.min_distance > r.min_separation
    (1, True, True)
    """
    scaffold = load(scaffold)
    params = params or GeometryParams()
    params.check()
    tr = result if result is not None else trace(scaffold, labels, nulls)
    scale = default_scale(scaffold)
    rho = params.radius if params.radius is not None else 0.12 * scale
    h = params.normal_offset if params.normal_offset is not None else 0.35 * rho
    margin = params.margin if params.margin is not None else 0.28 * scale
    min_sep = params.min_separation if params.min_separation is not None else 0.01 * scale
    for name, value in (("radius", rho), ("margin", margin), ("min_separation", min_sep)):
        if not np.isfinite(value) or value <= 0:
            raise GeometryError(f"geometry parameter {name} must be positive, got {value}")
    lengths = {"radius": rho, "normal_offset": h, "margin": margin, "tube_radius": params.tube_radius or 0.0}
    lengths["helix_radius"] = params.helix_radius or 0.0
    check_lengths(scaffold.name, lengths, scale)
    check_small(scaffold.name, {**lengths, "pitch": params.pitch}, scale)
    fr = side_tracks(scaffold, rho, h, margin, NEAR_ANGLE if params.normal_offset is None else None)
    if check:
        check_winding(scaffold, fr.pa, fr.pb, fr.margin, tr.labels, min_sep)
    model = port_model(scaffold)
    cp = model.corner_partner
    twist = tr.labels
    degrees = scaffold.edge_degrees
    dim = scaffold.dim

    steps = tr.steps
    n_steps = len(steps)
    strand_of_step = np.repeat(np.arange(tr.components), np.diff(tr.strand_starts))
    x = steps
    y = cp[x]
    z = tr.edge_partner[y]  # -1 at a cut
    # lattice copy of every step: accumulate the translation of each edge link
    if dim:
        st = scaffold.side_translation
        delta = np.where((z >= 0)[:, None], st[y // 2] - st[np.maximum(z, 0) // 2], 0)
        cum = np.cumsum(delta, axis=0)
        before = cum - delta
        base = before[tr.strand_starts[:-1]]
        copy_t = before - base[strand_of_step]
        step_shift = lattice_shift(scaffold, copy_t)
    else:
        step_shift = np.zeros((n_steps, 3))

    # corner turns: Bézier from the port x's track end to port y's track start
    nc = max(2, int(params.corner_samples))
    a_pt = fr.port_point[x] + step_shift
    c_pt = fr.port_point[y] + step_shift
    q_pt = bezier_controls(a_pt, fr.port_dir[x], c_pt, -fr.port_dir[y])
    u = np.arange(nc) / nc
    b0, b1, b2 = (1 - u) ** 2, 2 * u * (1 - u), u**2
    corner_pts = (
        b0[None, :, None] * a_pt[:, None] + b1[None, :, None] * q_pt[:, None] + b2[None, :, None] * c_pt[:, None]
    )  # (n_steps, nc, 3)

    # edge pieces: the helix from port y to port z
    ys = y // 2
    e = scaffold.side_edge[ys]
    k = degrees[e]
    t = np.where(k > 1, twist[e], 0)  # a lone strand's full turns about an empty axis are a curl: drawn straight
    has_edge = z >= 0
    turns = np.abs(t.astype(np.float64)) / k  # floats: -2**63 has no int64 abs
    n_edge = np.where(has_edge, params.edge_samples + np.ceil(params.samples_per_turn * turns), 0)
    n_copies = 1 if translations is None else max(1, np.size(translations) // max(dim, 1))
    estimate = (float(n_edge.sum()) + n_steps * nc) * n_copies
    if estimate > max_points:
        raise TooLargeError(
            f"{scaffold.name}: the curves would have about {estimate:,.0f} points > {max_points:,} ({bound}); "
            "use smaller twists (or a smaller block)"
        )
    if measure:
        check_samples(scaffold, tr.labels, rho, min_sep)
    n_edge = n_edge.astype(np.int64)
    piece = np.repeat(np.arange(n_steps), n_edge)
    offsets = np.concatenate([[0], np.cumsum(n_edge)])
    sig = (np.arange(len(piece)) - offsets[piece]) / np.maximum(n_edge[piece], 1)
    fwd = ((y % 2 == 0) == scaffold.side_forward[ys])[piece]  # port y at end a
    ep = e[piece]
    slot = scaffold.radial.side_slot[ys][piece]
    start, width = helix_windows(scaffold, fr, twist, params.pitch)
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
    edge_pts = (
        fr.pa[ep]
        + par[:, None] * (fr.pb[ep] - fr.pa[ep])
        + fr.side_shift[ys][piece]
        + step_shift[piece]
        + rad[:, None] * (np.cos(phi)[:, None] * fr.u1[ep] + np.sin(phi)[:, None] * fr.u2[ep])
    )

    # assemble: per step, the corner turn then its edge piece
    per_step = nc + n_edge
    pos = np.concatenate([[0], np.cumsum(per_step)])
    total = int(pos[-1])
    points = np.empty((total, 3))
    corner_index = pos[:-1, None] + np.arange(nc)[None, :]
    points[corner_index.reshape(-1)] = corner_pts.reshape(-1, 3)
    edge_index = pos[piece] + nc + (np.arange(len(piece)) - offsets[piece])
    points[edge_index] = edge_pts
    curves, closed_flags, strand_of, copy_of = [], [], [], []
    periods = tr.periods if dim else np.zeros((tr.components, 0), np.int64)
    if translations is not None and not dim:
        raise GeometryError(f"{scaffold.name}: translated copies need a periodic scaffold")
    translations = (
        np.zeros((1, dim), np.int64) if translations is None else np.asarray(translations, np.int64).reshape(-1, dim)
    )
    copy_shift = lattice_shift(scaffold, translations)
    for c_i, shift in enumerate(copy_shift):
        for s_i in range(tr.components):
            lo, hi = pos[tr.strand_starts[s_i]], pos[tr.strand_starts[s_i + 1]]
            pts = points[lo:hi]
            is_closed = bool(tr.closed[s_i]) and not np.any(periods[s_i] != 0)
            if not tr.closed[s_i]:
                last = tr.strand_starts[s_i + 1] - 1
                pts = np.vstack([pts, c_pt[last]])
            elif not is_closed:  # one period of an infinite thread
                last = tr.strand_starts[s_i + 1] - 1
                first = tr.strand_starts[s_i]
                pts = np.vstack([pts, a_pt[first] + lattice_shift(scaffold, periods[s_i][None])[0]])
            curves.append(pts + shift)
            closed_flags.append(is_closed)
            strand_of.append(s_i)
            copy_of.append(c_i)
    closed = np.array(closed_flags, bool)
    min_dist, closest = check_embedding(curves, closed, min_sep, scale) if measure else (float("inf"), {})
    if closest:
        closest["place"] = place_name(scaffold, closest["point"])
    if check and min_dist < min_sep:
        raise GeometryError(
            f"{scaffold.name}: strands {closest['curves'][0]} and {closest['curves'][1]} come within "
            f"{min_dist:.3g} (< min_separation {min_sep:.3g}) near {closest['place']}; the geometry would "
            "self-intersect (try a smaller --radius or --normal-offset)"
        )
    if params.tube_radius is not None:
        tube = params.tube_radius
    else:  # thin enough to stay clear of the other strands and not to fold where a curve bends
        tube = min(0.03 * scale, 0.45 * min_dist, 0.9 * tightest_bend(curves, closed)[0])
    return Realization(
        scaffold,
        tr,
        curves,
        closed,
        np.array(strand_of, np.int64),
        np.array(copy_of, np.int64),
        scale,
        float(rho),
        float(h),
        float(margin),
        float(tube),
        float(min_sep),
        float(min_dist),
        closest,
        translations,
    )
