"""Arrow columns of catalog rows built from per-class facts (lists expanded per row, vectorized)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pyarrow as pa

from ..design.batch import ClassTraces
from .schema import residue_schema

INT64_MAX = 2**63 - 1
"""Largest ``residue_class`` code stored; a larger one (a class of a big scaffold) is stored as null."""


def numpy_column(values: np.ndarray) -> pa.Array:
    """Return the ``(n,)`` numeric or bool array ``values`` as an Arrow array of its dtype (no nulls).

    Built from the array's buffer: ``pa.array`` would first import pandas (to check for
    pandas types), a quarter of a second that writing a catalog does not need.
    """
    values = np.ascontiguousarray(values)
    if values.dtype == np.bool_:
        bits = pa.py_buffer(np.packbits(values, bitorder="little"))
        return pa.Array.from_buffers(pa.bool_(), len(values), [None, bits])
    return pa.Array.from_buffers(pa.from_numpy_dtype(values.dtype), len(values), [None, pa.py_buffer(values)])


def value_column(values: Sequence[Any], type_: pa.DataType) -> pa.Array:
    """Return Python ``values`` (``None``: null) as an Arrow array of ``type_``: string, bool or a signed integer.

    Built from buffers, as :func:`numpy_column` (no pandas).
    """
    n = len(values)
    valid = np.fromiter((v is not None for v in values), bool, n)
    validity = None if valid.all() else pa.py_buffer(np.packbits(valid, bitorder="little"))
    if type_ == pa.string():
        data = [b"" if v is None else str(v).encode() for v in values]
        offsets = np.zeros(n + 1, np.int32)
        np.cumsum(np.fromiter(map(len, data), np.int64, n), out=offsets[1:])
        return pa.Array.from_buffers(type_, n, [validity, pa.py_buffer(offsets), pa.py_buffer(b"".join(data))])
    if type_ == pa.bool_():
        bits = np.packbits(np.fromiter((bool(v) for v in values), bool, n), bitorder="little")
        return pa.Array.from_buffers(type_, n, [validity, pa.py_buffer(bits)])
    if not pa.types.is_signed_integer(type_):
        raise TypeError(f"value_column: no buffer layout for {type_}")  # a bug in lkspace
    ints = np.fromiter((0 if v is None else int(v) for v in values), np.dtype(f"int{type_.bit_width}"), n)
    return pa.Array.from_buffers(type_, n, [validity, pa.py_buffer(ints)])


def list_column(values: np.ndarray, counts: np.ndarray, type_: pa.ListType) -> pa.Array:
    """Return a list column of Arrow type ``type_``: row ``i`` holds the next ``counts[i]`` of ``values``.

    ``values`` has the dtype of ``type_``'s elements.
    """
    offsets = np.zeros(len(counts) + 1, np.int32)
    np.cumsum(counts, out=offsets[1:])
    return pa.ListArray.from_arrays(numpy_column(offsets), numpy_column(values), type=type_)


def per_row_lists(values: np.ndarray, counts: np.ndarray, row_class: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Expand per-class lists (``values`` CSR with ``counts`` per class) to one list per row of ``row_class``.

    Returns ``(flat values, counts per row)``.
    """
    starts = np.zeros(len(counts) + 1, np.int64)
    np.cumsum(counts, out=starts[1:])
    cuts = np.flatnonzero(np.diff(row_class)) + 1
    if len(cuts) < 64:  # few runs of rows (chunks of large classes): tile each class's list
        bounds = [0, *cuts.tolist(), len(row_class)]
        pieces = [
            np.tile(values[starts[row_class[a]] : starts[row_class[a] + 1]], b - a)
            for a, b in zip(bounds[:-1], bounds[1:], strict=True)
            if b > a
        ]
        flat = np.concatenate(pieces) if pieces else values[:0]
        return flat, counts[row_class]
    starts = np.zeros(len(counts) + 1, np.int64)
    np.cumsum(counts, out=starts[1:])
    row_counts = counts[row_class]
    total = int(row_counts.sum())
    row_offsets = np.zeros(len(row_counts), np.int64)
    if len(row_counts):
        np.cumsum(row_counts[:-1], out=row_offsets[1:])
    idx = np.repeat(starts[row_class] - row_offsets, row_counts) + np.arange(total)
    return values[idx], row_counts


def strand_columns(traces: ClassTraces, row_class: np.ndarray, periodic: bool) -> dict[str, pa.Array]:
    """``strand_lengths`` (and, periodic, ``n_infinite``, ``strand_periods``) of each row from its class."""
    n_s = traces.components
    mask = np.arange(traces.lengths.shape[1])[None, :] < n_s[:, None]
    flat, counts = per_row_lists(traces.lengths[mask].astype(np.int32), n_s, row_class)
    cols = {"strand_lengths": list_column(flat, counts, pa.list_(pa.int32()))}
    if periodic:
        dim = traces.periods.shape[2]
        periods = traces.periods[mask]  # (total strands, dim)
        infinite = np.zeros(len(n_s), np.int16)
        np.add.at(infinite, np.repeat(np.arange(len(n_s)), n_s), np.any(periods != 0, axis=1))
        cols["n_infinite"] = numpy_column(infinite[row_class])
        flat_p, counts_p = per_row_lists(periods.reshape(-1), n_s * dim, row_class)
        inner = pa.ListArray.from_arrays(
            numpy_column(np.arange(len(flat_p) // max(dim, 1) + 1, dtype=np.int32) * dim),
            numpy_column(flat_p.astype(np.int64)),
        )
        offsets = np.zeros(len(counts) + 1, np.int32)
        np.cumsum(counts, out=offsets[1:])
        cols["strand_periods"] = pa.ListArray.from_arrays(numpy_column(offsets), inner)
    return cols


def residue_rows_to_batch(rows: Sequence[Mapping[str, Any]], periodic: bool) -> pa.RecordBatch:
    """Record batch of the residues schema from row dicts (few rows: one per class orbit)."""
    schema = residue_schema(periodic)
    data = {f.name: [r[f.name] for r in rows] for f in schema}
    data["residue_class"] = [c if c <= INT64_MAX else None for c in data["residue_class"]]
    return pa.RecordBatch.from_pydict(data, schema=schema)
