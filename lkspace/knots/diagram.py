"""Planar diagrams of realized curves: generic projection, crossings, PD code.

The curves are rotated by a random (seeded) rotation and projected along ``z``.  Every
transverse crossing of two non-adjacent projected segments becomes a crossing; the higher
segment (larger ``z`` at the crossing) is the over strand.

PD convention (KnotTheory, spherogram, regina): ``X[i, j, k, l]`` lists the four edge
labels around a crossing counter-clockwise, starting with the incoming under edge ``i``
(``k`` is the outgoing under edge).  Edges are numbered from 1 along each component in
its direction, components one after the other.  A crossing is positive (right-handed)
when the under strand points to the left of the over strand:
``sign = sign(over x under)``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..errors import DiagramError


@dataclass(frozen=True, eq=False)
class Diagram:
    """A link diagram read from closed polylines.

    Attributes
    ----------
    pd : list of [int, int, int, int]
        PD code (empty when there are no crossings).
    signs : (n_crossings,) int64
        +1 right-handed, -1 left-handed.
    crossing_components : (n_crossings, 2) int64
        Over and under component of each crossing.
    n_components : int
    free_components : list of int
        Components without any crossing (split, unknotted).
    """

    pd: list[list[int]]
    signs: np.ndarray
    crossing_components: np.ndarray
    n_components: int
    free_components: list[int]

    @property
    def n_crossings(self) -> int:
        """Number of crossings of the diagram."""
        return len(self.pd)

    def linking_matrix(self) -> np.ndarray:
        """(n_components, n_components) int64: linking numbers, zero diagonal."""
        n = self.n_components
        out = np.zeros((n, n), np.int64)
        a, b = self.crossing_components[:, 0], self.crossing_components[:, 1]
        mixed = a != b
        np.add.at(out, (a[mixed], b[mixed]), self.signs[mixed])
        np.add.at(out, (b[mixed], a[mixed]), self.signs[mixed])
        return out // 2


def _segments(curves: Sequence[np.ndarray]) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    starts, ends, owner, index = [], [], [], []
    for c, pts in enumerate(curves):
        closed_pts = np.vstack([pts, pts[:1]])
        starts.append(closed_pts[:-1])
        ends.append(closed_pts[1:])
        owner.append(np.full(len(pts), c))
        index.append(np.arange(len(pts)))
    return np.vstack(starts), np.vstack(ends), np.concatenate(owner), np.concatenate(index)


def project(curves: Sequence[np.ndarray], seed: int = 0, rotation: ArrayLike | None = None) -> Diagram:
    """Return the diagram of closed polylines ``curves`` (list of ``(n_k, 3)``) seen along a generic axis.

    Parameters
    ----------
    curves : list of (n_k, 3) float64
        Closed polylines (the last point joins the first).
    seed : int
        Seeds the random rotation that makes the projection generic.
    rotation : (3, 3) float64, optional
        Use this rotation instead.

    Examples
    --------
    >>> t = np.linspace(0, 2 * np.pi, 60, endpoint=False)
    >>> a = np.column_stack([np.cos(t), np.sin(t), 0 * t])
    >>> b = np.column_stack([1 + np.cos(t), 0 * t, np.sin(t)])
    >>> d = project([a, b])
    >>> d.n_crossings, int(abs(d.linking_matrix()[0, 1]))
    (2, 1)
    """
    rot = random_rotation(seed) if rotation is None else np.asarray(rotation)
    curves = [np.asarray(c, np.float64) @ rot.T for c in curves]
    p0, p1, owner, index = _segments(curves)
    lengths = np.array([len(c) for c in curves])
    first = np.concatenate([[0], np.cumsum(lengths)])
    i, j = near_pairs(p0, p1)
    same = owner[i] == owner[j]
    n_own = lengths[owner[i]]
    gap = np.abs(index[i] - index[j])
    adjacent = same & ((gap == 1) | (gap == n_own - 1))
    over, under, t_over, t_under, signs = transverse(p0, p1, i[~adjacent], j[~adjacent])
    n_x = len(over)
    # passages: each crossing is passed twice (over, under); order them along components
    seg = np.concatenate([over, under])
    par = np.concatenate([t_over, t_under])
    comp = owner[seg]
    position = (seg - first[comp]) + par
    order = np.lexsort((position, comp))
    comp_sorted = comp[order]
    counts = np.bincount(comp_sorted, minlength=len(curves))
    comp_first = np.concatenate([[0], np.cumsum(counts)])
    rank = np.arange(2 * n_x) - comp_first[comp_sorted]
    # passage k of a component enters by edge k - 1 (cyclically) and leaves by edge k
    label_out = comp_first[comp_sorted] + rank + 1
    label_in = comp_first[comp_sorted] + (rank - 1) % np.maximum(counts[comp_sorted], 1) + 1
    lab_in = np.empty(2 * n_x, np.int64)
    lab_out = np.empty(2 * n_x, np.int64)
    lab_in[order] = label_in
    lab_out[order] = label_out
    o_in, o_out = lab_in[:n_x], lab_out[:n_x]
    u_in, u_out = lab_in[n_x:], lab_out[n_x:]
    pd = np.where(
        (signs > 0)[:, None], np.column_stack([u_in, o_out, u_out, o_in]), np.column_stack([u_in, o_in, u_out, o_out])
    )
    # the over strand points 90 degrees clockwise of the under strand for a positive crossing
    free = [int(c) for c in range(len(curves)) if counts[c] == 0]
    return Diagram(pd.tolist(), signs, np.column_stack([owner[over], owner[under]]).astype(np.int64), len(curves), free)


DRAWS = {
    0: (1.764052345967664, 0.4001572083672233, 0.9787379841057392, 2.240893199201458),
    1: (1.6243453636632417, -0.6117564136500754, -0.5281717522634557, -1.0729686221561705),
    2: (-0.4167578474054706, -0.056266827226329474, -2.136196095668454, 1.6402708084049886),
    3: (1.7886284734303186, 0.43650985051198943, 0.09649746807200862, -1.8634927033644908),
}
"""``numpy.random.RandomState(seed).normal(size=4)`` of the seeds 0-3 (a test checks them)."""


def random_rotation(seed: int) -> np.ndarray:
    """Return the ``(3, 3)`` rotation matrix of a uniform random unit quaternion drawn from ``RandomState(seed)``.

    The rotation ``scipy.spatial.transform.Rotation.random(random_state=seed)`` returns
    (the same draw, scalar last), without importing scipy; the draws of the first seeds
    are written out (:data:`DRAWS`), so these do not import ``numpy.random`` either.
    """
    q = np.array(DRAWS[seed]) if seed in DRAWS else np.random.RandomState(seed).normal(size=4)
    x, y, z, w = q / np.linalg.norm(q)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def near_pairs(p0: np.ndarray, p1: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pairs ``i < j`` of segments ``p0 -> p1`` (``(n, 3)``) whose projections to ``xy`` may meet, sorted.

    The test is on the circles around each projected segment: no crossing is missed.  The
    candidates are the pairs whose boxes around the circles overlap (:func:`box_pairs`,
    the boxes widened by a rounding margin so that no touching circles are lost).
    """
    a2, b2 = p0[:, :2], p1[:, :2]
    mid = 0.5 * (a2 + b2)
    half = 0.5 * np.linalg.norm(b2 - a2, axis=1)
    if len(mid) < 2:
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    reach = half + 1e-12 * (1.0 + np.abs(mid).max() + half.max())
    i, j = box_pairs(mid - reach[:, None], mid + reach[:, None])
    near = np.linalg.norm(mid[i] - mid[j], axis=1) <= half[i] + half[j]
    return i[near], j[near]


def _box_cells(low: np.ndarray, high: np.ndarray, origin: np.ndarray, side: float) -> tuple[np.ndarray, np.ndarray]:
    """Return the first and last grid cell ``(n, 2) int64`` each box ``low..high`` covers."""
    return np.floor((low - origin) / side).astype(np.int64), np.floor((high - origin) / side).astype(np.int64)


def box_pairs(low: np.ndarray, high: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pairs ``i < j`` of closed 2D boxes ``low[k]..high[k]`` (``(n, 2)``) that overlap, sorted (``int64`` arrays).

    Each box is put in every cell of a square grid it covers, and boxes sharing a cell
    are compared; a pair is taken in one cell only, the one holding the corner
    ``max(low[i], low[j])`` of the overlap.  The grid's side is the median box size,
    doubled while the boxes would fill more than eight cells each on average (a few
    long boxes cover many small cells), and at least a 2**-20th of the extent, so one
    long box neither coarsens the grid for all (the search stays near linear) nor
    makes it quadratic.
    """
    n = len(low)
    origin = low.min(axis=0)
    extent = float((high.max(axis=0) - origin).max())
    side = max(float(np.median((high - low).max(axis=1))), extent / 2**20, np.finfo(np.float64).tiny)
    first, last = _box_cells(low, high, origin, side)
    while side < extent and int(np.prod(last - first + 1, axis=1).sum()) > 8 * n:
        side *= 2
        first, last = _box_cells(low, high, origin, side)
    # every (box, cell) it covers, cells numbered column by column
    wide = last - first + 1
    covered = wide[:, 0] * wide[:, 1]
    box = np.repeat(np.arange(n), covered)
    rank = np.arange(len(box)) - np.repeat(np.cumsum(covered) - covered, covered)
    x = first[box, 0] + rank // wide[box, 1]
    y = first[box, 1] + rank % wide[box, 1]
    rows = int(last[:, 1].max()) + 1
    order = np.argsort(x * rows + y, kind="stable")
    box, x, y = box[order], x[order], y[order]
    # each entry with the entries after it in its cell
    key = x * rows + y
    cell_end = np.searchsorted(key, key, side="right")
    later = cell_end - np.arange(len(key)) - 1
    at = np.repeat(np.arange(len(key)), later)
    other = at + 1 + np.arange(len(at)) - np.repeat(np.cumsum(later) - later, later)
    i, j = box[at], box[other]
    fx, fy = first[:, 0].copy(), first[:, 1].copy()
    here = (np.maximum(fx[i], fx[j]) == x[at]) & (np.maximum(fy[i], fy[j]) == y[at])
    i, j = i[here], j[here]
    lx, ly, hx, hy = (np.ascontiguousarray(a) for a in (low[:, 0], low[:, 1], high[:, 0], high[:, 1]))
    overlap = (lx[i] <= hx[j]) & (lx[j] <= hx[i]) & (ly[i] <= hy[j]) & (ly[j] <= hy[i])
    i, j = i[overlap], j[overlap]
    lo, hi = np.minimum(i, j), np.maximum(i, j)
    sort = np.lexsort((hi, lo))
    return lo[sort].astype(np.int64), hi[sort].astype(np.int64)


def transverse(
    p0: np.ndarray, p1: np.ndarray, i: np.ndarray, j: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Return the crossings, seen along ``z``, of segment pairs ``(i, j)`` of ``p0 -> p1`` (``(n, 3)``).

    A segment holds its start and not its end (parameters in ``[0, 1)``), so a polyline's
    vertex is crossed once.

    Returns
    -------
    over, under : (n_crossings,) int64
        The segment above (larger ``z``) and below.
    t_over, t_under : (n_crossings,) float64
        Where along each segment.
    signs : (n_crossings,) int64
        +1 right-handed (the under segment points to the left of the over one), -1 left.

    Raises
    ------
    DiagramError
        Two segments cross at equal height (the curves meet, or the view is not generic).
    """
    a2, b2 = p0[:, :2], p1[:, :2]
    r = b2[i] - a2[i]
    s_ = b2[j] - a2[j]
    denom = r[:, 0] * s_[:, 1] - r[:, 1] * s_[:, 0]
    qp = a2[j] - a2[i]
    ok = np.abs(denom) > 1e-15
    dsafe = np.where(ok, denom, 1.0)
    u = (qp[:, 0] * s_[:, 1] - qp[:, 1] * s_[:, 0]) / dsafe
    v = (qp[:, 0] * r[:, 1] - qp[:, 1] * r[:, 0]) / dsafe
    hit = ok & (u >= 0) & (u < 1) & (v >= 0) & (v < 1)
    i, j, u, v = i[hit], j[hit], u[hit], v[hit]
    zi = p0[i, 2] + u * (p1[i, 2] - p0[i, 2])
    zj = p0[j, 2] + v * (p1[j, 2] - p0[j, 2])
    scale = float(np.ptp(np.vstack([p0, p1]), axis=0).max()) if len(p0) else 1.0
    if len(i) and np.min(np.abs(zi - zj)) < 1e-9 * (scale or 1.0):
        raise DiagramError("two strands meet in the projection at equal height: the curves intersect")
    i_over = zi > zj
    over = np.where(i_over, i, j)
    under = np.where(i_over, j, i)
    d_over = (b2 - a2)[over]
    d_under = (b2 - a2)[under]
    signs = np.sign(d_over[:, 0] * d_under[:, 1] - d_over[:, 1] * d_under[:, 0]).astype(np.int64)
    return over, under, np.where(i_over, u, v), np.where(i_over, v, u), signs


def project_generic(curves: Sequence[np.ndarray], seed: int = 0) -> Diagram:
    """Project ``curves`` as :func:`project`; a rare non-generic projection is turned again (three tries)."""
    for attempt in range(3):
        try:
            return project(curves, seed=seed + attempt)
        except DiagramError:
            if attempt == 2:
                raise
    raise AssertionError("unreachable")  # pragma: no cover
