"""Motifs and gradients on periodic scaffolds: labels of a supercell from a few numbers.

A supercell ``NAME@AxBxC`` repeats the base cell of a periodic scaffold; every edge class
of the supercell is a copy of a base edge class in one cell ``c = (i, j, k)`` (the cell
of the base edge's first vertex).  :func:`cell_map` finds both from the coordinates
alone: a supercell vertex is a base vertex translated by a whole number of base cells.

**Motif.**  Labels on a block of cells, repeated by a tiling lattice ``M`` of the cells:
rows of ``M`` (lower triangular, positive diagonal, in cell units) generate the
translations that repeat the block.  ``M = diag(m_1, ..., m_d)`` repeats an
``m_1 x ... x m_d`` block straight; an off-diagonal entry is an offset pattern: ``[[2, 0],
[1, 1]]`` shifts each row of 2-cell blocks by one cell against the row below (a brick
bond).  The label of base edge ``e`` in cell ``c`` is ``motif[r(c), e]`` with ``r(c)`` the
block cell equal to ``c`` modulo ``M`` (index ``(r_1 * m_2 + r_2) * m_3 + r_3``).  The
supercell must be a multiple of ``M`` (each ``sizes_i e_i`` a combination of its rows).

**Gradient.**  Labels as a function of the layer ``l = c . direction`` (an integer):
``values[l mod len(values)]`` on every base edge, or ``values[l mod L, e]`` per base edge.
The supercell is periodic, so the last layer meets the first.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..errors import LabelError, ScaffoldError, TooLargeError
from ..model.scaffold import Scaffold

MAX_MOTIFS = 1 << 16
"""Most motifs :func:`motif_classes` walks."""


def _cells_of(base: Scaffold, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return the base vertex and integer cell of each point (a base vertex translated by whole cells)."""
    assert base.lattice is not None
    basis = base.lattice.basis
    scale = max(1.0, float(np.abs(basis).max()))
    verts, cells = np.empty(len(points), np.int64), np.empty((len(points), base.dim), np.int64)
    for i, p in enumerate(points):
        frac = np.linalg.lstsq(basis.T, (p[None, :] - base.vertices).T, rcond=None)[0].T  # (n_base, dim)
        near = np.round(frac)
        err = np.abs(frac - near).max(axis=1) + np.linalg.norm((frac - near) @ basis, axis=1) / scale
        v = int(err.argmin())
        if err[v] > 1e-6:
            raise ScaffoldError(f"vertex {i} of the supercell is no translate of a base vertex")
        verts[i], cells[i] = v, near[v]
    return verts, cells


def cell_map(base: Scaffold, supercell: Scaffold, sizes: Sequence[int]) -> tuple[np.ndarray, np.ndarray]:
    """Return the base edge class and cell of every supercell edge class.

    Returns
    -------
    base_edge : (n_edges,) int64
    cell : (n_edges, dim) int64
        In ``0 <= cell < sizes``: the cell of the base edge's first vertex.
    """
    if base.lattice is None or supercell.lattice is None:
        raise ScaffoldError(f"{base.name}: motifs need a periodic scaffold")
    sizes_arr = np.asarray(sizes, np.int64)
    verts, cells = _cells_of(base, supercell.vertices)
    index = {tuple(k): i for i, k in enumerate(base.edge_keys.tolist())}
    base_edge = np.empty(supercell.n_edges, np.int64)
    cell = np.empty((supercell.n_edges, base.dim), np.int64)
    for i, (a, b, *delta) in enumerate(supercell.edge_keys.tolist()):
        ca, cb = cells[a], cells[b] + np.asarray(delta) * sizes_arr
        forward = (int(verts[a]), int(verts[b]), *(cb - ca).tolist())
        backward = (int(verts[b]), int(verts[a]), *(ca - cb).tolist())
        if forward in index:
            base_edge[i], cell[i] = index[forward], ca % sizes_arr
        elif backward in index:
            base_edge[i], cell[i] = index[backward], cb % sizes_arr
        else:
            raise ScaffoldError(f"{supercell.name}: edge class {i} is no copy of an edge class of {base.name}")
    return base_edge, cell


def tiling_matrix(block: Sequence[int], shifts: Sequence[int] = ()) -> np.ndarray:
    """Return the lower-triangular tiling lattice ``M`` of a block with offsets.

    ``block = (m_1, ..., m_d)``; ``shifts`` lists the entries below the diagonal row by row
    (``M[1, 0]``, then ``M[2, 0], M[2, 1]``): ``tiling_matrix((2, 1), (1,))`` is the brick bond.
    """
    d = len(block)
    m = np.diag(np.asarray(block, np.int64))
    below = [(i, j) for i in range(d) for j in range(i)]
    if len(shifts) not in (0, len(below)) or min(block) < 1:
        raise LabelError(f"a block of {d} sizes >= 1 takes {len(below)} offsets, got {list(block)} and {list(shifts)}")
    for (i, j), s in zip(below, shifts, strict=False):
        m[i, j] = s
    return m


def reduce_cells(cells: np.ndarray, tiling: np.ndarray) -> np.ndarray:
    """Index in the block of each cell ``(n, dim)`` modulo the rows of ``tiling``."""
    c = np.array(cells, np.int64)
    for i in range(len(tiling) - 1, -1, -1):
        c -= np.floor_divide(c[:, i], tiling[i, i])[:, None] * tiling[i][None, :]
    block = np.diag(tiling)
    return np.ravel_multi_index(tuple(c.T), tuple(block.tolist()))


def check_tiles(tiling: np.ndarray, sizes: Sequence[int]) -> None:
    """Refuse a tiling whose repeats do not close up around the supercell."""
    periods = np.diag(np.asarray(sizes, np.int64))
    if np.any(reduce_cells(periods, tiling) != 0) or np.any(np.diag(tiling) > np.asarray(sizes)):
        raise LabelError(f"the motif tiling {tiling.tolist()} does not repeat evenly over a {list(sizes)} supercell")


def motif_labels(base_edge: np.ndarray, cell: np.ndarray, motif: ArrayLike, tiling: np.ndarray) -> np.ndarray:
    """Supercell labels ``(n_edges,) int64`` of ``motif (n_block_cells, n_base_edges)`` repeated by ``tiling``."""
    m = np.asarray(motif, np.int64).reshape(int(np.prod(np.diag(tiling))), -1)
    return m[reduce_cells(cell, tiling), base_edge]


def gradient_labels(base_edge: np.ndarray, cell: np.ndarray, values: ArrayLike, direction: Sequence[int]) -> np.ndarray:
    """Supercell labels from ``values`` by layer ``cell . direction`` (``(L,)`` or ``(L, n_base_edges)``)."""
    v = np.asarray(values, np.int64)
    layer = (cell @ np.asarray(direction, np.int64)) % len(v)
    return v[layer] if v.ndim == 1 else v[layer, base_edge]


@dataclass(frozen=True)
class MotifClass:
    """Motifs whose supercell designs are one design up to the supercell's symmetry.

    Attributes
    ----------
    motif : (n_block_cells, n_base_edges) int64
        The first motif of the class (lexicographic).
    labels : (n_edges,) int64
        Its supercell labels.
    motifs : int
        Motifs in the class.
    """

    motif: np.ndarray
    labels: np.ndarray
    motifs: int


def motif_classes(
    base_edge: np.ndarray,
    cell: np.ndarray,
    tiling: np.ndarray,
    label_set: Sequence[int],
    perms: np.ndarray,
    signs: np.ndarray,
) -> list[MotifClass]:
    """Every motif with labels from ``label_set``, grouped by design up to the actions ``(perms, signs)``.

    ``perms (n_g, n_edges)``, ``signs (n_g,)``: the supercell symmetry's signed edge
    permutations (``SymmetryGroup.action``).  Two motifs are one class when their supercell
    labels are related by an action (the image of ``t`` has ``signs[g] * t[e]`` on ``perms[g, e]``).
    """
    n_cells = int(np.prod(np.diag(tiling)))
    n_vars = n_cells * (int(base_edge.max()) + 1)
    if len(label_set) ** n_vars > MAX_MOTIFS:
        raise TooLargeError(
            f"{len(label_set)}^{n_vars} motifs (limit {MAX_MOTIFS:,}); use a smaller block or label set"
        )
    motifs = np.array(list(itertools.product(label_set, repeat=n_vars)), np.int64).reshape(
        -1, n_cells, n_vars // n_cells
    )
    where = reduce_cells(cell, tiling) * (n_vars // n_cells) + base_edge
    rows = motifs.reshape(len(motifs), -1)[:, where]
    best = rows.copy()
    for perm, sign in zip(perms, signs, strict=True):
        image = np.empty_like(rows)
        image[:, perm] = sign * rows
        swap = _lex_less(image, best)
        best[swap] = image[swap]
    keys, first, counts = np.unique(best, axis=0, return_index=True, return_counts=True)
    order = np.argsort(first)
    return [MotifClass(motifs[first[i]], rows[first[i]], int(counts[i])) for i in order.tolist()]


def _lex_less(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(m,) bool: row ``a[i]`` lexicographically before ``b[i]``."""
    diff = a != b
    first = diff.argmax(axis=1)
    rows = np.arange(len(a))
    return diff.any(axis=1) & (a[rows, first] < b[rows, first])
