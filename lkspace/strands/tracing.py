"""Twist labels -> strands: :func:`trace` and its result, :class:`Trace`.

The port model (:mod:`lkspace.strands.ports`) joins the ports of every face-side by
corner links and, for given labels, edge links; their union is a disjoint union of
cycles: the **strands** (walked by :mod:`lkspace.strands.walk`).  A strand
is traversed starting with a corner link; its ``faces`` list the face of each corner link
in traversal order.  A **null** side ``s`` cuts the edge link leaving ``s``'s end-``a``
port, so the strand through it becomes open, with those two ports as its ends.

For a periodic scaffold, passing an edge link from side ``s`` to side ``s'`` moves the
current face copy by ``side_translation[s] - side_translation[s']``; the sum around a
closed strand is its **period** (0: a closed loop; otherwise an infinite thread).  In the
JSON (:meth:`Trace.to_dict`) every strand has a ``kind``: ``"loop"``, ``"thread"`` or
``"open"``; ``closed`` is true for loops only.

Two strands **wind around each other** at an edge with ``t != 0`` that both run through
(own a port of).  The structure **holds together** when that relation connects all strands
(:mod:`lkspace.strands.holding_together`, which also decides the infinite lift of periodic
ones).  ``docs/model.md`` explains all of this for users.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from ..model.scaffold import Scaffold, validate_labels, validate_nulls
from ..runtime.progress import task
from ..words import plural
from .holding_together import HoldingTogether, holding_together
from .ports import port_model
from .walk import walk

if TYPE_CHECKING:
    import networkx as nx


@dataclass(frozen=True, eq=False, repr=False)
class Trace:
    """The strands of one labelled scaffold.

    Attributes
    ----------
    labels : (n_edges,) int64
        The twist label of every edge, in edge order.
    nulls : (n_corners,) bool
        Null edge-sides.
    strand_starts : (n_strands + 1,) int64
        Strand ``k`` owns steps ``strand_starts[k]:strand_starts[k + 1]``.
    steps : (n_corners,) int64
        Port leaving each corner link, in traversal order (``port // 2`` is its side).
    step_corners : (n_corners,) int64
        Face corner of each step.
    closed : (n_strands,) bool
    periods : (n_strands, dim) int64
        Lattice translation picked up once around each strand (``dim = 0`` if finite).
    port_strand : (2 * n_corners,) int64
    port_shift : (2 * n_corners, dim) int64
        Lattice translation of each port's face copy relative to its strand's start.
    edge_partner : (2 * n_corners,) int64
        Edge-link partner of every port, -1 where a null side cuts it.
    """

    scaffold: Scaffold
    labels: np.ndarray
    nulls: np.ndarray
    steps: np.ndarray
    step_corners: np.ndarray
    strand_starts: np.ndarray
    closed: np.ndarray
    periods: np.ndarray
    port_strand: np.ndarray
    port_shift: np.ndarray
    edge_partner: np.ndarray

    def __repr__(self) -> str:
        lengths = self.strand_lengths.tolist()
        shown = ", ".join(map(str, lengths[:8])) + (", ..." if len(lengths) > 8 else "")
        together = "holds together" if self.holds_together else "falls apart"
        return f"Trace({self.scaffold.name}: {plural(self.components, 'component')}, {together}, lengths [{shown}])"

    @property
    def components(self) -> int:
        """Number of strands (closed and open)."""
        return int(len(self.closed))

    @cached_property
    def strand_lengths(self) -> np.ndarray:
        """(n_strands,) int64: corners per strand; they add up to ``n_corners``."""
        return np.diff(self.strand_starts)

    @cached_property
    def strand_kinds(self) -> list[str]:
        """Kind of each strand: ``"loop"`` (a closed curve), ``"thread"`` (infinite, periodic only) or ``"open"``.

        A periodic strand that closes up in the quotient with a non-zero period is an
        infinite thread in space, not a closed curve.
        """
        infinite = np.any(self.periods != 0, axis=1) if self.periods.shape[1] else np.zeros(len(self.closed), bool)
        return ["open" if not c else "thread" if t else "loop" for c, t in zip(self.closed.tolist(), infinite.tolist())]

    def strand_faces(self, k: int) -> np.ndarray:
        """Face of each corner of strand ``k`` in traversal order."""
        s, e = self.strand_starts[k], self.strand_starts[k + 1]
        return self.scaffold.corner_face[self.step_corners[s:e]]

    @cached_property
    def holding(self) -> HoldingTogether:
        """How the strands hold together (pieces, and the lift index of periodic ones)."""
        return holding_together(self)

    @property
    def n_pieces(self) -> int:
        """Strand groups that fall apart from each other in the quotient."""
        return self.holding.n_pieces

    @property
    def holds_together(self) -> bool:
        """Whether the structure holds together (for periodic ones: its infinite lift)."""
        return self.holding.holds_together

    def strand_ends(self, k: int) -> list[dict[str, int]] | None:
        """Return the two cut ends of open strand ``k`` (face, side, edge, vertex); ``None`` if closed."""
        if self.closed[k]:
            return None
        s, e = self.strand_starts[k], self.strand_starts[k + 1]
        sc = self.scaffold
        first = self.steps[s]
        last = port_model(sc).corner_partner[self.steps[e - 1]]
        out = []
        for port in (first, last):
            side = int(port // 2)
            corner = side if port % 2 == 0 else int(sc.corner_next[side])
            out.append(
                {
                    "face": int(sc.corner_face[side]),
                    "side": side,
                    "edge": int(sc.side_edge[side]),
                    "vertex": int(sc.corners[corner]),
                }
            )
        return out

    def winding_graph(self) -> nx.Graph:
        """Return the strands as a networkx graph, joining strands that wind around each other.

        An edge joins two strands that wind around each other at a nonzero-label edge
        (attribute ``edges``: those scaffold edges).

        Nodes are strand numbers with attributes ``length``, ``closed`` and ``period``
        (``None`` for a finite scaffold).  The structure holds together in the quotient
        exactly when this graph is connected.

        Examples
        --------
        >>> import lkspace
        >>> g = lkspace.trace("tetrahedron", 1).winding_graph()
        >>> g.number_of_nodes(), g.number_of_edges(), sorted(g.edges[0, 1]["edges"])
        (3, 3, [0, 5])
        """
        import networkx as nx

        sc = self.scaffold
        graph = nx.Graph()
        for k in range(self.components):
            period = self.periods[k].tolist() if sc.periodic else None
            graph.add_node(k, length=int(self.strand_lengths[k]), closed=bool(self.closed[k]), period=period)
        edge_of_port = np.repeat(sc.side_edge, 2)
        active = self.labels[edge_of_port] != 0
        pairs = np.unique(np.column_stack([edge_of_port[active], self.port_strand[active]]), axis=0)
        starts = np.searchsorted(pairs[:, 0], np.arange(sc.n_edges + 1))
        for e in range(sc.n_edges):
            strands = pairs[starts[e] : starts[e + 1], 1].tolist()
            for i, a in enumerate(strands):
                for b in strands[i + 1 :]:
                    if not graph.has_edge(a, b):
                        graph.add_edge(a, b, edges=[])
                    graph.edges[a, b]["edges"].append(e)
        return graph

    def to_dict(self) -> dict[str, Any]:
        """Return the JSON form (``components``, ``holds_together``, ``strands`` and more; docs/cli.md)."""
        sc = self.scaffold
        strands = []
        kinds = self.strand_kinds
        for k in range(self.components):
            entry = {
                "closed": kinds[k] == "loop",
                "kind": kinds[k],
                "faces": self.strand_faces(k).tolist(),
                "length": int(self.strand_lengths[k]),
                "period": self.periods[k].tolist() if sc.periodic and self.closed[k] else None,
            }
            if sc.periodic and self.closed[k]:
                entry["infinite"] = kinds[k] == "thread"
                entry["direction"] = thread_direction(sc, self.periods[k])
            if not self.closed[k]:
                entry["ends"] = self.strand_ends(k)
            strands.append(entry)
        out = {
            "components": self.components,
            "holds_together": self.holds_together,
            "pieces": self.n_pieces,
            "n_open": int(np.sum(~self.closed)),
            "strands": strands,
            "labels": self.labels.tolist(),
        }
        if sc.periodic:
            out["lift_index"] = self.holding.lift_index
            infinite = self.closed & np.any(self.periods != 0, axis=1)
            out["threads_per_module"] = self.components
            out["closed_loops"] = int(np.sum(self.closed & ~infinite))
            out["infinite_threads"] = int(np.sum(infinite))
        return out


def thread_direction(scaffold: Scaffold, period: np.ndarray) -> list[float] | None:
    """Return the unit direction in space of a thread with lattice ``period``; ``None`` for a closed loop.

    The direction is sign-normalized: its first non-zero coordinate is positive.
    """
    assert scaffold.lattice is not None
    vector = scaffold.lattice.translate(period)
    norm = np.linalg.norm(vector)
    if norm == 0:
        return None
    vector = vector / norm
    first = vector[np.flatnonzero(np.abs(vector) > 1e-12)[0]]
    return np.round(np.sign(first) * vector, 12).tolist()


def trace(scaffold: Scaffold, labels: ArrayLike | None = None, nulls: ArrayLike | None = None) -> Trace:
    """Trace the strands of a scaffold under twist ``labels`` (and optional ``nulls``).

    Parameters
    ----------
    scaffold : Scaffold
        ``lkspace.trace`` also takes a path or a built-in name (:func:`lkspace.load`).
    labels : int or (n_edges,) int, optional
        Twist label per edge (a scalar labels every edge); default the scaffold's own.
    nulls : (n_corners,) bool or sequence of side indices, optional
        Null edge-sides; default the scaffold's own (none).

    Examples
    --------
    >>> import lkspace
    >>> [lkspace.trace("tetrahedron", t).components for t in (0, 1, 2)]
    [4, 3, 4]
    >>> lkspace.trace("cube", 1)
    Trace(cube: 4 components, holds together, lengths [6, 6, 6, 6])
    """
    if labels is None:
        labels = scaffold.labels if scaffold.labels is not None else 0
    labels = validate_labels(scaffold, labels)
    if nulls is None:
        nulls = scaffold.nulls
    null_mask = np.zeros(scaffold.n_corners, bool) if nulls is None else validate_nulls(scaffold, nulls)
    with task(f"tracing {scaffold.name}", total=3) as step:  # shown only for large scaffolds (> 2 s)
        step.note("radial order")
        port_model(scaffold)
        step.advance()
        step.note("strand walk")
        partner, (steps, starts, closed, periods, port_strand, port_shift) = walk(
            scaffold, labels, null_mask, compiled=False
        )
        step.advance()
        even = np.where(steps % 2 == 0, steps, port_model(scaffold).corner_partner[steps])
        result = Trace(
            scaffold, labels, null_mask, steps, even // 2, starts, closed, periods, port_strand, port_shift, partner
        )
        step.note("holding together")
        result.holding
        step.advance()
    return result
