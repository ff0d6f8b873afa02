"""Many designs' PD codes assembled in one compiled call (:func:`assemble_many`).

One call per design costs numba's argument checks (about 50 µs for the template's
arrays); a batch of designs checked against their names needs thousands of diagrams.
"""

from __future__ import annotations

import numpy as np

from ..compiled.kernels import helper, kernel
from .assembly import Scratch, assemble_into
from .labels_diagram import TemplateArrays


@helper
def _pieces(comps: np.ndarray, m: int, n_comp: int, parent: np.ndarray) -> int:
    """Return the pieces of a diagram: its ``n_comp`` components joined where they cross (``comps[:m]``)."""
    for i in range(n_comp):
        parent[i] = i
    pieces = n_comp
    for c in range(m):
        a = comps[c, 0]
        while parent[a] != a:
            a = parent[a]
        b = comps[c, 1]
        while parent[b] != b:
            b = parent[b]
        if a != b:
            parent[a] = b
            pieces -= 1
    return pieces


@kernel
def assemble_many(tmpl: TemplateArrays, vidx_2d: np.ndarray, work: Scratch) -> tuple[np.ndarray, ...]:
    """PD codes of the designs ``vidx_2d`` ``(n, n_edges)`` (indices into the template's values), one after another.

    Returns ``(pd (total, 4), signs (total,), offsets (n + 1,), components (n,),
    pieces (n,))``, all int64: design ``i``'s crossings are rows ``offsets[i]`` to
    ``offsets[i + 1]`` (as :func:`~lkspace.knots.assembly.assemble_one` gives them);
    ``pieces``: its components joined where they cross, a free component alone.
    """
    n = vidx_2d.shape[0]
    size = len(tmpl.crossing_sign)
    pd_one = np.zeros((size, 4), np.int64)
    signs_one = np.zeros(size, np.int64)
    comps = np.zeros((size, 2), np.int64)
    offsets = np.zeros(n + 1, np.int64)
    for i in range(n):  # first the sizes, then the rows
        m, _, _ = assemble_into(tmpl, vidx_2d[i], pd_one, signs_one, comps, work)
        offsets[i + 1] = offsets[i] + m
    pd = np.zeros((offsets[n], 4), np.int64)
    signs = np.zeros(offsets[n], np.int64)
    components = np.zeros(n, np.int64)
    pieces = np.zeros(n, np.int64)
    parent = np.zeros(max(size, 1) + 1, np.int64)
    for i in range(n):
        start = offsets[i]
        end = offsets[i + 1]
        m, n_comp, _ = assemble_into(tmpl, vidx_2d[i], pd[start:end], signs[start:end], comps, work)
        components[i] = n_comp
        if n_comp > len(parent):
            parent = np.zeros(n_comp, np.int64)
        pieces[i] = _pieces(comps, m, n_comp, parent)
    return pd, signs, offsets, components, pieces
