"""The determinant of a knot or link, from its PD code: a filter cheaper than the Jones polynomial.

The determinant ``det L = |V_L(-1)| = |Delta_L(-1)|`` is the absolute value of any first
minor of the diagram's **coloring matrix**: one row per crossing, one column per arc (an
over-strand from one undercrossing to the next), the row of ``X[a, b, c, d]`` holding
``+2`` at the arc through ``b`` and ``d`` (over) and ``-1`` at the arcs ending at ``a`` and
starting at ``c`` (under).  A split diagram (a free component, or a component passing only
over the others, so more arcs than crossings) has determinant 0, as a split link does.

Two forms: :func:`determinant` exact (Python integers, Bareiss elimination) for a target's
table diagram, and the compiled :func:`design_determinants` modulo the prime
:data:`~lkspace.knots.keyed.PRIME` for the designs of a search.  A design whose residue is
neither ``det`` nor ``-det`` of the target is proved to be another type; equal residues
prove nothing (the Jones polynomial and the tables decide).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..compiled.kernels import helper, kernel
from ..model.scaffold import Scaffold
from .assembly import Scratch, assemble_into, work_array
from .keyed import PRIME, power_mod
from .labels_diagram import TemplateArrays, template

MAX_DET_CROSSINGS = 400
"""Designs with more crossings get no residue (-1): elimination is cubic in the crossings."""


def _arcs(pd: Any) -> tuple[list[int], int]:
    """Return the arc of every edge (0-based edge ``e`` -> arc id) and the number of arcs: over edges ``b``, ``d`` joined."""
    n_edges = 2 * len(pd)
    parent = list(range(n_edges))

    def root(e: int) -> int:
        while parent[e] != e:
            parent[e] = parent[parent[e]]
            e = parent[e]
        return e

    for _, b, _, d in pd:
        parent[root(b - 1)] = root(d - 1)
    ids: dict[int, int] = {}
    arc = [ids.setdefault(root(e), len(ids)) for e in range(n_edges)]
    return arc, len(ids)


def coloring_matrix(pd: Any) -> list[list[int]]:
    """Return the coloring matrix of a PD code (1-based, ``X[a, b, c, d]`` from the incoming under edge): rows crossings, columns arcs."""
    arc, n_arcs = _arcs(pd)
    rows = []
    for a, b, c, _ in pd:
        row = [0] * n_arcs
        row[arc[b - 1]] += 2
        row[arc[a - 1]] -= 1
        row[arc[c - 1]] -= 1
        rows.append(row)
    return rows


def determinant(pd: Any, n_free: int = 0) -> int:
    """Return the determinant of the link of a PD code with ``n_free`` more components without crossings (exact).

    >>> determinant([[1, 5, 2, 4], [3, 1, 4, 6], [5, 3, 6, 2]])  # a trefoil
    3
    >>> determinant([[4, 1, 3, 2], [2, 3, 1, 4]])  # the Hopf link
    2
    """
    if n_free or not len(pd):
        return 0 if n_free + (len(pd) > 0) > 1 else 1
    rows = coloring_matrix(pd)
    if len(rows[0]) != len(rows):
        return 0
    minor = [r[:-1] for r in rows[:-1]]
    return abs(_bareiss(minor))


def _bareiss(m: list[list[int]]) -> int:
    """Return the determinant of a square integer matrix (fraction-free elimination; ``m`` is consumed)."""
    n = len(m)
    sign, prev = 1, 1
    for k in range(n - 1):
        if m[k][k] == 0:
            swap = next((r for r in range(k + 1, n) if m[r][k] != 0), None)
            if swap is None:
                return 0
            m[k], m[swap] = m[swap], m[k]
            sign = -sign
        for i in range(k + 1, n):
            for j in range(k + 1, n):
                m[i][j] = (m[i][j] * m[k][k] - m[i][k] * m[k][j]) // prev
        prev = m[k][k]
    return sign * m[n - 1][n - 1] if n else 1


@helper
def _root(parent: np.ndarray, e: int) -> int:
    """Return the representative of edge ``e``'s arc in the union-find ``parent``."""
    while parent[e] != e:
        e = parent[e]
    return e


@helper
def determinant_residue(pd: np.ndarray, m: int, n_free: int, scratch: np.ndarray, matrix: np.ndarray) -> int:
    """Return the determinant of ``pd[:m]`` (``n_free`` free components more) modulo :data:`PRIME`, up to sign; -1 past the cap.

    ``scratch`` ``(2, >= 2m)`` and ``matrix`` ``(>= m, >= m)`` are work space.
    """
    if m == 0:
        return 1 if n_free <= 1 else 0
    if n_free > 0:
        return 0
    if m > MAX_DET_CROSSINGS:
        return -1
    parent = scratch[0]
    arc = scratch[1]
    for e in range(2 * m):
        parent[e] = e
        arc[e] = -1
    for c in range(m):  # an arc runs on through its overcrossings: edges b and d are one arc
        x = _root(parent, pd[c, 1] - 1)
        y = _root(parent, pd[c, 3] - 1)
        if x != y:
            parent[x] = y
    n_arcs = 0
    for e in range(2 * m):
        r = _root(parent, e)
        if arc[r] < 0:
            arc[r] = n_arcs
            n_arcs += 1
    if n_arcs != m:  # a component with no undercrossing: split
        return 0
    n = m - 1  # the minor without the last crossing and the last arc
    for i in range(n):
        for j in range(n):
            matrix[i, j] = 0
    for c in range(n):
        for slot in range(3):
            a = arc[_root(parent, pd[c, slot] - 1)]
            if a < n:
                matrix[c, a] = (matrix[c, a] + (2 if slot == 1 else PRIME - 1)) % PRIME
    det = 1
    for k in range(n):
        pivot = -1
        for r in range(k, n):
            if matrix[r, k] != 0:
                pivot = r
                break
        if pivot < 0:
            return 0
        for j in range(k, n):  # a row swap changes the sign only
            matrix[k, j], matrix[pivot, j] = matrix[pivot, j], matrix[k, j]
        det = det * matrix[k, k] % PRIME
        inv = power_mod(matrix[k, k], PRIME - 2)
        for r in range(k + 1, n):
            f = matrix[r, k] * inv % PRIME
            if f == 0:
                continue
            for j in range(k, n):
                if matrix[k, j] != 0:
                    matrix[r, j] = (matrix[r, j] + (PRIME - f) * matrix[k, j]) % PRIME
    return det


@kernel
def design_determinants(tmpl: TemplateArrays, vidx_2d: np.ndarray, work: Scratch) -> np.ndarray:
    """``(n_designs,) int64``: each design's determinant modulo :data:`PRIME`, up to sign (-1: too many crossings).

    ``vidx_2d`` ``(n_designs, n_edges)``: indices into the template's ``label_values``.
    """
    n_designs = vidx_2d.shape[0]
    size = len(tmpl.crossing_sign)
    pd = np.zeros((size, 4), np.int64)
    signs = np.zeros(size, np.int64)
    comps = np.zeros((size, 2), np.int64)
    scratch = np.zeros((2, 2 * size + 2), np.int64)
    side = min(size, MAX_DET_CROSSINGS) + 1
    matrix = np.zeros((side, side), np.int64)
    out = np.zeros(n_designs, np.int64)
    for d in range(n_designs):
        m, _, n_free = assemble_into(tmpl, vidx_2d[d], pd, signs, comps, work)
        out[d] = determinant_residue(pd, m, n_free, scratch, matrix)
    return out


def determinants_of(scaffold: Scaffold, labels_2d: np.ndarray, seed: int = 0, label_values: Any = None) -> np.ndarray:
    """Return the determinants modulo :data:`PRIME`, up to sign, of ``labels_2d`` (``(n, n_edges)``; -1: not computed)."""
    values = np.unique(labels_2d) if label_values is None else np.union1d(label_values, np.unique(labels_2d))
    tmpl = template(scaffold, values, seed)
    vidx = tmpl.value_index(labels_2d)
    return design_determinants(tmpl.arrays(), np.ascontiguousarray(vidx), work_array(tmpl))


def same_determinant(residues: np.ndarray, det: int) -> np.ndarray:
    """``(n,) bool``: residues (:func:`determinants_of`) that may be ``det`` (``±det`` modulo the prime, or not computed)."""
    return (residues < 0) | (residues == det % PRIME) | (residues == -det % PRIME)
