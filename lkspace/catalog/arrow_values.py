"""Numpy views of Arrow integer columns, read from their buffers (``to_numpy`` would import pandas, 0.2 s)."""

from __future__ import annotations

import numpy as np
import pyarrow as pa

from ..errors import CatalogError


def integer_values(array: pa.Array, count: int | None = None, start: int = 0) -> np.ndarray:
    """Return ``count`` values (default all) of the null-free signed integer ``array`` from ``start``, as a view."""
    if array.null_count:
        raise ValueError(f"column of {array.type} has nulls")  # the callers' columns have none
    width = array.type.bit_width // 8
    n = len(array) - start if count is None else count
    return np.frombuffer(array.buffers()[1], np.dtype(f"int{8 * width}"), n, (array.offset + start) * width)


def label_rows(column: pa.ChunkedArray | pa.Array, n_edges: int | None = None) -> np.ndarray:
    """``(rows, n_edges)``: a catalog's ``labels`` column (lists of signed ints, no nulls) as a matrix of its own dtype.

    Every list must hold ``n_edges`` labels (default: as many as the first); a list of
    another length is refused, not read across rows.
    """
    lists = column.combine_chunks() if isinstance(column, pa.ChunkedArray) else column
    values = lists.values if pa.types.is_list(lists.type) or pa.types.is_large_list(lists.type) else None
    if values is None or not pa.types.is_signed_integer(values.type) or lists.null_count or values.null_count:
        raise CatalogError(f"labels: expected lists of signed integers without nulls, got {column.type}")
    offsets = integer_values(lists.offsets, len(lists) + 1)
    width = int(offsets[1] - offsets[0]) if n_edges is None and len(lists) else n_edges or 0
    if len(lists) and np.any(np.diff(offsets) != width):
        raise CatalogError(f"labels: expected lists of {width} labels (one per edge)")
    start = int(offsets[0]) if len(lists) else 0
    return integer_values(values, width * len(lists), start).reshape(len(lists), width)
