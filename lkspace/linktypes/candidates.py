"""Designs with a given number of components, simplest first.

The design walk (:mod:`lkspace.design.walk`) lists one design per orbit of the rotation
group (a rotation moves a structure rigidly: its knot type and chirality stay), with
the component count known per residue class before any label is expanded.  Here it is
run **shell by shell**: shell ``k`` holds the designs whose largest ``|t|`` is ``k``
(labels of ``SET`` with ``|t| <= k``), for ``k`` the values of ``|t|`` in ``SET`` in
increasing order; within a shell the designs are sorted by ``sum |t|``, then by the
number of non-zero labels, then in the walk's canonical order.  So the search meets
the designs in the order "largest label, total twist, non-zero labels".

``--fix`` pins edges: the symmetry is then dropped (mode ``none``) and rows are kept
when the pinned edges carry their labels.
"""

from __future__ import annotations

import time
from collections.abc import Iterator, Mapping
from dataclasses import dataclass

import numpy as np

from ..design.space import DesignSpace
from ..design.walk import walk_blocks
from ..errors import LabelError
from ..model.scaffold import Scaffold
from ..symmetry.group import SymmetryMode

MAX_SHELL_ROWS = 1 << 20
"""Most designs of one shell sorted together; a bigger shell is sorted in pieces of this size."""


@dataclass(frozen=True, eq=False)
class Candidates:
    """Designs of one shell, in search order: ``labels (m, n_edges) int8``, ``orbit_sizes (m,) int64``."""

    shell: int
    labels: np.ndarray
    orbit_sizes: np.ndarray


def shells(label_set: np.ndarray, no_zero: bool) -> list[int]:
    """Return the values ``k`` of ``|t|`` in the label set, increasing (0 left out under ``no_zero``)."""
    values = np.unique(np.abs(np.asarray(label_set, np.int64)))
    return [int(k) for k in values if not (no_zero and k == 0)]


def simplicity_order(labels: np.ndarray) -> np.ndarray:
    """Return indices sorting rows by ``sum |t|``, then the number of non-zero labels (stable)."""
    a = np.abs(labels.astype(np.int64))
    return np.lexsort(((a != 0).sum(axis=1), a.sum(axis=1)))


class OrderedWalk:
    """The designs with ``components`` strands (``None``: all), shell by shell, simplest first.

    Iterating yields :class:`Candidates`; it stops early once ``time.monotonic()`` passes
    ``deadline``.  ``complete`` tells afterwards whether the whole space was walked.

    Examples
    --------
    >>> from lkspace import load
    >>> walk = OrderedWalk(load("dihedron:3"), np.arange(-1, 2), 1)
    >>> [(c.shell, c.labels.tolist()) for c in walk], walk.complete
    ([(1, [[0, 0, -1], [0, 0, 1], [-1, -1, -1], [-1, -1, 1], [-1, 1, 1], [1, 1, 1]])], True)
    """

    def __init__(
        self,
        scaffold: Scaffold,
        label_set: np.ndarray,
        components: int | None,
        *,
        no_zero: bool = False,
        fixes: Mapping[int, int] | None = None,
        deadline: float | None = None,
        tolerance: float | None = None,
    ) -> None:
        self.fixes = dict(fixes or {})
        self.tolerance = tolerance
        self.label_set = np.unique(np.asarray(label_set, np.int64))
        if no_zero and 0 in self.fixes.values():
            raise LabelError("fixes EDGE=0 contradicts `no_zero`", usage=True, parameter="fixes")
        self.scaffold, self.components, self.no_zero, self.deadline = scaffold, components, no_zero, deadline
        self.complete = False

    def __iter__(self) -> Iterator[Candidates]:
        scaffold, label_set = self.scaffold, self.label_set
        mode: SymmetryMode = "none" if self.fixes else "rotations"
        free = np.ones(scaffold.n_edges, bool)
        free[list(self.fixes)] = False
        pinned = np.array(sorted(self.fixes.items()), np.int64).reshape(-1, 2)
        ks = shells(label_set, self.no_zero)
        self.complete = False
        for k in ks:
            sub = np.union1d(label_set[np.abs(label_set) <= k], pinned[:, 1])
            space = DesignSpace(scaffold, sub, mode, self.no_zero, self.tolerance)
            pending: list[np.ndarray] = []
            sizes: list[np.ndarray] = []
            n_rows = 0
            for block in walk_blocks(space, components=self.components):
                rows = block.labels  # int8: a shell of millions of designs stays small
                keep = np.ones(len(rows), bool)
                if len(pinned):
                    keep &= np.all(rows[:, pinned[:, 0]] == pinned[:, 1], axis=1)
                    keep &= np.all(np.isin(rows[:, free], label_set), axis=1)
                if free.any():
                    keep &= np.abs(rows[:, free].astype(np.int64)).max(axis=1) == k
                elif k != ks[0]:
                    keep[:] = False  # every edge pinned: one design, met in the first shell
                pending.append(rows[keep])
                sizes.append(block.orbit_sizes[keep].astype(np.int64))
                n_rows += int(keep.sum())
                if n_rows >= MAX_SHELL_ROWS:
                    yield _sorted(k, pending, sizes)
                    pending, sizes, n_rows = [], [], 0
                if self.deadline is not None and time.monotonic() > self.deadline:
                    if n_rows:
                        yield _sorted(k, pending, sizes)
                    return
            if n_rows:
                yield _sorted(k, pending, sizes)
        self.complete = True


def _sorted(shell: int, pending: list[np.ndarray], sizes: list[np.ndarray]) -> Candidates:
    labels = np.concatenate(pending)
    orbit = np.concatenate(sizes)
    order = simplicity_order(labels)
    return Candidates(shell, labels[order], orbit[order])
