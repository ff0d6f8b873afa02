"""Which designs are buildable as antiparallel B-DNA, and the 5' -> 3' direction of every strand.

A design is **buildable** when every edge has degree 2 (the two strands along it form one
double helix), every label is positive (B-DNA is right-handed and a positive label is a
right-handed twist, ``SIGN``; a zero label would be two strands that do not wind) and the
strands can be oriented so that the two passes along every edge run in opposite directions
(**antiparallel**).  On a coherently oriented closed surface the last condition is: the
edges with odd labels form a cut (the vertices can be 2-coloured so that exactly the odd
edges join the two colours); ``docs/dna.md`` derives it, :func:`orient` decides it for any
mesh from the traced strands.

A **pass** is one strand running along one edge.  Per strand, in traversal order, the passes
are ``(edge, slot at end a, from_a)``: the slot (radial order) the pass occupies at end
``a`` and whether it runs from end ``a`` to end ``b``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import LabelError, ScaffoldError
from ..model.scaffold import Scaffold
from ..strands.ports import port_model
from ..strands.tracing import Trace

SIGN = 1
"""A label ``t`` is ``SIGN * t`` right-handed half turns of B-DNA: positive labels are right-handed (docs/model.md)."""

BP_PER_TURN = 10.5
"""Base pairs per helical turn of B-DNA (default; ``bp_per_turn`` changes it)."""


@dataclass(frozen=True)
class Passes:
    """The oriented passes of a buildable design.

    Attributes
    ----------
    starts : (n_strands + 1,) int64
        Strand ``k`` owns passes ``starts[k]:starts[k + 1]``, in its 5' -> 3' order.
    edge, slot : (n_passes,) int64
        Edge of each pass and its slot at end ``a`` (0 or 1).
    from_a : (n_passes,) bool
        The pass runs 5' -> 3' from end ``a`` to end ``b``.
    corner : (n_passes,) int64
        Face corner the strand turns at just before the pass (its vertex is where the pass starts).
    """

    starts: np.ndarray
    edge: np.ndarray
    slot: np.ndarray
    from_a: np.ndarray
    corner: np.ndarray


def base_pairs(labels: np.ndarray, bp_per_turn: float = BP_PER_TURN) -> np.ndarray:
    """(n_edges,) int64: base pairs of each edge, ``round(bp_per_turn * t / 2)`` (at least 1)."""
    t = SIGN * np.asarray(labels, np.int64)
    # at most 2**62: a twist near 2**63 had wrapped around in the cast to one base pair (a wrong design, silently)
    return np.clip(np.round(bp_per_turn * t / 2.0), 1, 2.0**62).astype(np.int64)


def check_buildable(scaffold: Scaffold, labels: np.ndarray) -> None:
    """Refuse (one line naming an edge) a scaffold or labels that cannot be built as B-DNA duplexes."""
    if scaffold.periodic:
        raise ScaffoldError(f"{scaffold.name}: DNA export needs a finite scaffold, not a periodic one")
    degrees = scaffold.edge_degrees
    bad = np.flatnonzero(degrees != 2)
    if len(bad):
        e = int(bad[0])
        raise ScaffoldError(
            f"{scaffold.name}: edge {e} ({scaffold.edge_name(e)}) has {int(degrees[e])} faces; "
            "a DNA duplex needs every edge on exactly 2 faces"
        )
    bad = np.flatnonzero(SIGN * np.asarray(labels, np.int64) < 1)
    if len(bad):
        e = int(bad[0])
        raise LabelError(
            f"{scaffold.name}: edge {e} ({scaffold.edge_name(e)}) has twist {int(labels[e])}; B-DNA is right-handed, "
            "so every edge needs a positive twist (t half turns = about 5.25 t base pairs)"
        )


def raw_passes(trace: Trace) -> list[list[tuple[int, int, bool, int]]]:
    """Per strand, its passes ``(edge, slot, from_a, corner)`` in traversal order (before orienting)."""
    s = trace.scaffold
    model = port_model(s)
    slot_of_side = np.empty(s.n_corners, np.int64)
    slot_of_side[s.radial.edge_sides] = model.slot_index
    forward = s.side_forward
    out = []
    for k in range(len(trace.strand_starts) - 1):
        passes = []
        for x in trace.steps[trace.strand_starts[k] : trace.strand_starts[k + 1]]:
            y = int(model.corner_partner[x])
            z = int(trace.edge_partner[y])
            side_y = y // 2
            y_at_a = (y % 2 == 0) == bool(forward[side_y])
            slot = slot_of_side[side_y] if y_at_a else slot_of_side[z // 2]
            corner = int(x // 2) if x % 2 == 0 else int(s.corner_next[x // 2])
            passes.append((int(s.side_edge[side_y]), int(slot), y_at_a, corner))
        out.append(passes)
    return out


def orient(trace: Trace) -> Passes:
    """Orient every strand so that each edge's two passes run in opposite directions, or refuse.

    The two passes of an edge fix whether their strands keep or flip their traversal
    direction relative to each other; a breadth-first search over strands 2-colours that
    relation (strand 0 keeps its direction).  A conflict (an odd cycle) is refused, naming
    the edge where it shows.
    """
    s = trace.scaffold
    raw = raw_passes(trace)
    on_edge: list[list[tuple[int, bool]]] = [[] for _ in range(s.n_edges)]
    for k, passes in enumerate(raw):
        for e, _slot, from_a, _corner in passes:
            on_edge[e].append((k, from_a))
    flip = np.full(len(raw), -1, np.int64)
    for root in range(len(raw)):
        if flip[root] >= 0:
            continue
        flip[root] = 0
        queue = [root]
        while queue:
            k = queue.pop()
            for e, _slot, _f, _c in raw[k]:
                (k1, d1), (k2, d2) = on_edge[e]
                # antiparallel: (d1 xor flip1) != (d2 xor flip2)  <=>  flip1 xor flip2 = (d1 == d2)
                need = int(d1 == d2)
                for here, there in ((k1, k2), (k2, k1)):
                    if here == k and flip[there] < 0:
                        flip[there] = flip[k] ^ need
                        queue.append(there)
                if flip[k1] >= 0 and flip[k2] >= 0 and (flip[k1] ^ flip[k2]) != need:
                    raise LabelError(
                        f"{s.name}: the strands cannot run antiparallel along edge {e} ({s.edge_name(e)}): "
                        "the edges with odd twist must form a cut of the mesh (docs/dna.md)"
                    )
    return _oriented(raw, flip)


def _oriented(raw: list[list[tuple[int, int, bool, int]]], flip: np.ndarray) -> Passes:
    """Build :class:`Passes` with every flipped strand reversed."""
    edge, slot, from_a, corner, starts = [], [], [], [], [0]
    for k, passes in enumerate(raw):
        if flip[k]:
            # reversed: pass i is walked backwards, and it then starts where it ended, at the corner after it
            nxt = [c for _e, _s, _f, c in passes[1:]] + [passes[0][3]]
            seq = [(e, sl, not f, c) for (e, sl, f, _c), c in zip(passes, nxt, strict=True)][::-1]
        else:
            seq = passes
        for e, sl, f, c in seq:
            edge.append(e)
            slot.append(sl)
            from_a.append(f)
            corner.append(c)
        starts.append(len(edge))
    arr = np.asarray
    return Passes(
        arr(starts, np.int64), arr(edge, np.int64), arr(slot, np.int64), arr(from_a, bool), arr(corner, np.int64)
    )
