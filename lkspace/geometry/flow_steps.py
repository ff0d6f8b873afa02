"""The compiled iteration of the rope flow (:mod:`~lkspace.geometry.flow`) and its neighbour search.

:func:`flow_iteration` is one iteration of :func:`~lkspace.geometry.flow.rope_flow` as
a single loop over the points and the candidate pairs: the curvature radius of every point,
the distinct pieces within reach, the rope's growth when it fits, and the capped step
(curve shortening, curvature relief, overlap pushes).
The flow's rules are stated in that module's docstring; the arithmetic here follows it term
by term (the pushes are summed in the same order, first points then second points).

:func:`flow_candidates` is the flow's neighbour list of curves in space: the pairs of
points within a radius (:func:`close_point_pairs`, on a grid of that side, without
building a k-d tree) and how far apart along their curve each pair is.
"""

from __future__ import annotations

import numpy as np

from ..compiled.kernels import helper, kernel


@kernel
def flow_iteration(
    points: np.ndarray,
    prev: np.ndarray,
    nxt: np.ndarray,
    before: np.ndarray,
    after: np.ndarray,
    owner: np.ndarray,
    lengths: np.ndarray,
    cand_i: np.ndarray,
    cand_j: np.ndarray,
    cand_owner: np.ndarray,
    share: np.ndarray,
    shift: np.ndarray,
    reach: float,
    diameter: float,
    h: float,
    pull: float,
    grow: float,
    fold: float,
) -> tuple[np.ndarray, np.ndarray, float, float, float]:
    """Run one flow iteration: return ``(new points (n, 3), their curves' lengths, gap, thickness, diameter)``.

    ``prev``, ``nxt`` ``(n,)``: each point's neighbours, ``before``, ``after`` ``(n, 3)``
    added to them (a thread's period, else zeros); ``owner`` ``(n,)``: each point's curve;
    ``lengths``: of the curves.  The
    candidates ``cand_i``, ``cand_j``, ``cand_owner`` (the curve of ``i``), ``share``
    (separation along the curve as a share of its length, ``inf`` on two curves) and
    ``shift`` (``(m, 3)`` translation of ``j``'s image, or ``(0, 3)`` for none) hold every
    pair within ``reach``.  ``gap`` is the least distance of distinct pieces within
    ``reach`` (``reach`` when none), the thickness ``min(gap / 2, least curvature radius)``;
    with ``grow`` > 0 the diameter grows by that factor when the rope fits, before the step.
    """
    n = points.shape[0]
    radius = np.empty(n)
    mid = np.empty((n, 3))
    least_radius = np.inf
    for p in range(n):
        u, w = prev[p], nxt[p]
        a0, a1, a2 = points[u, 0] + before[p, 0], points[u, 1] + before[p, 1], points[u, 2] + before[p, 2]
        c0, c1, c2 = points[w, 0] + after[p, 0], points[w, 1] + after[p, 1], points[w, 2] + after[p, 2]
        b0, b1, b2 = points[p, 0], points[p, 1], points[p, 2]
        ab = np.sqrt((b0 - a0) ** 2 + (b1 - a1) ** 2 + (b2 - a2) ** 2)
        bc = np.sqrt((c0 - b0) ** 2 + (c1 - b1) ** 2 + (c2 - b2) ** 2)
        ca = np.sqrt((a0 - c0) ** 2 + (a1 - c1) ** 2 + (a2 - c2) ** 2)
        x = (b1 - a1) * (c2 - a2) - (b2 - a2) * (c1 - a1)
        y = (b2 - a2) * (c0 - a0) - (b0 - a0) * (c2 - a2)
        z = (b0 - a0) * (c1 - a1) - (b1 - a1) * (c0 - a0)
        area2 = np.sqrt(x * x + y * y + z * z)
        radius[p] = ab * bc * ca / (2.0 * area2) if area2 > 1e-14 * ab * bc else np.inf
        least_radius = min(least_radius, radius[p])
        mid[p, 0], mid[p, 1], mid[p, 2] = 0.5 * (a0 + c0) - b0, 0.5 * (a1 + c1) - b1, 0.5 * (a2 + c2) - b2
    shifted = shift.shape[0] > 0
    m = cand_i.shape[0]
    kept = np.empty(m, np.int64)
    dist = np.empty(m)
    n_kept = 0
    gap = reach
    for q in range(m):
        i, j = cand_i[q], cand_j[q]
        d2 = 0.0
        for k in range(3):
            e = points[i, k] - points[j, k] - (shift[q, k] if shifted else 0.0)
            d2 += e * e
        if d2 <= reach * reach:
            d = np.sqrt(d2)
            if share[q] * lengths[cand_owner[q]] > fold * d:
                kept[n_kept] = q
                dist[n_kept] = d
                n_kept += 1
                gap = min(gap, d)
    thick = min(0.5 * gap, least_radius)
    if grow > 0 and gap >= 0.98 * diameter and thick >= 0.49 * diameter:
        diameter *= 1 + grow
    near = np.full(n, max(diameter, 4 * h))
    total = np.zeros((n, 3))
    count = np.zeros(n)
    push = np.empty((n_kept, 3))
    for r in range(n_kept):
        q, d = kept[r], dist[r]
        i, j = cand_i[q], cand_j[q]
        if d < 0.75 * h:  # only these lower the cap below h / 4
            near[i] = min(near[i], d)
            near[j] = min(near[j], d)
        if d < diameter:
            f = 0.5 * (diameter - d) / max(d, 1e-300)
            for k in range(3):
                push[r, k] = f * (points[i, k] - points[j, k] - (shift[q, k] if shifted else 0.0))
                total[i, k] += push[r, k]
            count[i] += 1.0
    for r in range(n_kept):
        if dist[r] < diameter:
            j = cand_j[kept[r]]
            for k in range(3):
                total[j, k] -= push[r, k]
            count[j] += 1.0
    out = np.empty((n, 3))
    for p in range(n):
        weight = 0.5 if radius[p] < 0.5 * diameter else pull
        share_of = max(count[p], 1.0)
        m0 = weight * mid[p, 0] + total[p, 0] / share_of
        m1 = weight * mid[p, 1] + total[p, 1] / share_of
        m2 = weight * mid[p, 2] + total[p, 2] / share_of
        cap = min(0.25 * h, near[p] / 3.0)
        size = np.sqrt(m0 * m0 + m1 * m1 + m2 * m2)
        scale = cap / max(size, 1e-300) if size > cap else 1.0
        out[p, 0], out[p, 1], out[p, 2] = (
            points[p, 0] + m0 * scale,
            points[p, 1] + m1 * scale,
            points[p, 2] + m2 * scale,
        )
    new_lengths = np.zeros(lengths.shape[0])
    for p in range(n):
        w = nxt[p]
        e0 = out[w, 0] + after[p, 0] - out[p, 0]
        e1 = out[w, 1] + after[p, 1] - out[p, 1]
        e2 = out[w, 2] + after[p, 2] - out[p, 2]
        new_lengths[owner[p]] += np.sqrt(e0 * e0 + e1 * e1 + e2 * e2)
    return out, new_lengths, gap, thick, diameter


@helper
def close_point_pairs(points: np.ndarray, radius: float, n_first: int) -> tuple[np.ndarray, np.ndarray]:
    """Return the pairs ``i < j`` of ``points`` ``(n, 3)`` at most ``radius`` apart, ``i < n_first``: ``(i, j)`` int64 each.

    The points are sorted into cubic cells of side ``radius`` (at least a 2**-20th of
    the extent, so cell numbers fit in int64); each cell is compared with itself and
    the 13 neighbouring cells that come after it in the order of the cell numbers.
    """
    n = points.shape[0]
    low = np.empty(3)
    extent = 0.0
    for k in range(3):
        low[k] = points[:, k].min()
        extent = max(extent, points[:, k].max() - low[k])
    side = max(radius, extent / 2**20, 1e-300)
    cells = np.empty((n, 3), np.int64)
    for p in range(n):
        for k in range(3):
            cells[p, k] = np.int64(np.floor((points[p, k] - low[k]) / side)) + 1
    wide_y = cells[:, 1].max() + 2  # a neighbour offset never wraps into another row
    wide_z = cells[:, 2].max() + 2
    keys = (cells[:, 0] * wide_y + cells[:, 1]) * wide_z + cells[:, 2]
    order = np.argsort(keys, kind="mergesort")
    ordered = points[order]
    sorted_keys = keys[order]
    firsts = np.flatnonzero(np.concatenate((np.ones(1, np.bool_), sorted_keys[1:] != sorted_keys[:-1])))
    bounds = np.append(firsts, n)
    cell_keys = sorted_keys[firsts]
    limit = radius * radius
    found_i = np.empty(max(16, 8 * n), np.int64)
    found_j = np.empty(max(16, 8 * n), np.int64)
    n_found = 0
    steps = np.empty(14, np.int64)  # (0, 0, 0) and the 13 offsets after it in (x, y, z) order
    n_steps = 0
    for dx in range(2):
        for dy in range(-1, 2):
            for dz in range(-1, 2):
                if dx == 0 and (dy < 0 or (dy == 0 and dz < 0)):
                    continue
                steps[n_steps] = (dx * wide_y + dy) * wide_z + dz
                n_steps += 1
    for a in range(len(firsts)):
        for step in steps:
            b = a if step == 0 else np.searchsorted(cell_keys, cell_keys[a] + step)
            if b == len(cell_keys) or cell_keys[b] != cell_keys[a] + step:
                continue
            for s in range(bounds[a], bounds[a + 1]):
                for t in range(s + 1 if b == a else bounds[b], bounds[b + 1]):
                    e0 = ordered[s, 0] - ordered[t, 0]
                    e1 = ordered[s, 1] - ordered[t, 1]
                    e2 = ordered[s, 2] - ordered[t, 2]
                    if e0 * e0 + e1 * e1 + e2 * e2 <= limit and min(order[s], order[t]) < n_first:
                        if n_found == found_i.shape[0]:
                            found_i = np.concatenate((found_i, np.empty(n_found, np.int64)))
                            found_j = np.concatenate((found_j, np.empty(n_found, np.int64)))
                        found_i[n_found] = min(order[s], order[t])
                        found_j[n_found] = max(order[s], order[t])
                        n_found += 1
    return found_i[:n_found].copy(), found_j[:n_found].copy()


@kernel
def flow_candidates(
    points: np.ndarray, radius: float, owner: np.ndarray, index: np.ndarray, sizes: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Return the pairs of closed-curve ``points`` within ``radius``: ``(i, j, owner of i, share)``.

    ``owner``, ``index`` ``(n,)``: each point's curve and place along it; ``sizes``: points
    per curve.  ``share`` is the pair's separation along their curve (the shorter way
    round) as a share of its points, ``inf`` on two curves.
    """
    i, j = close_point_pairs(points, radius, points.shape[0])
    m = i.shape[0]
    owner_i = np.empty(m, np.int64)
    share = np.empty(m)
    for q in range(m):
        a = owner[i[q]]
        owner_i[q] = a
        if a == owner[j[q]]:
            steps = abs(index[i[q]] - index[j[q]])
            share[q] = min(steps, sizes[a] - steps) / sizes[a]
        else:
            share[q] = np.inf
    return i, j, owner_i, share


@kernel
def point_pairs(points: np.ndarray, radius: float, n_first: int) -> tuple[np.ndarray, np.ndarray]:
    """:func:`close_point_pairs` as a kernel of its own (the periodic cell's image search calls it)."""
    return close_point_pairs(points, radius, n_first)


@kernel
def image_shares(
    i: np.ndarray,
    j: np.ndarray,
    m: np.ndarray,
    owner: np.ndarray,
    index: np.ndarray,
    sizes: np.ndarray,
    periods: np.ndarray,
    basis: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return ``(owner of i, share, shift)`` of the image pairs ``(i, j, m)`` of thread classes.

    As :func:`~lkspace.geometry.cell.image_candidates` states: the image ``p_j + m @ basis``
    is on ``p_i``'s own thread when ``m`` is a whole number ``q`` of its period, ``q``
    periods further along it (for a loop, ``m = 0``, the shorter way round); ``share`` is
    the separation along the thread as a share of its points (``inf`` off it), ``shift``
    ``(k, 3)`` the translation ``m @ basis``.
    """
    k, dim = m.shape
    owner_i = np.empty(k, np.int64)
    share = np.empty(k)
    shift = np.zeros((k, 3))
    for q in range(k):
        a = owner[i[q]]
        owner_i[q] = a
        pp, mp = 0, 0
        for d in range(dim):
            pp += periods[a, d] * periods[a, d]
            mp += m[q, d] * periods[a, d]
            for c in range(3):
                shift[q, c] += m[q, d] * basis[d, c]
        turns = mp // pp if pp > 0 else 0
        along = a == owner[j[q]]
        for d in range(dim):
            along = along and m[q, d] == turns * periods[a, d]
        size = sizes[a]
        steps = abs(index[j[q]] + turns * size - index[i[q]])
        if pp == 0:
            steps = min(steps, size - steps)
        share[q] = steps / size if along else np.inf
    return owner_i, share, shift


@kernel
def resample_ring(
    points: np.ndarray, starts: np.ndarray, sizes: np.ndarray, offsets: np.ndarray, spacing: float, least: int
) -> tuple[np.ndarray, np.ndarray]:
    """Resample every closed curve of the concatenated ``points`` evenly by arc length: ``(points, sizes)``.

    Curve ``c`` is ``points[starts[c]:starts[c] + sizes[c]]``, closing on its first point
    moved by ``offsets[c]`` (a thread's period, else zero); it gets ``max(least,
    round(length / spacing))`` points (at least 3) about ``spacing`` apart, interpolated on
    its polyline as :func:`~lkspace.geometry.flow.resample_count` does.
    """
    n_curves = sizes.shape[0]
    counts = np.empty(n_curves, np.int64)
    for c in range(n_curves):
        length = 0.0
        for p in range(starts[c], starts[c] + sizes[c]):
            last = p == starts[c] + sizes[c] - 1
            q = starts[c] if last else p + 1
            e0 = points[q, 0] + (offsets[c, 0] if last else 0.0) - points[p, 0]
            e1 = points[q, 1] + (offsets[c, 1] if last else 0.0) - points[p, 1]
            e2 = points[q, 2] + (offsets[c, 2] if last else 0.0) - points[p, 2]
            length += np.sqrt(e0 * e0 + e1 * e1 + e2 * e2)
        counts[c] = max(3, max(least, int(round(length / spacing))))
    out = np.empty((counts.sum(), 3))
    at = 0
    for c in range(n_curves):
        size = sizes[c]
        ends = np.empty((size + 1, 3))
        ends[:size] = points[starts[c] : starts[c] + size]
        ends[size] = points[starts[c]] + offsets[c]
        cum = np.zeros(size + 1)
        for p in range(size):
            e0, e1, e2 = ends[p + 1, 0] - ends[p, 0], ends[p + 1, 1] - ends[p, 1], ends[p + 1, 2] - ends[p, 2]
            cum[p + 1] = cum[p] + np.sqrt(e0 * e0 + e1 * e1 + e2 * e2)
        step = cum[size] / counts[c]
        j = 0
        for k in range(counts[c]):
            x = k * step
            while j < size - 1 and cum[j + 1] <= x:
                j += 1
            width = cum[j + 1] - cum[j]
            for d in range(3):
                if width > 0:
                    out[at + k, d] = (ends[j + 1, d] - ends[j, d]) / width * (x - cum[j]) + ends[j, d]
                else:
                    out[at + k, d] = ends[j, d]
        at += counts[c]
    return out, counts


def load_kernels() -> None:
    """Compile the kernels (or load them from numba's cache) on a three-point curve, with the flow's argument types.

    :func:`~lkspace.geometry.flow.rope_flow` calls it before its progress clock starts, so
    that a first compilation (seconds, once per machine) is not reported as flow steps.
    """
    points = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    at = np.arange(3, dtype=np.int64)
    owner = np.zeros(3, np.int64)
    i, j, owner_i, share = flow_candidates(points, 2.0, owner, at, np.array([3], np.int64))
    point_pairs(points, 2.0, 3)
    resample_ring(points, np.zeros(1, np.int64), np.array([3], np.int64), np.zeros((1, 3)), 0.5, 12)
    image_shares(
        i, j, np.zeros((len(i), 3), np.int64), owner, at, np.array([3], np.int64), np.zeros((1, 3), np.int64), np.eye(3)
    )
    zeros = np.zeros((3, 3))
    nxt = (at + 1) % 3
    flow_iteration(
        points,
        (at - 1) % 3,
        nxt,
        zeros,
        zeros,
        owner,
        np.ones(1),
        i,
        j,
        owner_i,
        share,
        zeros[:0],
        1.0,
        1.0,
        0.1,
        0.1,
        0.0,
        1.5,
    )
