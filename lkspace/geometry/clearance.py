"""Numerical embedding check of polylines: the smallest distance between distinct pieces.

Curves are resampled at a fixed spacing and the samples put in a ``scipy.spatial.cKDTree``.
Two samples belong to distinct pieces when they lie on different curves, or on one curve
farther apart along it than an exclusion length; open curves that continue one another
(the periods of one infinite thread in a block of lattice translates) count as one curve.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from functools import partial
from typing import TYPE_CHECKING, NamedTuple, cast

import numpy as np
from numpy.typing import ArrayLike

from ..runtime.workers import interruptible

if TYPE_CHECKING:
    from scipy.spatial import cKDTree


@dataclass(frozen=True)
class Closest:
    """Where distinct pieces of the curves come closest (:func:`check_embedding`).

    Attributes
    ----------
    curves : (int, int)
        The two curves, smaller first (one curve twice for two stretches of it).
    point : (float, float, float)
        The midpoint of the two closest samples.
    place : str, optional
        The scaffold vertex or edge nearest to it, when named (:func:`lkspace.geometry.tracks.place_name`).
    """

    curves: tuple[int, int]
    point: tuple[float, float, float]
    place: str | None = None

    def named(self, place: str) -> Closest:
        """Return this point named ``place``."""
        return replace(self, place=place)

    def to_json(self) -> dict[str, object]:
        """Return ``{"curves": [i, j], "point": [x, y, z]}`` and ``"place"`` when named."""
        out: dict[str, object] = {"curves": list(self.curves), "point": list(self.point)}
        if self.place is not None:
            out["place"] = self.place
        return out

    @classmethod
    def from_json(cls, data: Mapping[str, object] | None) -> Closest | None:
        """Read :meth:`to_json`; ``None`` for an empty object (nothing measured)."""
        if not data:
            return None
        curves, point = cast(Sequence[int], data["curves"]), cast(Sequence[float], data["point"])
        place = data.get("place")
        return cls(
            (int(curves[0]), int(curves[1])),
            (float(point[0]), float(point[1]), float(point[2])),
            None if place is None else str(place),
        )


def closest_json(closest: Closest | None) -> dict[str, object]:
    """Return ``closest`` as JSON: ``{}`` when nothing was measured."""
    return {} if closest is None else closest.to_json()


CHUNK = 20_000
"""Samples whose neighbours the coarse pass of :func:`check_embedding` examines at once (bounds its memory)."""


def sample_tree(points: np.ndarray) -> cKDTree:
    """Return a KD-tree of curve samples ``(n, 3)``, built without compacted nodes.

    Compacted nodes (scipy's default) make ``query_pairs`` at about the sampling step
    pathologically slow on samples along straight or planar runs: 59 s instead of 3 s
    for 3 million samples of the cube's strands.  (scipy is imported here, not with the
    module: commands that only name designs by key import this module, 0.1 s less.)
    """
    from scipy.spatial import cKDTree

    return interruptible(lambda: cKDTree(points, compact_nodes=False), len(points))


class Resampled(NamedTuple):
    """A polyline resampled at a fixed spacing (:func:`resample`)."""

    points: np.ndarray
    """(m, 3) float64"""
    arclength: np.ndarray
    """(m,) float64: the arclength of each point from the start"""
    length: float
    """The whole length (a closed polyline's includes its closing segment)."""


def resample(curve: np.ndarray, closed: bool, spacing: float) -> Resampled:
    """Return the points every ``spacing`` along a polyline (:class:`Resampled`)."""
    pts = np.vstack([curve, curve[:1]]) if closed else curve
    seg = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    cum = np.concatenate([[0.0], np.cumsum(seg)])
    length = float(cum[-1])
    m = max(2, int(np.ceil(length / spacing)) + (0 if closed else 1))
    s = np.linspace(0.0, length, m, endpoint=not closed)
    out = np.column_stack([np.interp(s, cum, pts[:, i]) for i in range(3)])
    return Resampled(out, s, length)


def pieces_apart(
    owner: np.ndarray,
    arc: np.ndarray,
    lengths: np.ndarray,
    closed: np.ndarray,
    i: np.ndarray,
    j: np.ndarray,
    exclusion: float,
    joins: list[tuple[int, int]] | None = None,
) -> np.ndarray:
    """Mask of sample pairs ``(i, j)`` on distinct pieces (other curve, or far along one).

    ``joins`` maps ``(curve_a, curve_b)`` to True when ``a``'s end is ``b``'s start (the
    periods of one infinite thread in a block of translates): their near-end samples
    count as one piece.
    """
    oi, oj = owner[i], owner[j]
    same = oi == oj
    along = np.abs(arc[i] - arc[j])
    cyc = closed[oi]
    along = np.where(same & cyc, np.minimum(along, lengths[oi] - along), along)
    apart = ~same | (along > exclusion)
    if joins:  # vectorized over the pairs: one table lookup per orientation
        pair_keys = np.unique(np.array([a * len(lengths) + b for a, b in joins], np.int64))
        for x, y in ((i, j), (j, i)):
            keys = owner[x].astype(np.int64) * len(lengths) + owner[y]
            at = np.minimum(np.searchsorted(pair_keys, keys), len(pair_keys) - 1)
            m = pair_keys[at] == keys  # np.isin sorts all the keys: seconds for millions of pairs
            if m.any():
                gap = (lengths[owner[x[m]]] - arc[x[m]]) + arc[y[m]]
                apart[m] &= gap > exclusion
    return apart


def _joins(curves: Sequence[np.ndarray], closed: np.ndarray, tol: float) -> list[tuple[int, int]]:
    """Pairs ``(a, b)`` of open curves where ``a`` ends at ``b``'s start."""
    open_ids = [k for k, c in enumerate(closed) if not c]
    if len(open_ids) < 2:
        return []
    starts = np.array([curves[k][0] for k in open_ids])
    ends = np.array([curves[k][-1] for k in open_ids])
    from scipy.spatial import cKDTree

    pairs = cKDTree(ends).query_ball_point(starts, tol)
    return [(open_ids[a], open_ids[b]) for b, hits in enumerate(pairs) for a in hits if a != b]


def samples(
    curves: Sequence[np.ndarray], closed: np.ndarray, spacing: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Resample every curve at ``spacing``: ``(points, arclength, owner curve, curve lengths)``."""
    chunks = [resample(c, bool(cl), spacing) for c, cl in zip(curves, closed, strict=False)]
    pts = np.vstack([c.points for c in chunks])
    arc = np.concatenate([c.arclength for c in chunks])
    owner = np.repeat(np.arange(len(chunks)), [len(c.points) for c in chunks])
    lengths = np.array([c.length for c in chunks])
    return pts, arc, owner, lengths


def check_embedding(
    curves: Sequence[np.ndarray], closed: ArrayLike, min_separation: float, scale: float, measure: bool = True
) -> tuple[float, Closest | None]:
    """Smallest distance between distinct pieces of the polylines (sampled).

    Two sample points are on distinct pieces when they lie on different curves, or on one
    curve farther apart along it than ``4 * min_separation`` (fine pass) or ``0.3 *
    scale`` (coarse pass).  The fine pass samples every ``min_separation / 2`` and finds
    every pair closer than ``min_separation`` (so a true crossing is always found); the
    coarse pass samples every ``0.02 * scale`` and finds the nearest distinct piece of
    every sample among its 48 nearest neighbours, up to ``0.3 * scale``.  ``measure=False``
    skips the coarse pass: enough to tell whether two pieces come closer than
    ``min_separation`` (the distance is ``inf`` when none do).

    Returns
    -------
    min_distance : float
        ``inf`` when no two distinct pieces come within ``0.3 * scale``.
    closest : Closest or None
        The two curves and the midpoint of the closest pair (``None`` if none).
    """
    closed = np.asarray(closed, bool)
    joins = _joins(curves, closed, 1e-9 * max(1.0, scale))
    best = float("inf")
    where: Closest | None = None

    def consider(pts: np.ndarray, owner: np.ndarray, i: np.ndarray, j: np.ndarray) -> None:
        nonlocal best, where
        if len(i) == 0:
            return
        d = np.linalg.norm(pts[i] - pts[j], axis=1)
        b = int(np.argmin(d))
        if d[b] < best:
            best = float(d[b])
            c0, c1 = sorted([int(owner[i[b]]), int(owner[j[b]])])
            x, y, z = (0.5 * (pts[i[b]] + pts[j[b]])).tolist()
            where = Closest((c0, c1), (x, y, z))

    pts, arc, owner, lengths = samples(curves, closed, min_separation / 2.0)
    fine = sample_tree(pts)
    pairs = interruptible(lambda: fine.query_pairs(min_separation, output_type="ndarray"), len(pts))
    if len(pairs):
        keep = pieces_apart(owner, arc, lengths, closed, pairs[:, 0], pairs[:, 1], 4 * min_separation, joins)
        consider(pts, owner, pairs[keep, 0], pairs[keep, 1])
    if not measure:
        return best, where
    spacing = max(min_separation / 2.0, 0.02 * scale)
    pts, arc, owner, lengths = samples(curves, closed, spacing)
    k = min(48, len(pts))
    tree = sample_tree(pts)
    for lo in range(0, len(pts), CHUNK):  # in chunks: k neighbours per sample take ~3 kB each
        hi = min(lo + CHUNK, len(pts))
        _, nb = interruptible(partial(tree.query, pts[lo:hi], k=k, distance_upper_bound=0.3 * scale), hi - lo)
        i = np.repeat(np.arange(lo, hi), k)
        j = nb.reshape(-1)
        found = j < len(pts)
        i, j = i[found], j[found]
        keep = pieces_apart(owner, arc, lengths, closed, i, j, 0.3 * scale, joins)
        consider(pts, owner, i[keep], j[keep])
    return best, where


class Bend(NamedTuple):
    """The tightest bend of some polylines (:func:`tightest_bend`)."""

    radius: float
    """The smallest bend radius (``inf`` for straight polylines)."""
    piece: int
    """The polyline it is on (-1 if none bends)."""
    point: np.ndarray
    """(3,) float64: the point where it bends."""


def tightest_bend(curves: list[np.ndarray], closed: np.ndarray) -> Bend:
    """Return the smallest bend radius of the centrelines, its piece and point (:class:`Bend`).

    At a polyline point where the direction turns by ``theta`` between segments of
    lengths ``a`` and ``b``, the bend radius is ``min(a, b) / 2 / tan(theta / 2)`` (the
    circle tangent to both segments at the nearer midpoint distance).
    """
    best, piece, where = np.inf, -1, np.zeros(3)
    for k, (c, cl) in enumerate(zip(curves, closed, strict=True)):
        pts = np.vstack([c[-1:], c, c[:1]]) if cl else c
        seg = np.diff(pts, axis=0)
        a, b = seg[:-1], seg[1:]
        la, lb = np.linalg.norm(a, axis=1), np.linalg.norm(b, axis=1)
        ok = (la > 0) & (lb > 0)
        cosang = np.einsum("ij,ij->i", a, b) / np.where(ok, la * lb, 1.0)
        turn = np.arccos(np.clip(cosang, -1.0, 1.0))
        bend = np.where(ok & (turn > 1e-9), 0.5 * np.minimum(la, lb) / np.tan(0.5 * np.maximum(turn, 1e-9)), np.inf)
        if len(bend) and bend.min() < best:
            i = int(np.argmin(bend))
            best, piece, where = float(bend[i]), k, pts[i + 1]
    return Bend(float(best), piece, where)
