"""Buildable designs of a mesh at a given scale: labels near each edge's natural twist, antiparallel.

At ``nm_per_unit`` an edge of length ``L`` holds ``n = (L - gap_a - gap_b) / RISE_NM + 1`` base
pairs (:mod:`~lkspace.dna.helix`), which make ``2 n / bp_per_turn`` half turns: its **natural
twist**.  A label within ``window`` of it (and at least 1) fits the edge with a few base pairs
more or less.  The odd labels must form a cut (``docs/dna.md``), so the search runs over the
2-colourings of the vertices (vertex 0 white) and, for each, over the labels of the right
parity on every edge: at most ``max_designs`` designs are traced.  On a mesh whose faces
are oriented coherently this finds every buildable design in the window; elsewhere each
candidate is checked by :func:`~lkspace.dna.model.orient` and some may be missed.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import LabelError, TooLargeError
from ..model.scaffold import Scaffold
from ..strands.tracing import trace
from .helix import RISE_NM, edge_frames, vertex_gaps
from .model import BP_PER_TURN, check_buildable, orient


@dataclass(frozen=True)
class DnaSolution:
    """One buildable design of a DNA search: its labels, strand count and (for a type search) name."""

    labels: tuple[int, ...]
    components: int
    name: str | None = None

    def to_json(self) -> dict[str, Any]:
        """Return the design as one entry of the search's ``solutions`` (``name`` only when searched by type)."""
        out: dict[str, Any] = {"labels": list(self.labels)}
        if self.name is not None:
            out["name"] = self.name
        return {**out, "components": self.components}


@dataclass(frozen=True)
class DnaSearchResult:
    """The answer of a DNA search: status, designs, and the scale they were searched at."""

    status: str
    """``feasible``/``infeasible`` (by strand count) or ``found``/``exhausted`` (by type)."""
    solutions: tuple[DnaSolution, ...]
    nm_per_unit: float
    window: float
    natural_twist: tuple[float, ...]
    """Per edge, the half turns its length holds at this scale (rounded to 3 decimals)."""

    def to_json(self) -> dict[str, Any]:
        """Return the answer as the command line prints it in JSON."""
        return {
            "status": self.status,
            "solutions": [s.to_json() for s in self.solutions],
            "dna": {"nm_per_unit": self.nm_per_unit, "window": self.window, "natural_twist": list(self.natural_twist)},
        }


def natural_twist(scaffold: Scaffold, nm_per_unit: float, bp_per_turn: float = BP_PER_TURN) -> np.ndarray:
    """(n_edges,) float: the half turns each edge's helix makes at ``nm_per_unit``."""
    d, _e1, _e2, length = edge_frames(scaffold)
    gaps = vertex_gaps(scaffold, d)
    ab = scaffold.edge_vertices
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):  # inf at a scale past floats: refused after
        n = (nm_per_unit * length - gaps[ab[:, 0]] - gaps[ab[:, 1]]) / RISE_NM + 1
        return np.asarray(2 * n / bp_per_turn)


MAX_WINDOW_LABEL = 127
"""Largest label a DNA window holds: a catalog's labels are int8 (about 670 base pairs on one edge)."""


def window_labels(
    scaffold: Scaffold, nm_per_unit: float, window: float = 1.0, bp_per_turn: float = BP_PER_TURN
) -> list[list[int]]:
    """Per edge, the labels within ``window`` half turns of its natural twist at ``nm_per_unit`` (at least 1), ascending.

    A window past :data:`MAX_WINDOW_LABEL` is refused, naming the largest scale that fits
    (``nm_per_unit`` 1e308 had been an internal error: labels past int8).
    """
    natural = natural_twist(scaffold, nm_per_unit, bp_per_turn)
    top = natural + window
    if not np.all(np.isfinite(top)) or top.max(initial=0.0) > MAX_WINDOW_LABEL:
        past = f"past label {MAX_WINDOW_LABEL} (about {MAX_WINDOW_LABEL * bp_per_turn / 2:.0f} base pairs on one edge)"
        if not window < MAX_WINDOW_LABEL - 1:
            raise TooLargeError(
                f"window: {window:g} half turns about each edge's natural twist reaches {past}", parameter="window"
            )
        d, _e1, _e2, length = edge_frames(scaffold)
        gaps, ab = vertex_gaps(scaffold, d), scaffold.edge_vertices
        turns = (MAX_WINDOW_LABEL - window) * bp_per_turn / 2  # base pairs of the largest label
        fits = float(np.min(((turns - 1) * RISE_NM + gaps[ab[:, 0]] + gaps[ab[:, 1]]) / length))
        raise TooLargeError(
            f"{scaffold.name}: at {nm_per_unit:g} nm per mesh unit an edge's window reaches {past}; "
            f"use a scale of at most {max(fits, 0.0):.4g} or a smaller `window`"
        )
    lo = np.maximum(np.ceil(natural - window), 1).astype(np.int64)
    hi = np.floor(natural + window).astype(np.int64)
    return [list(range(a, b + 1)) for a, b in zip(lo.tolist(), hi.tolist(), strict=True)]


def buildable_designs(
    scaffold: Scaffold,
    nm_per_unit: float,
    *,
    components: int | None = None,
    window: float = 1.0,
    bp_per_turn: float = BP_PER_TURN,
    max_designs: int = 1_000_000,
) -> Iterator[np.ndarray]:
    """Yield the label vectors (n_edges,) int64 that are buildable at ``nm_per_unit`` (with ``components`` strands).

    Raises ``TooLargeError`` before any work when more than ``max_designs`` label vectors
    would be traced.
    """
    options = window_labels(scaffold, nm_per_unit, window, bp_per_turn)
    lo = np.array([opts[0] if opts else 1 for opts in options], np.int64)
    by_parity = [([t for t in opts if t % 2 == 0], [t for t in opts if t % 2 == 1]) for opts in options]
    ab = scaffold.edge_vertices
    total = 2 ** (scaffold.n_vertices - 1) * int(np.prod([max(map(len, p)) for p in by_parity], dtype=object))
    if total > max_designs:
        raise TooLargeError(
            f"max_designs: up to {total:,} label vectors at this scale (window {window:g}) > {max_designs:,}; "
            "use a smaller `window` or a smaller mesh"
        )
    check_buildable(scaffold, np.maximum(lo, 1))
    seen = set()  # a mesh in several pieces gives one cut from several colourings
    for colours in itertools.product((0, 1), repeat=scaffold.n_vertices - 1):
        c = np.array((0, *colours))
        odd = c[ab[:, 0]] != c[ab[:, 1]]
        choices = [by_parity[e][int(odd[e])] for e in range(scaffold.n_edges)]
        for labels in itertools.product(*choices):
            key = tuple(labels)
            if key in seen:  # the colouring and its swap give the same cut
                continue
            seen.add(key)
            arr = np.array(labels, np.int64)
            tr = trace(scaffold, arr)
            if components is not None and tr.components != components:
                continue
            try:
                orient(tr)
            except LabelError:  # faces not oriented coherently: the cut is only a candidate
                continue
            yield arr
