"""Diagrams from labels: a design's PD code assembled from the scaffold and its labels alone.

The strands of every design of a finite scaffold are made of the same **pieces**
(:mod:`lkspace.geometry.construction`): the corner turn inside each face (one per side,
whatever the labels) and, along each edge of degree ``K``, the edge piece of each slot
for the edge's twist ``t`` (it depends on that edge's twist only).  A
:class:`DiagramTemplate` realizes every piece once, for every twist of a label set, and
projects them all along one generic direction; it keeps every crossing between two
pieces that can meet in one design (pieces of one edge with different twists never do).

A design then needs no geometry: :func:`assemble_pd` walks its strands exactly as the
trace does (:func:`lkspace.strands.walk.walk_strands`: from the smallest unvisited port,
corner link then edge link), passes the pieces in the order and direction the walk meets
them, keeps the crossings whose two pieces are both in the design, and numbers the edges
of the PD code along the way.  Component order and orientation are the trace's, so the
linking matrix reads as :func:`lkspace.knots.recognition.identify`'s.  The crossings at an
edge are thereby those of its ``K``-strand helix of ``t / K`` turns, seen from the fixed
direction, and the crossings between faces' tracks are computed once per scaffold.

PD convention as in :mod:`lkspace.knots.diagram` (KnotTheory, 1-based).
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.spatial.transform import Rotation

from ..errors import DiagramError, UsageError
from ..geometry.construction import corner_pieces, edge_pieces
from ..geometry.params import GeometryParams, Resolved
from ..geometry.tracks import side_tracks
from ..kernels import helper, kernel
from ..model.scaffold import Scaffold
from ..strands.ports import port_model
from .diagram import near_pairs, transverse


@dataclass(frozen=True, eq=False)
class DiagramTemplate:
    """Every crossing a design of one scaffold can have, for twists in ``label_values``.

    Pieces: ``0 .. n - 1`` the corner turns (turn ``s`` from port ``2 s + 1`` to its
    corner partner), then ``n + v n + j`` the edge piece of slot position ``j`` for twist
    ``label_values[v]`` (from ``port_a[j]`` to the end-``b`` port it reaches), ``n =
    n_corners``.

    Attributes
    ----------
    label_values : (n_values,) int64
        Sorted twists the template covers.
    corner_partner, port_a, port_b, slot_edge, slot_index, edge_starts, degrees : int64 arrays
        The port model (:class:`~lkspace.strands.ports.PortModel`) and edge degrees.
    slot_of_a, slot_of_b : (2 n,) int64
        The slot position whose end-``a`` (end-``b``) port each port is, else -1.
    pass_offsets : (n_pieces + 1,) int64
        Piece ``p``'s passages are ``pass_offsets[p]:pass_offsets[p + 1]``, in order along it.
    pass_crossing, pass_other : (n_passages,) int64
        The crossing of each passage and the other piece at it.
    pass_over : (n_passages,) bool
        The piece passes over.
    crossing_sign : (n_crossings,) int64
        Sign of each crossing when both pieces run their own way (a reversed piece flips it).
    """

    label_values: np.ndarray
    corner_partner: np.ndarray
    port_a: np.ndarray
    port_b: np.ndarray
    slot_edge: np.ndarray
    slot_index: np.ndarray
    edge_starts: np.ndarray
    degrees: np.ndarray
    slot_of_a: np.ndarray
    slot_of_b: np.ndarray
    pass_offsets: np.ndarray
    pass_crossing: np.ndarray
    pass_other: np.ndarray
    pass_over: np.ndarray
    crossing_sign: np.ndarray

    @property
    def n_crossings(self) -> int:
        """Crossings over all pieces (a design keeps those between its own pieces)."""
        return len(self.crossing_sign)

    def value_index(self, labels: ArrayLike) -> np.ndarray:
        """Index into ``label_values`` of each label, ``(..., n_edges) int64``; refuses a twist not covered."""
        lab = np.asarray(labels, np.int64)
        idx = np.searchsorted(self.label_values, lab)
        idx = np.minimum(idx, len(self.label_values) - 1)
        bad = self.label_values[idx] != lab
        if bad.any():
            raise UsageError(
                f"labels: twist {int(lab[bad].flat[0])} is not in the template's label set "
                f"{self.label_values.tolist()}",
                parameter="labels",
            )
        return idx

    def arrays(self) -> tuple[np.ndarray, ...]:
        """The arrays :func:`assemble_into` takes, in its order."""
        return (
            self.corner_partner,
            self.port_a,
            self.port_b,
            self.slot_edge,
            self.slot_index,
            self.edge_starts,
            self.degrees,
            self.slot_of_a,
            self.slot_of_b,
            self.label_values,
            self.pass_offsets,
            self.pass_crossing,
            self.pass_other,
            self.pass_over,
            self.crossing_sign,
        )


def build_template(scaffold: Scaffold, label_values: ArrayLike, seed: int = 0) -> DiagramTemplate:
    """Realize every piece for twists ``label_values``, project them along a seeded generic direction.

    A rare non-generic direction (two crossings at one height) is turned again (three tries).
    """
    if scaffold.periodic:
        raise UsageError(f"{scaffold.name}: a periodic scaffold has no finite diagram", parameter="scaffold")
    values = np.unique(np.asarray(label_values, np.int64).reshape(-1))
    if not len(values):
        values = np.zeros(1, np.int64)
    shape = Resolved.of(scaffold, GeometryParams(smooth=False))
    fr = side_tracks(scaffold, shape.radius, shape.normal_offset, shape.margin, shape.near_angle)
    polylines = list(corner_pieces(scaffold, fr, shape))
    for t in values:
        points, offsets = edge_pieces(scaffold, fr, shape, int(t))
        polylines.extend(np.split(points, offsets[1:-1]))
    for attempt in range(3):
        try:
            return _template(scaffold, values, polylines, seed + attempt)
        except DiagramError:
            if attempt == 2:
                raise
    raise AssertionError("unreachable")  # pragma: no cover


def _template(scaffold: Scaffold, values: np.ndarray, polylines: list[np.ndarray], seed: int) -> DiagramTemplate:
    n = scaffold.n_corners
    model = port_model(scaffold)
    rot = Rotation.random(random_state=seed).as_matrix()
    sizes = np.array([len(p) - 1 for p in polylines], np.int64)
    piece = np.repeat(np.arange(len(polylines)), sizes)
    step = np.concatenate([np.arange(k) for k in sizes])
    allpts = np.vstack(polylines) @ rot.T
    starts = np.concatenate([[0], np.cumsum(sizes + 1)])[:-1]
    first = np.repeat(starts, sizes) + step
    p0, p1 = allpts[first], allpts[first + 1]
    # segments meeting at a port (piece ends) or at a polyline vertex are not crossings
    start_port, end_port = _piece_ports(scaffold, values, model)
    i, j = near_pairs(p0, p1)
    pi, pj = piece[i], piece[j]
    same_piece_adjacent = (pi == pj) & (np.abs(step[i] - step[j]) == 1)
    ends_i = np.where(step[i] == 0, start_port[pi], -2), np.where(step[i] == sizes[pi] - 1, end_port[pi], -3)
    ends_j = np.where(step[j] == 0, start_port[pj], -4), np.where(step[j] == sizes[pj] - 1, end_port[pj], -5)
    share_port = (
        (ends_i[0] == ends_j[0]) | (ends_i[0] == ends_j[1]) | (ends_i[1] == ends_j[0]) | (ends_i[1] == ends_j[1])
    )
    # pieces of one edge with different twists never meet in a design
    edge_i, value_i = _piece_edge(pi, n, model.slot_edge)
    edge_j, value_j = _piece_edge(pj, n, model.slot_edge)
    exclusive = (edge_i >= 0) & (edge_i == edge_j) & (value_i != value_j)
    keep = ~(same_piece_adjacent | share_port | exclusive)
    over, under, t_over, t_under, signs = transverse(p0, p1, i[keep], j[keep])
    n_x = len(over)
    seg = np.concatenate([over, under])
    pos = step[seg] + np.concatenate([t_over, t_under])
    owner = piece[seg]
    other = np.concatenate([piece[under], piece[over]])
    order = np.lexsort((pos, owner))
    counts = np.bincount(owner, minlength=len(polylines))
    crossing = np.concatenate([np.arange(n_x), np.arange(n_x)])
    is_over = np.concatenate([np.ones(n_x, bool), np.zeros(n_x, bool)])
    slot_of_a = np.full(2 * n, -1, np.int64)
    slot_of_a[model.port_a] = np.arange(n)
    slot_of_b = np.full(2 * n, -1, np.int64)
    slot_of_b[model.port_b] = np.arange(n)
    return DiagramTemplate(
        label_values=values,
        corner_partner=model.corner_partner,
        port_a=model.port_a,
        port_b=model.port_b,
        slot_edge=model.slot_edge,
        slot_index=model.slot_index,
        edge_starts=np.ascontiguousarray(model.edge_starts),
        degrees=np.ascontiguousarray(scaffold.edge_degrees, np.int64),
        slot_of_a=slot_of_a,
        slot_of_b=slot_of_b,
        pass_offsets=np.concatenate([[0], np.cumsum(counts)]),
        pass_crossing=crossing[order],
        pass_other=other[order],
        pass_over=is_over[order],
        crossing_sign=signs,
    )


def _piece_ports(scaffold: Scaffold, values: np.ndarray, model: object) -> tuple[np.ndarray, np.ndarray]:
    """Start and end port of every piece (``(n_pieces,) int64``)."""
    from ..strands.ports import PortModel, edge_partner

    assert isinstance(model, PortModel)
    n = scaffold.n_corners
    corner_start = 2 * np.arange(n) + 1
    starts, ends = [corner_start], [model.corner_partner[corner_start]]
    for t in values:
        partner = edge_partner(model, scaffold.edge_degrees, np.full(scaffold.n_edges, t))
        starts.append(model.port_a)
        ends.append(partner[model.port_a])
    return np.concatenate(starts), np.concatenate(ends)


def _piece_edge(piece: np.ndarray, n: int, slot_edge: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Edge (-1 for a corner turn) and twist index of pieces."""
    edge_piece = piece >= n
    rest = np.maximum(piece - n, 0)
    return np.where(edge_piece, slot_edge[rest % n], -1), np.where(edge_piece, rest // n, -1)


_TEMPLATES: weakref.WeakKeyDictionary[Scaffold, dict[tuple[tuple[int, ...], int], DiagramTemplate]] = (
    weakref.WeakKeyDictionary()
)


def template(scaffold: Scaffold, label_values: ArrayLike, seed: int = 0) -> DiagramTemplate:
    """The scaffold's :class:`DiagramTemplate` for ``label_values`` and ``seed``, built once per live scaffold."""
    values = tuple(int(v) for v in np.unique(np.asarray(label_values, np.int64)))
    per = _TEMPLATES.setdefault(scaffold, {})
    key = (values, seed)
    if key not in per:
        per[key] = build_template(scaffold, values, seed)
    return per[key]


WORK_ROWS = 7
"""Rows of :func:`assemble_into`'s scratch array."""


def work_array(tmpl: DiagramTemplate) -> np.ndarray:
    """Scratch for :func:`assemble_into`: ``(WORK_ROWS, 2 n_crossings + 1) int64``, row 0 all -1."""
    work = np.zeros((WORK_ROWS, 2 * tmpl.n_crossings + 1), np.int64)
    work[0] = -1
    return work


@helper
def assemble_into(
    corner_partner: np.ndarray,
    port_a: np.ndarray,
    port_b: np.ndarray,
    slot_edge: np.ndarray,
    slot_index: np.ndarray,
    edge_starts: np.ndarray,
    degrees: np.ndarray,
    slot_of_a: np.ndarray,
    slot_of_b: np.ndarray,
    label_values: np.ndarray,
    pass_offsets: np.ndarray,
    pass_crossing: np.ndarray,
    pass_other: np.ndarray,
    pass_over: np.ndarray,
    crossing_sign: np.ndarray,
    vidx: np.ndarray,
    pd: np.ndarray,
    signs: np.ndarray,
    comps: np.ndarray,
    work: np.ndarray,
) -> tuple[int, int, int]:
    """Assemble the PD code of the design whose edges take twists ``label_values[vidx]``.

    Writes ``pd[:m]`` (``(m, 4)``, 1-based), ``signs[:m]`` and ``comps[:m]`` (over and
    under component of each crossing, ``(m, 2)``); returns ``(m, n_components, n_free)``
    (``n_free``: components without a crossing).  ``work`` is scratch from
    :func:`work_array` (row 0 is all -1 again on return).
    """
    local, glob, seq_cross, seq_over, seq_comp, seq_into, seq_out = (
        work[0], work[1], work[2], work[3], work[4], work[5], work[6]
    )
    n = len(port_a)
    visited = np.zeros(2 * n, np.bool_)
    m = 0  # crossings of the design so far
    n_seq = 0  # passages so far
    n_comp = 0
    n_free = 0
    for x0 in range(2 * n):
        if visited[x0]:
            continue
        comp_first = n_seq
        x = x0
        while True:
            y = corner_partner[x]  # the corner turn from x (turn s runs from port 2 s + 1)
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
                # the edge link from y: its slot's piece passed forward from end a, or back from end b
                j = slot_of_a[y]
                if j >= 0:
                    e = slot_edge[j]
                    kk = degrees[e]
                    y = port_b[edge_starts[e] + (slot_index[j] + label_values[vidx[e]] % kk) % kk]
                    forward = True
                else:
                    mb = slot_of_b[y]
                    e = slot_edge[mb]
                    kk = degrees[e]
                    j = edge_starts[e] + (slot_index[mb] - label_values[vidx[e]] % kk + kk) % kk
                    y = port_a[j]
                    forward = False
                piece = n + vidx[e] * n + j
            x = y
            if x == x0:
                break
        count = n_seq - comp_first
        if count == 0:
            n_free += 1
        for i in range(count):  # passage i enters by the component's edge i and leaves by edge i + 1
            seq_into[comp_first + i] = comp_first + (i - 1 + count) % count + 1
            seq_out[comp_first + i] = comp_first + i + 1
        n_comp += 1
    for i in range(n_seq):
        c = seq_cross[i]
        if seq_over[i] == 1:
            comps[c, 0] = seq_comp[i]
            if signs[c] > 0:  # X[under in, over out, under out, over in]
                pd[c, 1] = seq_out[i]
                pd[c, 3] = seq_into[i]
            else:  # X[under in, over in, under out, over out]
                pd[c, 1] = seq_into[i]
                pd[c, 3] = seq_out[i]
        else:
            comps[c, 1] = seq_comp[i]
            pd[c, 0] = seq_into[i]
            pd[c, 2] = seq_out[i]
    for i in range(m):
        local[glob[i]] = -1
    return m, n_comp, n_free


@kernel
def assemble_one(
    corner_partner: np.ndarray,
    port_a: np.ndarray,
    port_b: np.ndarray,
    slot_edge: np.ndarray,
    slot_index: np.ndarray,
    edge_starts: np.ndarray,
    degrees: np.ndarray,
    slot_of_a: np.ndarray,
    slot_of_b: np.ndarray,
    label_values: np.ndarray,
    pass_offsets: np.ndarray,
    pass_crossing: np.ndarray,
    pass_other: np.ndarray,
    pass_over: np.ndarray,
    crossing_sign: np.ndarray,
    vidx: np.ndarray,
    work: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, int, int]:
    """One design's ``(pd, signs, comps, n_components, n_free)`` (:func:`assemble_into`)."""
    size = len(crossing_sign)
    pd = np.zeros((size, 4), np.int64)
    signs = np.zeros(size, np.int64)
    comps = np.zeros((size, 2), np.int64)
    m, n_comp, n_free = assemble_into(
        corner_partner,
        port_a,
        port_b,
        slot_edge,
        slot_index,
        edge_starts,
        degrees,
        slot_of_a,
        slot_of_b,
        label_values,
        pass_offsets,
        pass_crossing,
        pass_other,
        pass_over,
        crossing_sign,
        vidx,
        pd,
        signs,
        comps,
        work,
    )
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
    """The diagram of ``scaffold`` under twist ``labels`` (no nulls), from its :func:`template`.

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
    pd, signs, comps, n_comp, n_free = assemble_one(*tmpl.arrays(), tmpl.value_index(lab), work_array(tmpl))
    return LabelDiagram(pd, signs, comps, int(n_comp), int(n_free))
