"""The construction of :mod:`~lkspace.geometry.realization`: corner turns and edge helices, cut into strands.

:func:`edge_counts` says how many points each edge piece gets (before anything is
built, so that too many are refused); :func:`build_curves` builds them: per step of the
trace, the Bézier turn across its face corner then the helix along its edge (module
docstring of :mod:`~lkspace.geometry.realization`), cut into one polyline per strand and
lattice copy.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..model.scaffold import Scaffold
from ..strands.ports import edge_partner, port_model
from ..strands.tracing import Trace
from .helix import edge_angles, even_offsets, helix_windows, twist_profile
from .params import Resolved
from .tracks import Tracks, bezier_controls, lattice_shift


@dataclass(frozen=True, eq=False)
class Curves:
    """Polylines built for a trace, one per strand and lattice copy.

    Attributes
    ----------
    curves : list of (n_k, 3) float64
    closed : (n_curves,) bool
    strand_of, copy_of : (n_curves,) int64
        The strand each curve realizes and the index of its copy's translation.
    translations : (n_copies, dim) int64
        The lattice translations of the copies.
    """

    curves: list[np.ndarray]
    closed: np.ndarray
    strand_of: np.ndarray
    copy_of: np.ndarray
    translations: np.ndarray


def build_curves(
    scaffold: Scaffold,
    fr: Tracks,
    tr: Trace,
    ports: Ports,
    counts: np.ndarray,
    shape: Resolved,
    translations: np.ndarray,
    strands: np.ndarray | None = None,
) -> Curves:
    """Build the strands of ``tr`` on the tracks ``fr``, ``counts`` points per edge piece (:func:`edge_counts`).

    With ``strands`` (indices into the trace), only those are built, in that order; every
    step is built on its own, so a strand's curve is the same built alone or with the others.
    """
    ids, starts = np.arange(tr.components), tr.strand_starts
    if strands is not None:
        ids = np.asarray(strands, np.int64)
        lengths = np.diff(starts)[ids]
        starts = np.concatenate([[0], np.cumsum(lengths)])
        steps = np.repeat(tr.strand_starts[ids] - starts[:-1], lengths) + np.arange(starts[-1])
        ports, counts = Ports(ports.x[steps], ports.y[steps], ports.z[steps], ports.shift[steps]), counts[steps]
    plan = _edge_plan(counts)
    corners, a_pt, c_pt = _corner_turns(fr, ports, shape.corner_samples)
    points = _assemble(corners, _edge_points(scaffold, fr, tr.labels, ports, plan, shape), plan)
    return _strand_curves(scaffold, tr, ids, starts, points, plan, a_pt, c_pt, translations)


@dataclass(frozen=True, eq=False)
class Ports:
    """Per step of the trace: the ports it joins and the lattice shift of its copy."""

    x: np.ndarray  # (n_steps,) port where the corner turn starts
    y: np.ndarray  # (n_steps,) port where it ends and the edge piece starts
    z: np.ndarray  # (n_steps,) port where the edge piece ends (-1 at a cut)
    shift: np.ndarray  # (n_steps, 3)

    @staticmethod
    def of(scaffold: Scaffold, tr: Trace) -> Ports:
        """Return the ports and lattice shifts of every step of ``tr``."""
        model = port_model(scaffold)
        x = tr.steps
        y = model.corner_partner[x]
        z = tr.edge_partner[y]
        if not scaffold.dim:
            return Ports(x, y, z, np.zeros((len(x), 3)))
        # lattice copy of every step: accumulate the translation of each edge link
        strand_of_step = np.repeat(np.arange(tr.components), np.diff(tr.strand_starts))
        st = scaffold.side_translation
        delta = np.where((z >= 0)[:, None], st[y // 2] - st[np.maximum(z, 0) // 2], 0)
        before = np.cumsum(delta, axis=0) - delta
        base = before[tr.strand_starts[:-1]]
        return Ports(x, y, z, lattice_shift(scaffold, before - base[strand_of_step]))


def _corner_turns(fr: Tracks, ports: Ports, nc: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Bézier turns from each port x's track end to port y's track start: ``(n_steps, nc, 3)``, ends a, c."""
    a_pt = fr.port_point[ports.x] + ports.shift
    c_pt = fr.port_point[ports.y] + ports.shift
    q_pt = bezier_controls(a_pt, fr.port_dir[ports.x], c_pt, -fr.port_dir[ports.y])
    u = np.arange(nc) / nc
    b0, b1, b2 = (1 - u) ** 2, 2 * u * (1 - u), u**2
    pts = b0[None, :, None] * a_pt[:, None] + b1[None, :, None] * q_pt[:, None] + b2[None, :, None] * c_pt[:, None]
    return pts, a_pt, c_pt


def corner_pieces(scaffold: Scaffold, fr: Tracks, shape: Resolved) -> np.ndarray:
    """Every corner turn, ``(n_corners, corner_samples + 1, 3)``, both ends included.

    Turn ``s`` runs inside its face from port ``2 s + 1`` (side ``s`` at its second
    corner) to that port's corner partner; a strand may pass it either way.
    """
    n = scaffold.n_corners
    x = 2 * np.arange(n) + 1
    y = port_model(scaffold).corner_partner[x]
    pts, _, c_pt = _corner_turns(fr, Ports(x, y, np.full(n, -1), np.zeros((n, 3))), shape.corner_samples)
    return np.concatenate([pts, c_pt[:, None]], axis=1)


def edge_pieces(scaffold: Scaffold, fr: Tracks, shape: Resolved, twist: int) -> tuple[np.ndarray, np.ndarray]:
    """Every slot's edge piece when every edge has twist ``twist``, both ends included.

    Piece ``j`` (a slot position of :class:`~lkspace.strands.ports.PortModel`) runs from
    the slot's end-``a`` port to the end-``b`` port the twist takes it to.  A piece depends
    on its own edge's twist only, so pieces of different twists can be mixed edge by edge.

    Returns
    -------
    points : (n_points, 3) float64
    offsets : (n_corners + 1,) int64
        Piece ``j`` is ``points[offsets[j]:offsets[j + 1]]``.
    """
    model = port_model(scaffold)
    labels = np.full(scaffold.n_edges, twist, np.int64)
    y = model.port_a
    z = edge_partner(model, scaffold.edge_degrees, labels)[y]
    ports = Ports(model.corner_partner[y], y, z, np.zeros((len(y), 3)))
    plan = _edge_plan(edge_counts(scaffold, labels, ports, shape))
    inner = _edge_points(scaffold, fr, labels, ports, plan, shape)
    sizes = plan.n_edge + 1
    offsets = np.concatenate([[0], np.cumsum(sizes)])
    points = np.empty((int(offsets[-1]), 3))
    keep = np.ones(len(points), bool)
    keep[offsets[1:] - 1] = False
    points[keep] = inner
    points[offsets[:-1]] = fr.port_point[y]  # exactly the ports, so pieces meet exactly
    points[offsets[1:] - 1] = fr.port_point[z]
    return points, offsets


@dataclass(frozen=True, eq=False)
class EdgePlan:
    """Sampling of the edge pieces: points per step and, per point, its step and parameter."""

    n_edge: np.ndarray  # (n_steps,) int64
    piece: np.ndarray  # (n_points,) step of each edge point
    offsets: np.ndarray  # (n_steps + 1,)
    sigma: np.ndarray  # (n_points,) in [0, 1)


def edge_counts(scaffold: Scaffold, labels: np.ndarray, ports: Ports, shape: Resolved) -> np.ndarray:
    """Points on each step's edge piece, ``(n_steps,) float64`` (floats: huge twists are refused, not cast)."""
    e = scaffold.side_edge[ports.y // 2]
    k = scaffold.edge_degrees[e]
    t = np.where(k > 1, labels[e], 0)
    turns = np.abs(t.astype(np.float64)) / k  # floats: -2**63 has no int64 abs
    return np.where(ports.z >= 0, shape.edge_samples + np.ceil(shape.samples_per_turn * turns), 0.0)


def _edge_plan(counts: np.ndarray) -> EdgePlan:
    n_edge = counts.astype(np.int64)
    piece = np.repeat(np.arange(len(n_edge)), n_edge)
    offsets = np.concatenate([[0], np.cumsum(n_edge)])
    sigma = (np.arange(len(piece)) - offsets[piece]) / np.maximum(n_edge[piece], 1)
    return EdgePlan(n_edge, piece, offsets, sigma)


def _edge_points(
    scaffold: Scaffold, fr: Tracks, labels: np.ndarray, ports: Ports, plan: EdgePlan, shape: Resolved
) -> np.ndarray:
    """Return the helices from port y to port z of every step, ``(n_points, 3)`` (module docstring)."""
    ys = ports.y // 2
    e = scaffold.side_edge[ys]
    degrees = scaffold.edge_degrees
    t = np.where(degrees[e] > 1, labels[e], 0)  # a lone strand's full turns about an empty axis: drawn straight
    piece, sig = plan.piece, plan.sigma
    fwd = ((ports.y % 2 == 0) == scaffold.side_forward[ys])[piece]  # port y at end a
    ep = e[piece]
    slot = scaffold.radial.side_slot[ys][piece]
    start, width = helix_windows(scaffold, fr, labels, shape.pitch)
    g = twist_profile((sig - start[ep]) / width[ep])
    xs = np.where(fwd, slot + t[piece] * g, slot - t[piece] * g)
    fa, fb = fr.margin[ep, 0], fr.margin[ep, 1]
    span = 1 - fa - fb
    par = np.where(fwd, fa + span * sig, 1 - fb - span * sig)
    theta0 = even_offsets(scaffold, fr)
    if shape.helix_radius is not None:
        helix_radius = np.full(scaffold.n_edges, float(shape.helix_radius))
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


def _assemble(corners: np.ndarray, edge_pts: np.ndarray, plan: EdgePlan) -> np.ndarray:
    """All points in trace order: per step, its corner turn then its edge piece, ``(n, 3)``."""
    nc = corners.shape[1]
    pos = np.concatenate([[0], np.cumsum(nc + plan.n_edge)])
    points = np.empty((int(pos[-1]), 3))
    points[(pos[:-1, None] + np.arange(nc)[None, :]).reshape(-1)] = corners.reshape(-1, 3)
    points[pos[plan.piece] + nc + (np.arange(len(plan.piece)) - plan.offsets[plan.piece])] = edge_pts
    return points


def _strand_curves(
    scaffold: Scaffold,
    tr: Trace,
    ids: np.ndarray,
    starts: np.ndarray,
    points: np.ndarray,
    plan: EdgePlan,
    a_pt: np.ndarray,
    c_pt: np.ndarray,
    translations: np.ndarray,
) -> Curves:
    """Cut the points into one polyline per strand and copy (strands ``ids``, owning steps ``starts[i]:starts[i + 1]``)."""
    nc = (len(points) - int(plan.n_edge.sum())) // max(len(plan.n_edge), 1)  # points per corner turn
    pos = np.concatenate([[0], np.cumsum(nc + plan.n_edge)])
    periods = tr.periods if scaffold.dim else np.zeros((tr.components, 0), np.int64)
    curves, closed_flags, strand_of, copy_of = [], [], [], []
    for c_i, shift in enumerate(lattice_shift(scaffold, translations)):
        for i, s_i in enumerate(ids.tolist()):
            first, last = starts[i], starts[i + 1] - 1
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
    flags = np.array(closed_flags, bool)
    return Curves(curves, flags, np.array(strand_of, np.int64), np.array(copy_of, np.int64), translations)
