"""Streaming a catalog file: record batches -> one Parquet file, written atomically."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import replace

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

from ..io.atomic import atomic_path
from .arrow_values import integer_values
from .records import PartFooter, PartSummary
from .schema import METADATA_KEY, ROW_GROUP


class CatalogWriter:
    """Stream record batches into one Parquet file, written atomically.

    Rows are buffered to ``ROW_GROUP`` and written as zstd row groups; the file appears
    under its final name only when :meth:`close` succeeds (bounded memory: one row group).
    The ``lkspace`` metadata is in the Arrow schema (what pyarrow, pandas and Dask show)
    and, with the run's totals added, in the file footer (what :func:`read_metadata` reads).
    Every data page carries a CRC-32 checksum, which readers verify.
    """

    def __init__(self, path: str, schema: pa.Schema, header: PartFooter) -> None:
        self.path = path
        self.header = header
        self.schema = schema.with_metadata({METADATA_KEY: header.encode()})
        self._ctx = atomic_path(path, suffix=".parquet.tmp")
        self._tmp = self._ctx.__enter__()
        self._writer = pq.ParquetWriter(self._tmp, self.schema, compression="zstd", write_page_checksum=True)
        self._pending: list[pa.RecordBatch] = []
        self._n_pending = 0
        self.rows = 0

    def write(self, batch: pa.RecordBatch) -> None:
        """Add the rows of ``batch`` (written out a row group at a time)."""
        if batch.num_rows == 0:
            return
        self._pending.append(batch)
        self._n_pending += batch.num_rows
        self.rows += batch.num_rows
        if self._n_pending >= ROW_GROUP:
            self._flush()

    def _flush(self) -> None:
        if self._pending:
            table = pa.Table.from_batches(self._pending, schema=self.schema)
            self._writer.write_table(table, row_group_size=ROW_GROUP)
        self._pending, self._n_pending = [], 0

    def close(self, totals: PartSummary) -> None:
        """Finish the file; the ``lkspace`` metadata with ``totals`` goes into its footer."""
        self._flush()
        footer = replace(self.header, totals=replace(totals, rows=self.rows))
        self._writer.add_key_value_metadata({METADATA_KEY: footer.encode()})
        self._writer.close()
        self._ctx.__exit__(None, None, None)

    def abort(self, exc: BaseException) -> None:
        """Give up after ``exc``: close the writer and remove the temporary file (``path`` stays untouched)."""
        try:
            self._writer.close()
        finally:
            self._ctx.__exit__(type(exc), exc, exc.__traceback__)


def write_batches(
    path: str,
    schema: pa.Schema,
    header: PartFooter,
    batches: Iterable[pa.RecordBatch],
    on_rows: Callable[[int], object] | None = None,
) -> PartSummary:
    """Write ``batches`` to ``path`` atomically under ``header`` (settings and shard); return its totals.

    The totals are stored in its footer as well.
    """
    writer = CatalogWriter(path, schema, header)
    by: dict[str, int] = {}
    covered = 0
    try:
        for batch in batches:
            writer.write(batch)
            covered = tally(batch, by, covered)
            if on_rows is not None:
                on_rows(batch.num_rows)
    except BaseException as exc:
        writer.abort(exc)
        raise
    totals = PartSummary(by, covered, writer.rows)
    writer.close(totals)
    return totals


def tally(batch: pa.RecordBatch, by: dict[str, int], covered: int) -> int:
    """Count the rows of ``batch`` into ``by`` (rows by components); return ``covered`` plus their orbit sizes.

    The totals a catalog file records; -1 stands for a sum past 64 bits.
    """
    comps = integer_values(batch.column("components"))
    for c, n in zip(*np.unique(comps, return_counts=True), strict=True):
        by[str(int(c))] = by.get(str(int(c)), 0) + int(n)
    sizes = integer_values(batch.column("orbit_size"))
    return -1 if covered < 0 or (sizes < 0).any() else covered + int(sizes.sum())  # -1: past 64 bits
