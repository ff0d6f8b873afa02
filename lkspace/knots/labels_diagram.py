"""Diagrams from labels: a design's PD code assembled from the scaffold and its labels alone.

The strands of every design of a finite scaffold are made of the same **pieces**
(:mod:`lkspace.geometry.construction`): the corner turn inside each face (one per side,
whatever the labels) and, along each edge of degree ``K``, the edge piece of each slot
for the edge's twist ``t`` (it depends on that edge's twist only).  A
:class:`DiagramTemplate` realizes every piece once, for every twist of a label set, and
projects them all along one generic direction; it keeps every crossing between two
pieces that can meet in one design (pieces of one edge with different twists never do).

A design then needs no geometry: :mod:`lkspace.knots.assembly` walks its strands and
keeps the crossings between its own pieces.  The crossings at an edge are thereby those
of its ``K``-strand helix of ``t / K`` turns, seen from the fixed direction, and the
crossings between faces' tracks are computed once per scaffold.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ..errors import DiagramError, UsageError
from ..geometry.construction import corner_pieces, edge_pieces
from ..geometry.params import GeometryParams, Resolved
from ..geometry.tracks import side_tracks
from ..model.scaffold import Scaffold
from ..strands.ports import PortModel, edge_partner, port_model
from .diagram import near_pairs, random_rotation, transverse


class TemplateArrays(NamedTuple):
    """The arrays of a :class:`DiagramTemplate` as compiled kernels take them (numba reads a NamedTuple by name).

    Fields as the attributes of :class:`DiagramTemplate`: all ``int64`` but ``pass_over`` (``bool``).
    """

    corner_partner: np.ndarray
    port_a: np.ndarray
    port_b: np.ndarray
    slot_edge: np.ndarray
    slot_index: np.ndarray
    edge_starts: np.ndarray
    degrees: np.ndarray
    slot_of_a: np.ndarray
    slot_of_b: np.ndarray
    label_values: np.ndarray
    pass_offsets: np.ndarray
    pass_crossing: np.ndarray
    pass_other: np.ndarray
    pass_over: np.ndarray
    crossing_sign: np.ndarray


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

    def arrays(self) -> TemplateArrays:
        """Return the arrays the compiled kernels take (:func:`~lkspace.knots.assembly.assemble_into`)."""
        return TemplateArrays(**{name: getattr(self, name) for name in TemplateArrays._fields})


def build_template(scaffold: Scaffold, label_values: ArrayLike, seed: int = 0) -> DiagramTemplate:
    """Realize every piece for twists ``label_values``, project them along a seeded generic direction.

    A rare non-generic direction (two crossings at one height) is turned again (three tries).
    """
    if scaffold.periodic:
        raise UsageError(f"{scaffold.name}: a periodic scaffold has no finite diagram", parameter="scaffold")
    values = np.array(sorted(set(np.asarray(label_values, np.int64).reshape(-1).tolist())), np.int64)
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
    rot = random_rotation(seed)
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


def _piece_ports(scaffold: Scaffold, values: np.ndarray, model: PortModel) -> tuple[np.ndarray, np.ndarray]:
    """Start and end port of every piece (``(n_pieces,) int64``)."""
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
    """Return the scaffold's :class:`DiagramTemplate` for ``label_values`` and ``seed`` (built once per live scaffold)."""
    values = tuple(sorted(set(np.asarray(label_values, np.int64).reshape(-1).tolist())))  # np.unique imports numpy.ma
    per = _TEMPLATES.setdefault(scaffold, {})
    key = (values, seed)
    if key not in per:
        per[key] = build_template(scaffold, values, seed)
    return per[key]
