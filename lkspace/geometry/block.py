"""Periodic blocks: an A x B (x C) block of cells, its threads cut at the block's faces.

The block is the parallelepiped ``{centre + sum_i f_i a_i : |f_i| <= n_i / 2}`` of the
cell vectors ``a_i`` (:func:`cell_vectors`: the conventional cubic or orthorhombic cell
when the lattice has one, else the lattice basis) around lattice points (for
``honeycomb:cP``, whose cubes are centred on the lattice points, a 2x2x2 block is
exactly eight cubes; for ``honeycomb:cI`` it is eight conventional cubes, 16 cells).
:func:`realize_block` realizes every translate reaching into the block, joins the periods
of every infinite thread into one polyline (:func:`join_curves`), cuts the polylines
where they leave the block widened by a small ``margin`` (so that threads running in
the block's surface stay whole), drops stubs, and keeps every closed loop whose centre
lies in the block whole.  :func:`block_faces` lists the faces (cells) to draw.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import ArrayLike
from scipy.spatial import cKDTree

from ..errors import GeometryError
from ..model.scaffold import Scaffold
from .limits import MAX_POINTS
from .params import GeometryParams, RealizeOptions
from .realization import Realization, realize

STUB = 0.5
"""Runs of a thread inside a block shorter than this many shortest edges are left out."""

JOIN = 1e-6
"""Periods of a thread are joined where one ends within this many shortest edges of another's start."""

__all__ = ["CellBlock", "block_faces", "block_of", "clip_curves", "join_curves", "realize_block"]


@dataclass(frozen=True, eq=False)
class CellBlock:
    """A block of lattice cells.

    Attributes
    ----------
    sizes : (dim,) int64
        Cells along each lattice vector.
    centre : (3,) float64
        Centre of the block.
    basis : (dim, 3) float64
        The lattice vectors.
    margin : float
        Length by which threads may leave the block before they are cut.
    shortest : float
        Runs of a thread inside the block shorter than this are dropped (stubs).
    """

    sizes: np.ndarray
    centre: np.ndarray
    basis: np.ndarray
    margin: float
    shortest: float = 0.0

    def fractional(self, points: ArrayLike) -> np.ndarray:
        """Block coordinates ``(..., dim)`` of ``points``: 0 at the centre, ``+-sizes/2`` on the faces."""
        return (np.asarray(points, np.float64) - self.centre) @ np.linalg.pinv(self.basis)

    def slack(self) -> np.ndarray:
        """(dim,) the margin in block coordinates along each lattice vector."""
        inv = np.linalg.pinv(self.basis)  # (3, dim); the face i lies at a distance 1/|inv[:, i]| per unit
        return self.margin * np.linalg.norm(inv, axis=0)

    def inside(self, points: ArrayLike, widen: bool = True) -> np.ndarray:
        """(n,) bool: points within the block (widened by ``margin`` when ``widen``)."""
        f = self.fractional(points)
        half = self.sizes / 2 + (self.slack() if widen else 0.0) + 1e-9  # points cut on the surface count
        return np.all(np.abs(f) <= half, axis=-1)

    def corners(self) -> np.ndarray:
        """(2**dim, 3) the corners of the block."""
        dim = len(self.sizes)
        signs = np.array(np.meshgrid(*[[-0.5, 0.5]] * dim, indexing="ij")).reshape(dim, -1).T
        return self.centre + (signs * self.sizes) @ self.basis

    def frame(self) -> list[np.ndarray]:
        """Return the block's edges as (2, 3) segments (12 in 3D, 4 in 2D)."""
        dim = len(self.sizes)
        c = self.corners()
        out = []
        for i in range(len(c)):
            for k in range(dim):
                j = i | (1 << (dim - 1 - k))
                if j != i:
                    out.append(np.array([c[i], c[j]]))
        return out


def cell_vectors(basis: np.ndarray) -> np.ndarray:
    """(dim, 3) the block's cell: the conventional axis-aligned cell when the lattice has one.

    In 3D, the shortest lattice vectors along x, y and z (integer combinations of the
    basis with entries in -2..2) span the conventional cubic or orthorhombic cell of
    ``cP``, ``cI``, ``cF``, ``oF`` and ``hP``; otherwise (and in 2D) the basis itself.
    """
    dim = len(basis)
    if dim != 3:
        return basis
    grid = np.array(np.meshgrid(*[np.arange(-2, 3)] * 3, indexing="ij")).reshape(3, -1).T
    vectors = grid @ basis
    scale = float(np.abs(basis).max())
    cells = []
    for axis in np.eye(3):
        along = vectors @ axis
        off = np.linalg.norm(vectors - along[:, None] * axis, axis=1)
        ok = (off < 1e-9 * scale) & (along > 1e-9 * scale)
        if not ok.any():
            return basis
        cells.append(vectors[ok][np.argmin(along[ok])])
    cell = np.array(cells)
    if abs(np.linalg.det(cell)) > 4.5 * abs(np.linalg.det(basis)):
        return basis
    return cell


def block_of(scaffold: Scaffold, sizes: ArrayLike, margin: float, shortest: float = 0.0) -> CellBlock:
    """Return the :class:`CellBlock` of ``sizes`` cells of periodic ``scaffold`` (cells of :func:`cell_vectors`)."""
    if scaffold.lattice is None:
        raise GeometryError(f"{scaffold.name}: a block needs a periodic scaffold", usage=True)
    sizes = np.asarray(sizes, np.int64)
    basis = scaffold.lattice.basis
    cell = cell_vectors(basis)
    # the cell of translate 0 is centred on the lattice point nearest to its faces' middle
    return CellBlock(sizes, lattice_origin(scaffold) + 0.5 * (sizes - 1) @ cell, cell, float(margin), float(shortest))


def lattice_origin(scaffold: Scaffold) -> np.ndarray:
    """(3,) the lattice point nearest to the middle of the scaffold's corners (translate 0's cell)."""
    assert scaffold.lattice is not None
    lattice = scaffold.lattice
    return np.asarray(np.round(lattice.fractional(scaffold.corner_positions.mean(axis=0))) @ lattice.basis)


def covering_translations(scaffold: Scaffold, block: CellBlock, content: np.ndarray) -> np.ndarray:
    """(n, dim) int64: every lattice translation whose copy of ``content`` (points, ``(m, 3)``) can reach into ``block``.

    A copy is kept when the bounding box of its content, in block coordinates, meets the
    block widened by its margin (one period of an infinite thread may span several cells
    along its period and none across it: the box test keeps only what is needed).
    """
    assert scaffold.lattice is not None
    lattice = scaffold.lattice
    inv = np.linalg.pinv(block.basis)
    f = (np.asarray(content, np.float64) - block.centre) @ inv
    lo, hi = f.min(axis=0), f.max(axis=0)
    half = block.sizes / 2 + block.slack()
    # candidates: translations whose shift lies within the block's box minus the content's
    corners = block.corners()
    span = np.abs(np.vstack([lo, hi])).max(axis=0) @ np.abs(block.basis)  # (3,) generous extent of the content
    far = np.vstack([corners - span, corners + span, corners])
    frac = lattice.fractional(far)
    ranges = [
        np.arange(np.floor(a) - 1, np.ceil(b) + 2) for a, b in zip(frac.min(axis=0), frac.max(axis=0), strict=True)
    ]
    cand = np.column_stack([g.reshape(-1) for g in np.meshgrid(*ranges, indexing="ij")]).astype(np.int64)
    shift = lattice.translate(cand) @ inv
    keep = np.all((shift + hi >= -half - 1e-9) & (shift + lo <= half + 1e-9), axis=1)
    return cand[keep]


def join_curves(
    curves: list[np.ndarray], closed: np.ndarray, tol: float
) -> tuple[list[np.ndarray], np.ndarray, list[list[int]]]:
    """Join open polylines whose end is another's start (the periods of one thread).

    Returns the joined polylines, their closed flags (a chain that comes back to its
    start is closed) and, for each, the indices of the input curves it joins.
    """
    open_ids = [k for k, c in enumerate(closed) if not c]
    nxt: dict[int, int] = {}
    if len(open_ids) > 1:
        starts = np.array([curves[k][0] for k in open_ids])
        ends = np.array([curves[k][-1] for k in open_ids])
        dist, idx = cKDTree(starts).query(ends)
        for a, (d, b) in enumerate(zip(dist, idx, strict=True)):
            if d <= tol and a != b:
                nxt[open_ids[a]] = open_ids[int(b)]
    has_prev = set(nxt.values())
    out: list[np.ndarray] = []
    flags: list[bool] = []
    members: list[list[int]] = []
    seen: set[int] = set()
    order = [k for k in open_ids if k not in has_prev] + [k for k in open_ids if k in has_prev]
    for k in range(len(curves)):
        if closed[k]:
            out.append(curves[k])
            flags.append(True)
            members.append([k])
            seen.add(k)
    for k in order:
        if k in seen:
            continue
        chain = [k]
        seen.add(k)
        while chain[-1] in nxt and nxt[chain[-1]] not in seen:
            chain.append(nxt[chain[-1]])
            seen.add(chain[-1])
        ring = chain[-1] in nxt and nxt[chain[-1]] == chain[0]
        pts = np.vstack([curves[chain[0]]] + [curves[c][1:] for c in chain[1:]])
        if ring:
            pts = pts[:-1]
        out.append(pts)
        flags.append(bool(ring))
        members.append(chain)
    return out, np.array(flags, bool), members


def clip_curves(
    curves: list[np.ndarray], closed: np.ndarray, block: CellBlock
) -> tuple[list[np.ndarray], np.ndarray, np.ndarray]:
    """Cut polylines where they leave ``block`` (widened by its margin).

    Closed loops are kept whole when their centre lies in the block and dropped
    otherwise; an open polyline (a thread) is kept from where it first enters to where
    it last leaves, ended exactly on the widened block's surface: one run per thread,
    whole even where it strays out of the block and back in between; a run that never
    enters the block itself (a stub in the margin) is dropped.  Returns ``(pieces,
    closed flags, source curve per piece)``.
    """
    pieces: list[np.ndarray] = []
    flags: list[bool] = []
    source: list[int] = []
    half = block.sizes / 2 + block.slack()
    for k, (c, cl) in enumerate(zip(curves, closed, strict=True)):
        if cl:
            if block.inside(c.mean(axis=0)[None])[0]:
                pieces.append(c)
                flags.append(True)
                source.append(k)
            continue
        f = block.fractional(c)
        ins = np.all(np.abs(f) <= half, axis=1)
        if not ins.any():
            continue
        inside = np.flatnonzero(ins)
        lo, hi = int(inside[0]), int(inside[-1]) + 1
        run = [c[lo:hi]]
        if lo > 0:  # the way in: from the last point outside to the surface
            run.insert(0, cut_point(c[lo - 1], c[lo], f[lo - 1], f[lo], half)[None])
        if hi < len(c):
            run.append(cut_point(c[hi], c[hi - 1], f[hi], f[hi - 1], half)[None])
        pts = np.vstack(run)
        if len(pts) >= 3 and arc_length(pts) >= block.shortest:  # not a stub
            pieces.append(pts)
            flags.append(False)
            source.append(k)
    return pieces, np.array(flags, bool), np.array(source, np.int64)


def arc_length(points: np.ndarray) -> float:
    """Length of the polyline ``points``."""
    return float(np.linalg.norm(np.diff(points, axis=0), axis=1).sum())


def cut_point(out_p: np.ndarray, in_p: np.ndarray, out_f: np.ndarray, in_f: np.ndarray, half: np.ndarray) -> np.ndarray:
    """Return the point where the segment from ``in_p`` to ``out_p`` crosses the box ``|f| <= half``."""
    s = 1.0
    d = out_f - in_f
    for i in range(len(half)):
        for bound in (half[i], -half[i]):
            if d[i] != 0:
                u = (bound - in_f[i]) / d[i]
                if 0 <= u < s:
                    s = u
    return np.asarray(in_p + s * (out_p - in_p))


def clip_polygon(poly: np.ndarray, f: np.ndarray, half: np.ndarray) -> np.ndarray:
    """Clip a planar polygon (``(m, 3)`` points, block coordinates ``f``) to ``|f_i| <= half_i`` (Sutherland-Hodgman)."""
    pts, coords = poly, f
    for axis in range(len(half)):
        for sign in (1.0, -1.0):
            if len(pts) == 0:
                return pts
            inside = sign * coords[:, axis] <= half[axis] + 1e-12
            if inside.all():
                continue
            out_p, out_f = [], []
            for k in range(len(pts)):
                j = (k + 1) % len(pts)
                if inside[k]:
                    out_p.append(pts[k])
                    out_f.append(coords[k])
                if inside[k] != inside[j]:
                    u = (sign * half[axis] - coords[k, axis]) / (coords[j, axis] - coords[k, axis])
                    out_p.append(pts[k] + u * (pts[j] - pts[k]))
                    out_f.append(coords[k] + u * (coords[j] - coords[k]))
            pts, coords = np.array(out_p).reshape(-1, 3), np.array(out_f).reshape(-1, len(half))
    return pts


def block_faces(scaffold: Scaffold, block: CellBlock) -> list[np.ndarray]:
    """Polygons (each ``(m, 3)``) of the translates' faces cut to the block: its cells, cut like the threads."""
    assert scaffold.lattice is not None
    corners = scaffold.corner_positions
    shifts = scaffold.lattice.translate(covering_translations(scaffold, block, corners))
    half = block.sizes / 2
    starts = scaffold.face_starts
    out: list[np.ndarray] = []
    for shift in shifts:
        moved = corners + shift
        f = block.fractional(moved)
        near = np.all(np.abs(f) <= half + 1e-9, axis=1)
        for face in range(scaffold.n_faces):
            lo, hi = starts[face], starts[face + 1]
            if near[lo:hi].all():
                out.append(moved[lo:hi])
            elif np.all(np.abs(f[lo:hi]).min(axis=0) <= half):  # may cross the block: cut it
                piece = clip_polygon(moved[lo:hi], f[lo:hi], half)
                if len(piece) >= 3:
                    out.append(piece)
    return out


def realize_block(
    scaffold: Scaffold,
    labels: ArrayLike | None,
    nulls: ArrayLike | None,
    params: GeometryParams | None,
    sizes: ArrayLike,
    *,
    max_points: int = MAX_POINTS,
    relax: Callable[[Realization], Realization] | None = None,
) -> Realization:
    """Realize an ``sizes`` block of a periodic scaffold, cut to the block.

    Every translate that can reach into the block (:func:`covering_translations`) is
    realized (and checked) with :func:`~lkspace.geometry.realization.realize`, the periods of each thread joined,
    and the result cut by :func:`clip_curves`; the margin is the normal offset plus two
    tube radii, so that threads running in the block's surface stay whole; runs shorter
    than :data:`STUB` shortest edges are left out.  ``copy_of`` and ``strand_of`` of a
    piece are those of its first period.  ``max_points`` bounds each realization
    (:class:`~lkspace.geometry.params.RealizeOptions`).  The thread classes are smoothed
    in the periodic cell, and relaxed there by ``relax`` when given (e.g.
    :func:`~lkspace.geometry.relax.relax`), before the copies are joined and cut: every
    copy of a class has the same shape.

    Examples
    --------
    >>> from lkspace import load
    >>> r = realize_block(load("honeycomb:cP"), [2, 1, 1], None, None, (2, 2, 2))
    >>> bool(r.block is not None and all(r.block.inside(c[[0, -1]]).all() for c in r.curves))
    True
    """
    if not scaffold.periodic:
        raise GeometryError(f"{scaffold.name}: a block needs a periodic scaffold", usage=True)
    sizes = np.asarray(sizes, np.int64)
    one = realize(
        scaffold, labels, nulls, params, options=RealizeOptions(max_points=max_points)
    )  # how far one copy reaches
    margin = one.normal_offset + 2 * one.tube_radius
    covering = covering_translations(scaffold, block_of(scaffold, sizes, margin), np.vstack(one.curves))
    options = RealizeOptions(translations=covering, trace=one.trace, max_points=max_points)
    real = realize(scaffold, labels, nulls, params, options=options)
    if relax is not None:
        real = relax(real)
    block = block_of(scaffold, sizes, margin, STUB * real.scale)
    joined, joined_closed, members = join_curves(real.curves, real.closed, JOIN * real.scale)
    pieces, closed, source = clip_curves(joined, joined_closed, block)
    first = np.array([members[s][0] for s in source], np.int64)
    return replace(
        real,
        curves=pieces,
        closed=closed,
        strand_of=real.strand_of[first] if len(first) else np.zeros(0, np.int64),
        copy_of=real.copy_of[first] if len(first) else np.zeros(0, np.int64),
        block=block,
    )
