"""Twist labels -> strands: the combinatorial heart of lkspace.

Model (SPEC §1)
---------------
Every face-side carries one strand segment running along its edge.  A segment has two
**ports**, one at each end of the side; port ``2*s`` sits at side ``s``'s first corner
(corner ``s``) and port ``2*s + 1`` at its second corner (``corner_next[s]``).  Two
perfect matchings join the ports:

* **corner links** — inside face ``f`` the strand turns at every corner: the port of
  side ``prev(c)`` at corner ``c`` is joined to the port of side ``c`` at corner ``c``;
* **edge links** — along edge ``e`` of degree ``K`` with twist ``t`` the strand in slot
  ``i`` at end ``a`` continues in slot ``(i + t) mod K`` at end ``b``: the end-``a`` port of
  the side in slot ``i`` is joined to the end-``b`` port of the side in slot
  ``(i + t) mod K``.  Slots are the radial order of :mod:`lkspace.radial`, so positive
  ``t`` turns counter-clockwise about the axis ``a -> b`` (right-handed), and the rule
  reads the same from end ``b`` (the axis flips and so does the slot order).

The union of the two matchings is a disjoint union of cycles: the **strands**.  A strand
is traversed starting with a corner link; its ``faces`` list the face of each corner link
in traversal order.  A **null** side ``s`` cuts the edge link leaving ``s``'s end-``a``
port, so the strand through it becomes open, with those two ports as its ends.

For a periodic scaffold, passing an edge link from side ``s`` to side ``s'`` moves the
current face copy by ``side_translation[s] - side_translation[s']``; the sum around a
closed strand is its **period** (0: a closed loop; otherwise an infinite thread).

Two strands **wind around each other** at an edge with ``t != 0`` that both run through
(own a port of).  The structure **holds together** when that relation connects all strands
(see :mod:`lkspace.connectivity`, which also handles the infinite lift of periodic ones).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numba
import numpy as np

from .mesh import Scaffold, check_nulls, check_twists


@dataclass(frozen=True, eq=False)
class PortModel:
    """Label-independent arrays of the strand model of one scaffold.

    Attributes
    ----------
    corner_partner : (2 * n_corners,) int64
        The port each port is joined to by its corner link.
    port_a, port_b : (n_corners,) int64
        End-``a`` and end-``b`` port of the side in each slot, grouped by edge in slot
        order (index ``edge_starts[e] + i`` is slot ``i`` of edge ``e``).
    slot_edge : (n_corners,) int64
        Edge of each slot position; ``slot_index`` its slot number.
    """

    edge_starts: np.ndarray
    port_a: np.ndarray
    port_b: np.ndarray
    slot_edge: np.ndarray
    slot_index: np.ndarray
    corner_partner: np.ndarray


def port_model(scaffold: Scaffold) -> PortModel:
    """Build the :class:`PortModel` of ``scaffold`` (vectorized, O(n_corners))."""
    n = scaffold.n_corners
    radial = scaffold.radial
    sides = radial.edge_sides
    forward = scaffold.side_forward[sides]
    port_a = 2 * sides + np.where(forward, 0, 1)
    port_b = 2 * sides + np.where(forward, 1, 0)
    partner = np.empty(2 * n, np.int64)
    nxt = scaffold.corner_next
    partner[2 * np.arange(n) + 1] = 2 * nxt
    partner[2 * nxt] = 2 * np.arange(n) + 1
    degrees = scaffold.edge_degrees
    slot_edge = np.repeat(np.arange(scaffold.n_edges), degrees)
    slot_index = np.arange(n) - radial.edge_starts[slot_edge]
    for arr in (port_a, port_b, partner, slot_edge, slot_index):
        arr.setflags(write=False)
    return PortModel(radial.edge_starts, port_a, port_b, slot_edge, slot_index, partner)


def edge_partner(model: PortModel, degrees: np.ndarray, twists: np.ndarray) -> np.ndarray:
    """Edge-link partner of every port ``(2 * n_corners,) int64`` for ``twists``."""
    k = degrees[model.slot_edge]
    target = model.edge_starts[model.slot_edge] + (model.slot_index + twists[model.slot_edge]) % k
    partner = np.empty(2 * len(model.port_a), np.int64)
    partner[model.port_a] = model.port_b[target]
    partner[model.port_b[target]] = model.port_a
    return partner


@numba.njit(cache=True)
def _walk(corner_partner, edge_partner, translation):  # pragma: no cover - compiled
    n_ports = len(corner_partner)
    dim = translation.shape[1]
    visited = np.zeros(n_ports, np.bool_)
    steps = np.empty(n_ports // 2, np.int64)
    starts = np.empty(n_ports // 2 + 1, np.int64)
    closed = np.empty(n_ports // 2, np.bool_)
    periods = np.zeros((n_ports // 2, dim), np.int64)
    port_strand = np.empty(n_ports, np.int64)
    port_shift = np.zeros((n_ports, dim), np.int64)
    n_steps = 0
    n_strands = 0
    for phase in range(2):
        for x0 in range(n_ports):
            if visited[x0] or (phase == 0 and edge_partner[x0] != -1):
                continue
            starts[n_strands] = n_steps
            x = x0
            while True:
                y = corner_partner[x]
                steps[n_steps] = x
                n_steps += 1
                visited[x] = True
                visited[y] = True
                port_strand[x] = n_strands
                port_strand[y] = n_strands
                for j in range(dim):
                    port_shift[x, j] = periods[n_strands, j]
                    port_shift[y, j] = periods[n_strands, j]
                z = edge_partner[y]
                if z == -1:
                    closed[n_strands] = False
                    break
                for j in range(dim):
                    periods[n_strands, j] += translation[y // 2, j] - translation[z // 2, j]
                if z == x0:
                    closed[n_strands] = True
                    break
                x = z
            n_strands += 1
    starts[n_strands] = n_steps
    return steps, starts[: n_strands + 1], closed[:n_strands], periods[:n_strands], port_strand, port_shift


@dataclass(frozen=True, eq=False)
class Trace:
    """The strands of one labelled scaffold.

    Attributes
    ----------
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
    twists: np.ndarray
    nulls: np.ndarray
    steps: np.ndarray
    step_corners: np.ndarray
    strand_starts: np.ndarray
    closed: np.ndarray
    periods: np.ndarray
    port_strand: np.ndarray
    port_shift: np.ndarray
    edge_partner: np.ndarray

    @property
    def components(self) -> int:
        """Number of strands (closed and open)."""
        return int(len(self.closed))

    @cached_property
    def strand_lengths(self) -> np.ndarray:
        """(n_strands,) int64: corners per strand; they add up to ``n_corners``."""
        return np.diff(self.strand_starts)

    def strand_faces(self, k: int) -> np.ndarray:
        """Face of each corner of strand ``k`` in traversal order."""
        s, e = self.strand_starts[k], self.strand_starts[k + 1]
        return self.scaffold.corner_face[self.step_corners[s:e]]

    @cached_property
    def connectivity(self):
        """How the strands hold together: :class:`~lkspace.connectivity.Connectivity`."""
        from .connectivity import connectivity

        return connectivity(self)

    @property
    def n_pieces(self) -> int:
        """Strand groups that fall apart from each other in the quotient (SPEC §1)."""
        return self.connectivity.n_pieces

    @property
    def holds_together(self) -> bool:
        """Whether the structure holds together (for periodic ones: its infinite lift)."""
        return self.connectivity.holds_together

    def strand_ends(self, k: int) -> list[dict] | None:
        """The two cut ends of open strand ``k`` (face, side, vertex); ``None`` if closed."""
        if self.closed[k]:
            return None
        s, e = self.strand_starts[k], self.strand_starts[k + 1]
        sc = self.scaffold
        first = self.steps[s]
        last = sc_port_model(sc).corner_partner[self.steps[e - 1]]
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

    def to_dict(self) -> dict:
        """The JSON form of SPEC §2 (``components``, ``holds_together``, ``strands``)."""
        sc = self.scaffold
        strands = []
        for k in range(self.components):
            entry = {
                "closed": bool(self.closed[k]),
                "faces": self.strand_faces(k).tolist(),
                "length": int(self.strand_lengths[k]),
                "period": self.periods[k].tolist() if sc.periodic and self.closed[k] else None,
            }
            if sc.periodic and self.closed[k]:
                entry["infinite"] = bool(np.any(self.periods[k] != 0))
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
        }
        if sc.periodic:
            out["lift_index"] = self.connectivity.lift_index
            infinite = self.closed & np.any(self.periods != 0, axis=1)
            out["threads_per_module"] = self.components
            out["closed_loops"] = int(np.sum(self.closed & ~infinite))
            out["infinite_threads"] = int(np.sum(infinite))
        return out


def thread_direction(scaffold: Scaffold, period: np.ndarray) -> list[float] | None:
    """Unit direction in space of a thread with lattice ``period``, sign-normalized
    (first non-zero coordinate positive); ``None`` for a closed loop."""
    vector = scaffold.lattice.translate(period)
    norm = np.linalg.norm(vector)
    if norm == 0:
        return None
    vector = vector / norm
    first = vector[np.flatnonzero(np.abs(vector) > 1e-12)[0]]
    return np.round(np.sign(first) * vector, 12).tolist()


def sc_port_model(scaffold: Scaffold) -> PortModel:
    """The scaffold's :class:`PortModel`, cached on the scaffold object."""
    cached = scaffold.__dict__.get("_port_model")
    if cached is None:
        cached = port_model(scaffold)
        object.__setattr__(scaffold, "_port_model", cached)
    return cached


def walk(scaffold: Scaffold, twists: np.ndarray, null_mask: np.ndarray | None = None):
    """Run the strand walk for validated ``twists`` (residues suffice) and optional nulls.

    Returns the edge-link partners and the kernel's arrays ``(steps, strand_starts,
    closed, periods, port_strand, port_shift)``; :func:`trace` wraps them in a
    :class:`Trace`, the enumerator and the solver's local search use them raw.
    """
    model = sc_port_model(scaffold)
    partner = edge_partner(model, scaffold.edge_degrees, np.asarray(twists, np.int64))
    if null_mask is not None and null_mask.any():
        cut = 2 * np.flatnonzero(null_mask) + np.where(scaffold.side_forward[null_mask], 0, 1)
        partner[partner[cut]] = -1
        partner[cut] = -1
    translation = scaffold.side_translation if scaffold.periodic else np.zeros((scaffold.n_corners, 0), np.int64)
    return partner, _walk(model.corner_partner, partner, np.ascontiguousarray(translation))


def trace(scaffold: Scaffold, twists=None, nulls=None) -> Trace:
    """Trace the strands of ``scaffold`` under ``twists`` (and optional ``nulls``).

    Parameters
    ----------
    twists : int or (n_edges,) int, optional
        Twist label per edge (a scalar labels every edge); default the scaffold's own.
    nulls : (n_corners,) bool or sequence of side indices, optional
        Null edge-sides; default the scaffold's own (none).

    Examples
    --------
    >>> from lkspace import load
    >>> [trace(load("tetrahedron"), t).components for t in (0, 1, 2)]
    [4, 3, 4]
    """
    if twists is None:
        twists = scaffold.twists if scaffold.twists is not None else 0
    twists = check_twists(scaffold, twists)
    if nulls is None:
        nulls = scaffold.nulls
    null_mask = np.zeros(scaffold.n_corners, bool) if nulls is None else check_nulls(scaffold, nulls)
    partner, (steps, starts, closed, periods, port_strand, port_shift) = walk(scaffold, twists, null_mask)
    even = np.where(steps % 2 == 0, steps, sc_port_model(scaffold).corner_partner[steps])
    return Trace(
        scaffold, twists, null_mask, steps, even // 2, starts, closed, periods, port_strand, port_shift, partner
    )
