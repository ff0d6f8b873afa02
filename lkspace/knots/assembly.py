"""Assembling a design's PD code from a :class:`~lkspace.knots.labels_diagram.DiagramTemplate`.

:func:`assemble_into` (compiled, called in the loops of :mod:`lkspace.knots.keyed`) walks
the design's strands exactly as the trace does (:func:`lkspace.strands.walk.walk_strands`:
from the smallest unvisited port, corner link then edge link), passes the pieces in the
order and direction the walk meets them, keeps the crossings whose two pieces are both
in the design, and numbers the edges of the PD code along the way.  Component order and
orientation are the trace's, so the linking matrix reads as
:func:`lkspace.knots.recognition.identify`'s.  PD convention as in
:mod:`lkspace.knots.diagram` (KnotTheory, 1-based).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ..compiled.kernels import helper, kernel
from ..errors import UsageError
from ..model.scaffold import Scaffold
from .labels_diagram import DiagramTemplate, TemplateArrays, template


class Scratch(NamedTuple):
    """Scratch of :func:`assemble_into`: ``(2 n_crossings + 1,) int64`` each (:func:`work_array`).

    Attributes
    ----------
    local : the design's number of each template crossing, -1 where not met (all -1 between designs)
    glob : the template crossing of each of the design's crossings
    seq_cross, seq_over, seq_comp : per passage along the strands, its crossing (the design's
        number), 1 if it passes over, its component
    seq_into, seq_out : per passage, the PD edge it enters and leaves by
    """

    local: np.ndarray
    glob: np.ndarray
    seq_cross: np.ndarray
    seq_over: np.ndarray
    seq_comp: np.ndarray
    seq_into: np.ndarray
    seq_out: np.ndarray


def work_array(tmpl: DiagramTemplate) -> Scratch:
    """Scratch for :func:`assemble_into`, ``local`` all -1."""
    size = 2 * tmpl.n_crossings + 1
    return Scratch(np.full(size, -1, np.int64), *(np.zeros(size, np.int64) for _ in Scratch._fields[1:]))


@helper
def _walk(t: TemplateArrays, vidx: np.ndarray, signs: np.ndarray, work: Scratch) -> tuple[int, int, int, int]:
    """Walk the design's strands, recording the passages at crossings of two of its pieces.

    From the smallest unvisited port, the corner turn then the edge link, as the trace
    does; each piece is passed in the direction the walk meets it (an edge piece forward
    from end ``a``, back from end ``b``).  New crossings take the next numbers, their sign
    the template's, flipped for each piece run backwards.  Returns ``(m, n_seq, n_comp,
    n_free)``: crossings, passages, components and components without a crossing.
    """
    pass_offsets, pass_other, pass_crossing, pass_over = t.pass_offsets, t.pass_other, t.pass_crossing, t.pass_over
    slot_edge, crossing_sign, label_values, degrees = t.slot_edge, t.crossing_sign, t.label_values, t.degrees
    local, glob, seq_cross, seq_over, seq_comp = work.local, work.glob, work.seq_cross, work.seq_over, work.seq_comp
    n = len(t.port_a)
    visited = np.zeros(2 * n, np.bool_)
    m = n_seq = n_comp = n_free = 0
    for x0 in range(2 * n):
        if visited[x0]:
            continue
        comp_first = n_seq
        x = x0
        # lkspace.strands.walk.walk_strand written out: building the edge links first and passing its
        # steps again for the crossings cost this kernel 3-21% in designs per second (measured, interleaved)
        while True:
            y = t.corner_partner[x]  # the corner turn from x (turn s runs from port 2 s + 1)
            visited[x] = True
            visited[y] = True
            piece = x // 2 if x % 2 == 1 else y // 2
            forward = x % 2 == 1
            for pass_round in range(2):
                lo = pass_offsets[piece]
                hi = pass_offsets[piece + 1]
                for q in range(hi - lo):
                    k = lo + q if forward else hi - 1 - q
                    o = pass_other[k]
                    if o >= n and vidx[slot_edge[(o - n) % n]] != (o - n) // n:
                        continue  # the other piece is not in this design
                    c = pass_crossing[k]
                    if local[c] < 0:
                        local[c] = m
                        glob[m] = c
                        signs[m] = crossing_sign[c]
                        m += 1
                    if not forward:
                        signs[local[c]] = -signs[local[c]]
                    seq_cross[n_seq] = local[c]
                    seq_over[n_seq] = 1 if pass_over[k] else 0
                    seq_comp[n_seq] = n_comp
                    n_seq += 1
                if pass_round == 1:
                    break
                j = t.slot_of_a[y]  # the edge link from y
                if j >= 0:
                    e = slot_edge[j]
                    kk = degrees[e]
                    y = t.port_b[t.edge_starts[e] + (t.slot_index[j] + label_values[vidx[e]] % kk) % kk]
                    forward = True
                else:
                    mb = t.slot_of_b[y]
                    e = slot_edge[mb]
                    kk = degrees[e]
                    j = t.edge_starts[e] + (t.slot_index[mb] - label_values[vidx[e]] % kk + kk) % kk
                    y = t.port_a[j]
                    forward = False
                piece = n + vidx[e] * n + j
            x = y
            if x == x0:
                break
        if n_seq == comp_first:
            n_free += 1
        _label_edges(work.seq_into, work.seq_out, comp_first, n_seq)
        n_comp += 1
    return m, n_seq, n_comp, n_free


@helper
def _label_edges(seq_into: np.ndarray, seq_out: np.ndarray, first: int, end: int) -> None:
    """Label the PD edges of one component's passages ``first:end``: passage i enters by edge i, leaves by i + 1."""
    count = end - first
    for i in range(count):
        seq_into[first + i] = first + (i - 1 + count) % count + 1
        seq_out[first + i] = first + i + 1


@helper
def _write_pd(work: Scratch, n_seq: int, signs: np.ndarray, pd: np.ndarray, comps: np.ndarray) -> None:
    """Write each crossing's PD row and its over and under component from the passages."""
    for i in range(n_seq):
        c = work.seq_cross[i]
        if work.seq_over[i] == 1:
            comps[c, 0] = work.seq_comp[i]
            if signs[c] > 0:  # X[under in, over out, under out, over in]
                pd[c, 1] = work.seq_out[i]
                pd[c, 3] = work.seq_into[i]
            else:  # X[under in, over in, under out, over out]
                pd[c, 1] = work.seq_into[i]
                pd[c, 3] = work.seq_out[i]
        else:
            comps[c, 1] = work.seq_comp[i]
            pd[c, 0] = work.seq_into[i]
            pd[c, 2] = work.seq_out[i]


@helper
def assemble_into(
    t: TemplateArrays,
    vidx: np.ndarray,
    pd: np.ndarray,
    signs: np.ndarray,
    comps: np.ndarray,
    work: Scratch,
) -> tuple[int, int, int]:
    """Assemble the PD code of the design whose edges take twists ``label_values[vidx]``.

    ``t`` is :meth:`DiagramTemplate.arrays`.  Writes ``pd[:m]`` (``(m, 4)``, 1-based),
    ``signs[:m]`` and ``comps[:m]`` (over and under component of each crossing, ``(m,
    2)``); returns ``(m, n_components, n_free)`` (``n_free``: components without a
    crossing).  ``work`` is scratch from :func:`work_array` (``local`` is all -1 again on
    return).
    """
    m, n_seq, n_comp, n_free = _walk(t, vidx, signs, work)
    _write_pd(work, n_seq, signs, pd, comps)
    for i in range(m):
        work.local[work.glob[i]] = -1
    return m, n_comp, n_free


@kernel
def assemble_one(
    tmpl: TemplateArrays, vidx: np.ndarray, work: Scratch
) -> tuple[np.ndarray, np.ndarray, np.ndarray, int, int]:
    """One design's ``(pd, signs, comps, n_components, n_free)`` (:func:`assemble_into`)."""
    size = len(tmpl.crossing_sign)
    pd = np.zeros((size, 4), np.int64)
    signs = np.zeros(size, np.int64)
    comps = np.zeros((size, 2), np.int64)
    m, n_comp, n_free = assemble_into(tmpl, vidx, pd, signs, comps, work)
    return pd[:m], signs[:m], comps[:m], n_comp, n_free


@dataclass(frozen=True, eq=False)
class LabelDiagram:
    """A design's diagram assembled from its labels.

    Attributes
    ----------
    pd : (n_crossings, 4) int64
        PD code, 1-based (KnotTheory convention).
    signs : (n_crossings,) int64
    crossing_components : (n_crossings, 2) int64
        Over and under component (the trace's strand order).
    n_components, n_free : int
        Components, and those without any crossing.
    """

    pd: np.ndarray
    signs: np.ndarray
    crossing_components: np.ndarray
    n_components: int
    n_free: int

    def linking_matrix(self) -> np.ndarray:
        """(n_components, n_components) int64: linking numbers, zero diagonal."""
        out = np.zeros((self.n_components, self.n_components), np.int64)
        a, b = self.crossing_components[:, 0], self.crossing_components[:, 1]
        mixed = a != b
        np.add.at(out, (a[mixed], b[mixed]), self.signs[mixed])
        np.add.at(out, (b[mixed], a[mixed]), self.signs[mixed])
        return out // 2


def assemble_pd(scaffold: Scaffold, labels: ArrayLike, seed: int = 0) -> LabelDiagram:
    """Return the diagram of ``scaffold`` under twist ``labels`` (no nulls), from its :func:`template`.

    Examples
    --------
    >>> from lkspace import load
    >>> d = assemble_pd(load("dihedron:3"), [1, 1, 1])
    >>> d.n_components, int(abs(d.signs.sum())) >= 3
    (1, True)
    """
    lab = np.asarray(labels, np.int64).reshape(-1)
    if len(lab) != scaffold.n_edges:
        raise UsageError(f"labels: expected {scaffold.n_edges} labels, got {len(lab)}", parameter="labels")
    tmpl = template(scaffold, lab, seed)
    pd, signs, comps, n_comp, n_free = assemble_one(tmpl.arrays(), tmpl.value_index(lab), work_array(tmpl))
    return LabelDiagram(pd, signs, comps, int(n_comp), int(n_free))
