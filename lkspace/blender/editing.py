"""What the add-on's buttons do to twist labels, in lkspace's edge order (no ``bpy``).

Every function takes and returns ``(n_edges,) int64`` labels of a scaffold; the add-on
maps them to and from the mesh's ``lk_twist`` attribute (:mod:`lkspace.blender.meshdata`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from ..errors import LabelError
from ..model.scaffold import Scaffold
from ..model.specs import parse_label_set
from ..strands.tracing import Trace

if TYPE_CHECKING:
    from ..symmetry.group import SymmetryMode


def fill_orbit(scaffold: Scaffold, labels: ArrayLike, edge: int, mode: SymmetryMode = "rotations") -> np.ndarray:
    """Copy the label of ``edge`` to every edge of its orbit under the scaffold's symmetry.

    ``mode`` is ``"rotations"`` (a rotation keeps a label) or ``"isometries"`` (a mirror
    image gets ``-t``).  A label a mirror maps onto its own negative on the same edge
    (``t != -t``) cannot be filled: :class:`~lkspace.errors.LabelError`.

    Examples
    --------
    >>> import lkspace
    >>> fill_orbit(lkspace.load("cube"), [2] + [0] * 11, 0).tolist()
    [2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2]
    """
    from ..symmetry.group import check_mode, symmetry_group

    out = np.array(labels, np.int64)
    perms, signs = symmetry_group(scaffold).action(check_mode(mode))
    t = int(out[edge])
    images = perms[:, edge]
    values = signs * t
    for image in np.unique(images).tolist():
        seen = np.unique(values[images == image])
        if len(seen) > 1:
            raise LabelError(
                f"{scaffold.name}: a mirror maps edge {scaffold.edge_name(edge)} onto edge "
                f"{scaffold.edge_name(image)} with twist {t} and with {-t}; fill with rotations or use twist 0"
            )
        out[image] = seen[0]
    return out


def random_labels(scaffold: Scaffold, label_set: str, seed: int, no_zero: bool = False) -> np.ndarray:
    """Labels drawn uniformly from ``label_set`` (``"-2..2"``, ``"1,2"``), reproducibly from ``seed``.

    Examples
    --------
    >>> import lkspace
    >>> a = random_labels(lkspace.load("cube"), "-2..2", seed=1, no_zero=True)
    >>> bool(np.all(a != 0)), np.array_equal(a, random_labels(lkspace.load("cube"), "-2..2", 1, True))
    (True, True)
    """
    choices = parse_label_set(label_set)
    if no_zero:
        choices = choices[choices != 0]
    if len(choices) == 0:
        raise LabelError(f"label set {label_set!r} has no label to draw (without 0: none left)")
    return np.random.default_rng(seed).choice(choices, size=scaffold.n_edges).astype(np.int64)


def component_order(result: Trace) -> np.ndarray:
    """Strand numbers in colour order: by the lowest face corner each strand turns around.

    A strand keeps its colour slot while its lowest corner stays the lowest of a strand
    and no strand with a lower one appears or vanishes; the tracer's own order may change
    with any edit.

    Examples
    --------
    >>> import lkspace
    >>> component_order(lkspace.trace("tetrahedron", 0)).tolist()
    [0, 1, 2, 3]
    """
    lowest = np.minimum.reduceat(result.step_corners, result.strand_starts[:-1])
    return np.argsort(lowest, kind="stable")
