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


def validate_labels(scaffold: Scaffold, labels: ArrayLike) -> np.ndarray:
    """Validate twist labels -> ``(n_edges,) int64``; a scalar applies to every edge."""
    arr = np.asarray(labels)
    if arr.ndim == 0:
        arr = np.full(scaffold.n_edges, arr)
    if arr.dtype.kind == "f":
        if not np.all(np.isfinite(arr)) or np.any(arr != np.round(arr)):
            raise LabelError("twist labels must be integers")
    elif arr.dtype.kind not in "iub":
        raise LabelError(f"twist labels must be integers, got {arr.dtype}")
    if arr.shape != (scaffold.n_edges,):
        raise LabelError(f"{scaffold.name}: expected {scaffold.n_edges} twist labels (one per edge), got {arr.size}")
    return arr.astype(np.int64)


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
