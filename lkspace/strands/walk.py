"""The strand walk: follow corner links and edge links until every port is visited.

A strand is traversed starting with a corner link.  A **null** side ``s`` cuts the edge
link leaving ``s``'s end-``a`` port, so the strand through it becomes open, with those two
ports as its ends (open strands are walked first, from their cut ends).  For a periodic
scaffold, passing an edge link from side ``s`` to side ``s'`` moves the current face copy
by ``side_translation[s] - side_translation[s']``; the sum around a closed strand is its
**period**.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ..compiled.kernels import helper, kernel
from ..model.scaffold import Scaffold
from .ports import edge_partner, port_model

WalkArrays = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]
"""``(steps, strand_starts, closed, periods, port_strand, port_shift)``: see :class:`~lkspace.strands.tracing.Trace`."""


@helper
def walk_strand(
    corner_partner: np.ndarray,
    edge_partner: np.ndarray,
    translation: np.ndarray,
    x0: int,
    strand: int,
    visited: np.ndarray,
    steps: np.ndarray,
    n_steps: int,
    port_strand: np.ndarray,
    port_shift: np.ndarray,
    period: np.ndarray,
) -> tuple[int, bool]:
    """Walk one strand from port ``x0``: its corner link, then its edge link, until back at ``x0`` or at a cut.

    The strand walk of the trace (:func:`walk_strands`) and of
    :func:`~lkspace.design.batch_kernels.trace_classes`; the census
    (:func:`~lkspace.design.census_kernel.census_range`) and the PD assembly
    (:func:`~lkspace.knots.assembly.assemble_into`) keep theirs written out, measured faster
    so (see there).  Each port ``x`` a corner link leaves
    goes to ``steps[n_steps]``, ``steps[n_steps + 1]``, ...; both ports of the link are marked
    ``visited``, given ``port_strand = strand`` and ``port_shift (n_ports, dim)`` the
    translation reached so far, which ``period (dim,)`` (zero on entry) sums over the edge
    links passed.  Returns ``(n_steps after the strand, closed)``: ``closed`` is False when
    an edge link was cut (``edge_partner`` -1).
    """
    dim = len(period)
    x = x0
    while True:
        y = corner_partner[x]
        steps[n_steps] = x
        n_steps += 1
        visited[x] = True
        visited[y] = True
        port_strand[x] = strand
        port_strand[y] = strand
        for j in range(dim):
            port_shift[x, j] = period[j]
            port_shift[y, j] = period[j]
        z = edge_partner[y]
        if z == -1:
            return n_steps, False
        for j in range(dim):
            period[j] += translation[y // 2, j] - translation[z // 2, j]
        if z == x0:
            return n_steps, True
        x = z


@kernel
def walk_strands(corner_partner: np.ndarray, edge_partner: np.ndarray, translation: np.ndarray) -> WalkArrays:
    """Walk every strand and return its :data:`WalkArrays` (open strands first, from their cut ends).

    ``corner_partner`` and ``edge_partner`` are ``(2 * n_corners,) int64`` (-1: a cut edge
    link), ``translation`` ``(n_corners, dim) int64`` the side translations.
    """
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
            n_steps, is_closed = walk_strand(
                corner_partner,
                edge_partner,
                translation,
                x0,
                n_strands,
                visited,
                steps,
                n_steps,
                port_strand,
                port_shift,
                periods[n_strands],
            )
            closed[n_strands] = is_closed
            n_strands += 1
    starts[n_strands] = n_steps
    return steps, starts[: n_strands + 1], closed[:n_strands], periods[:n_strands], port_strand, port_shift


def walk(
    scaffold: Scaffold, labels: ArrayLike, null_mask: np.ndarray | None = None, *, compiled: bool = True
) -> tuple[np.ndarray, WalkArrays]:
    """Run the strand walk for validated ``labels`` (residues suffice) and optional nulls.

    Returns the edge-link partners ``(2 * n_corners,) int64`` and the kernel's arrays
    ``(steps, strand_starts, closed, periods, port_strand, port_shift)``.  With
    ``compiled=False`` a small scaffold is walked in plain Python (no numba start-up).
    """
    model = port_model(scaffold)
    partner = edge_partner(model, scaffold.edge_degrees, np.asarray(labels, np.int64))
    if null_mask is not None and null_mask.any():
        cut = 2 * np.flatnonzero(null_mask) + np.where(scaffold.side_forward[null_mask], 0, 1)
        partner[partner[cut]] = -1
        partner[cut] = -1
    translation = scaffold.side_translation if scaffold.periodic else np.zeros((scaffold.n_corners, 0), np.int64)
    args = (model.corner_partner, partner, np.ascontiguousarray(translation))
    work = len(partner) if not compiled else 1 << 62
    return partner, walk_strands.run(work, *args)
