"""Validating twist labels and null edge-sides against a scaffold (arrays, not text).

Text as users type it (``--twist``, ``--null``, label sets) is parsed by
:mod:`lkspace.model.specs`, which ends here too.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from ..errors import LabelError

if TYPE_CHECKING:
    from .scaffold import Scaffold

MAX_LABEL = 2**63 - 1
"""Largest twist label magnitude accepted anywhere (``|t| <= 2**63 - 1``, the int64 range).

Only ``t mod K`` decides the strands: labels are reduced mod K per edge before any kernel
adds a slot number to them, so a label near the limit traces as its residue.  Larger
values (and ``-2**63``, whose magnitude does not fit) are an error naming the value and
where it came from, never a silent wrap-around.
"""

MAX_LABEL_SET_SIZE = 100_000
"""Most labels a label set (``--labels``) may hold; a range like ``-2..2`` counts its members."""


MAX_COORDINATE = 1e12
"""Largest vertex coordinate magnitude accepted (and lattice vector entry): past it angles and lengths lose all precision."""


def check_label(value: int, where: str) -> int:
    """Return the integer ``value`` if ``|value| <= MAX_LABEL``; raise :class:`LabelError` naming ``where``."""
    if not -MAX_LABEL <= value <= MAX_LABEL:
        shown = str(value) if abs(value) < 10**30 else f"an integer of {len(str(abs(value)))} digits"
        raise LabelError(f"{where}: {shown} is out of range; twist labels must lie within -(2**63 - 1)..2**63 - 1")
    return value


def validate_labels(scaffold: Scaffold, labels: ArrayLike) -> np.ndarray:
    """Validate twist labels -> ``(n_edges,) int64``; a scalar applies to every edge."""
    try:
        arr = np.asarray(labels)
    except (OverflowError, ValueError) as exc:
        raise LabelError(f"{scaffold.name}: twist labels must be integers ({exc})") from None
    if arr.ndim == 0:
        arr = np.full(scaffold.n_edges, arr)
    if arr.dtype.kind == "O" and all(isinstance(v, int) and not isinstance(v, bool) for v in arr.reshape(-1)):
        for i, v in enumerate(arr.reshape(-1).tolist()):  # Python ints past int64
            check_label(v, f"{scaffold.name}: label {i}")
    if arr.dtype.kind == "f":
        if not np.all(np.isfinite(arr)) or np.any(arr != np.round(arr)):
            raise LabelError("twist labels must be integers")
        if arr.size and np.abs(arr).max() >= 2.0**63:  # float(MAX_LABEL) rounds up to 2**63
            raise LabelError(
                f"{scaffold.name}: a twist label is out of range; labels must lie within -(2**63 - 1)..2**63 - 1"
            )
    elif arr.dtype.kind not in "iub":
        raise LabelError(f"twist labels must be integers, got {arr.dtype}")
    if arr.shape != (scaffold.n_edges,):
        raise LabelError(f"{scaffold.name}: expected {scaffold.n_edges} twist labels (one per edge), got {arr.size}")
    out = arr.astype(np.int64)
    bad = np.flatnonzero((out > MAX_LABEL) | (out < -MAX_LABEL) | (arr.dtype.kind == "u") & (out < 0))
    if len(bad):
        check_label(int(arr[bad[0]]), f"{scaffold.name}: edge {scaffold.edge_name(bad[0])} (label {bad[0]})")
    return out


def validate_nulls(scaffold: Scaffold, nulls: ArrayLike) -> np.ndarray:
    """Validate null edge-sides -> ``(n_corners,) bool`` mask.

    ``nulls`` is a boolean mask over sides or a sequence of side indices.
    """
    arr = np.asarray(nulls)
    if arr.dtype == bool:
        if arr.shape != (scaffold.n_corners,):
            raise LabelError(f"null mask must have one entry per face-side ({scaffold.n_corners}), got {arr.size}")
        return arr.copy()
    arr = arr.reshape(-1)
    if arr.size and (arr.dtype.kind not in "iu" or arr.min() < 0 or arr.max() >= scaffold.n_corners):
        raise LabelError(f"null edge-sides must be side indices in 0..{scaffold.n_corners - 1}")
    mask = np.zeros(scaffold.n_corners, bool)
    mask[arr.astype(np.int64)] = True
    return mask
