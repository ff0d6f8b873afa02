"""The port model: label-independent arrays every strand walk starts from.

Every face-side carries one strand segment running along its edge.  A segment has two
**ports**, one at each end of the side; port ``2*s`` sits at side ``s``'s first corner
(corner ``s``) and port ``2*s + 1`` at its second corner (``corner_next[s]``).  Two
perfect matchings join the ports:

* **corner links** — inside face ``f`` the strand turns at every corner: the port of
  side ``prev(c)`` at corner ``c`` is joined to the port of side ``c`` at corner ``c``;
* **edge links** — along edge ``e`` of degree ``K`` with label ``t`` the strand in slot
  ``i`` at end ``a`` continues in slot ``(i + t) mod K`` at end ``b``: the end-``a`` port of
  the side in slot ``i`` is joined to the end-``b`` port of the side in slot
  ``(i + t) mod K``.  Slots are the radial order of :mod:`lkspace.model.radial`, so
  positive ``t`` turns counter-clockwise about the axis ``a -> b`` (right-handed), and the
  rule reads the same from end ``b`` (the axis flips and so does the slot order).

The union of the two matchings is a disjoint union of cycles: the strands
(:mod:`lkspace.strands.walk`).  The conventions are explained for users in
``docs/model.md``.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass

import numpy as np

from ..model.scaffold import Scaffold


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


def build_port_model(scaffold: Scaffold) -> PortModel:
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


def edge_partner(model: PortModel, degrees: np.ndarray, labels: np.ndarray) -> np.ndarray:
    """Edge-link partner of every port ``(2 * n_corners,) int64`` for ``labels``.

    Labels are reduced mod K per edge first (``np.mod`` never overflows), so a label near
    the int64 limit gives the partner of its residue instead of wrapping around.
    """
    k = degrees[model.slot_edge]
    residues = np.mod(np.asarray(labels, np.int64), np.maximum(degrees, 1))
    target = model.edge_starts[model.slot_edge] + (model.slot_index + residues[model.slot_edge]) % k
    partner = np.empty(2 * len(model.port_a), np.int64)
    partner[model.port_a] = model.port_b[target]
    partner[model.port_b[target]] = model.port_a
    return partner


_PORT_MODELS: weakref.WeakKeyDictionary[Scaffold, PortModel] = weakref.WeakKeyDictionary()
"""Each live scaffold's port model (a scaffold is compared by identity; its entry goes with it)."""


def port_model(scaffold: Scaffold) -> PortModel:
    """Return the scaffold's :class:`PortModel`, built once per scaffold (the scaffold itself stays as built)."""
    cached = _PORT_MODELS.get(scaffold)
    if cached is None:
        cached = _PORT_MODELS[scaffold] = build_port_model(scaffold)
    return cached
