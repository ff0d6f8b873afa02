"""A catalog browser: filter, sort and page a catalog on the server, one page to the browser.

The scalar columns and the packed labels (``key``) are read once into an Arrow table
(about 45 bytes a row: 450 MB for the 10-million-row cube catalog); every query is
vectorized Arrow compute: a filter expression, a top-k selection
(``select_k_unstable``: ``offset + limit`` rows, not a full sort) and a take.  Only row
numbers and the sort column are carried through a query, never whole rows; the last
filter's row numbers and sorted selection are kept, so paging does not filter again.
"""

from __future__ import annotations

import threading
import time
from typing import Any

import numpy as np

from ..catalog.verify import open_catalog
from ..errors import CatalogError, UsageError
from .answers import CatalogInfo, CatalogPage
from .requests import CatalogRequest, Filter
from .wire import JsonAnswer


class Browser:
    """The catalog at ``path``, read in a background thread; :meth:`query` answers the page."""

    def __init__(self, path: str) -> None:
        self.path = path
        self._parts = open_catalog(path)  # the structure: a bad catalog is refused at once
        self.footer = self._parts.footer  # its lkspace metadata (catalogs.records.PartFooter)
        self._table: Any = None
        self._error: str | None = None
        self._filtered: tuple[str, Any] | None = None
        self._sorted: tuple[tuple[str, object, str], Any] | None = None
        self._lock = threading.Lock()
        self._ready = threading.Event()
        self.load_seconds = 0.0
        threading.Thread(target=self._load, name="catalog-reader", daemon=True).start()

    def _load(self) -> None:
        import pyarrow as pa
        import pyarrow.dataset as ds

        from ..catalog.verify import damaged

        t0 = time.perf_counter()
        try:
            self._parts.verify_all()  # every part's SHA-256, then pages' checksums as they are read
            checked = ds.ParquetFragmentScanOptions(page_checksum_verification=True)
            fmt = ds.ParquetFileFormat(default_fragment_scan_options=checked)
            dataset = ds.dataset(list(self._parts.files), format=fmt)
            schema = dataset.schema
            scalars = [f.name for f in schema if not pa.types.is_nested(f.type) and f.name != "key"]
            extra = ["key"] if "key" in schema.names else ["labels"]
            table = dataset.to_table(columns=scalars + extra).combine_chunks()  # one chunk: a take is O(rows taken)
            self._table = table.append_column("row", pa.array(np.arange(table.num_rows, dtype=np.int64)))
            self.columns = ["row", *scalars]
        except CatalogError as exc:
            self._error = str(exc)
        except (OSError, pa.ArrowException) as exc:
            self._error = str(damaged(self.path, exc))
        self.load_seconds = time.perf_counter() - t0
        self._ready.set()

    def wait(self, timeout: float | None = None) -> bool:
        """Wait until the catalog is read; return whether it is."""
        return self._ready.wait(timeout)

    def info(self) -> CatalogInfo:
        """Scaffold name, row count and columns (``ready`` false while reading)."""
        out: CatalogInfo = {
            "path": self.path,
            "scaffold": self.footer.settings.scaffold.name,
            "label_set": list(self.footer.settings.label_set),
            "symmetry": self.footer.to_json().get("symmetry"),
            "ready": self._ready.is_set(),
            "error": self._error,
        }
        if self._table is not None:
            out["rows"] = self._table.num_rows
            out["columns"] = self.columns
            out["load_seconds"] = round(self.load_seconds, 3)
        return out

    def _expression(self, filters: tuple[Filter, ...]) -> Any:
        import pyarrow.compute as pc

        expr = None
        for column, op, value in filters:
            if column not in self.columns:
                raise UsageError(f"filter column {column[:40]!r}: not a column ({', '.join(self.columns)})")
            kind = self._table.schema.field(column).type
            value = self._value(column, kind, op, value)
            field = pc.field(column)
            if op == "contains":
                term = pc.match_substring(field, value)
            else:
                term = {
                    "==": field == value,
                    "!=": field != value,
                    "<": field < value,
                    "<=": field <= value,
                    ">": field > value,
                    ">=": field >= value,
                }[op]
            expr = term if expr is None else expr & term
        return expr

    @staticmethod
    def _value(column: str, kind: Any, op: str, value: object) -> Any:
        import pyarrow as pa

        if pa.types.is_string(kind) or pa.types.is_large_string(kind):
            if not isinstance(value, str) or len(value) > 200:
                raise UsageError(f"filter on {column}: expected a string")
            return value
        if op == "contains":
            raise UsageError(f"filter on {column}: 'contains' applies to text columns")
        if pa.types.is_boolean(kind):
            if value in (True, False, "true", "false", 1, 0):
                return value in (True, "true", 1)
            raise UsageError(f"filter on {column}: expected true or false")
        if isinstance(value, bool) or not isinstance(value, int | float) or not np.isfinite(value):
            raise UsageError(f"filter on {column}: expected a number")
        if abs(value) > 2**62:
            raise UsageError(f"filter on {column}: {value} is out of range")
        return value

    def query(self, request: CatalogRequest | None = None) -> CatalogPage | JsonAnswer:
        """One page of rows: ``{"ready", "total", "offset", "columns", "rows": [[...]], "labels": [[...]], "seconds"}``."""
        if not self._ready.is_set():
            waiting: JsonAnswer = {"ready": False, **self.info()}
            return waiting
        if self._error is not None:
            raise CatalogError(self._error)
        req = request or CatalogRequest()
        if req.sort is not None and req.sort not in self.columns:
            raise UsageError(f"sort column {req.sort[:40]!r}: not a column")
        t0 = time.perf_counter()
        fkey = repr(req.filters)
        with self._lock:
            if self._filtered is not None and self._filtered[0] == fkey:
                rows_in = self._filtered[1]
            else:
                rows_in = self._matching(req.filters)
                self._filtered = (fkey, rows_in)
        total = self._table.num_rows if rows_in is None else len(rows_in)
        end = min(total, req.offset + req.limit)
        in_order = req.sort is None or req.sort == "row" and not req.descending
        if rows_in is None and in_order:
            page = self._table.slice(req.offset, max(0, end - req.offset))  # no filter, table order: no take at all
        else:
            page = self._table.take(self._chosen(req, fkey, rows_in, total, end))
        rows = [[_plain(v) for v in r.values()] for r in page.select(self.columns).to_pylist()]
        return {
            "ready": True,
            "total": total,
            "offset": req.offset,
            "columns": self.columns,
            "rows": rows,
            "labels": self._labels(page),
            "seconds": round(time.perf_counter() - t0, 4),
        }

    def _chosen(self, req: CatalogRequest, fkey: str, rows_in: Any, total: int, end: int) -> Any:
        """Row numbers (Arrow) of the page ``req.offset:end`` of the ``total`` rows ``rows_in`` (``None``: all)."""
        import pyarrow as pa
        import pyarrow.compute as pc

        offset, sort, descending = req.offset, req.sort, req.descending
        if offset >= total:
            return pa.array([], pa.int64())
        if sort is None or sort == "row" and not descending:
            return pa.array(np.arange(offset, end)) if rows_in is None else rows_in[offset:end]
        if sort == "row":  # row numbers backwards: no sort to do
            if rows_in is None:
                return pa.array(np.arange(total - 1 - offset, total - 1 - end, -1))
            return rows_in[::-1][offset:end]
        order = "descending" if descending else "ascending"
        skey = (fkey, sort, order)
        with self._lock:
            top = self._sorted[1] if self._sorted is not None and self._sorted[0] == skey else None
        if top is None or len(top) < end:
            keys = [(sort, order), ("row", "ascending")]
            k = min(total, max(2 * end, 1000))  # the next pages come from the same selection
            both = self._table.select([sort, "row"])
            both = both if rows_in is None else both.take(rows_in)  # two columns, not the whole rows
            best = both.take(pc.select_k_unstable(both, k=k, sort_keys=keys))
            top = best.take(pc.sort_indices(best, sort_keys=keys)).column("row").combine_chunks()
            with self._lock:
                self._sorted = (skey, top)
        return top[offset:end]

    def _matching(self, filters: tuple[Filter, ...]) -> Any:
        """Row numbers ``(n,) int64`` (Arrow) matching ``filters``; ``None`` for every row."""
        import pyarrow.dataset as ds

        expr = self._expression(filters) if filters else None
        if expr is None:
            return None
        return ds.dataset(self._table).to_table(filter=expr, columns=["row"]).column("row").combine_chunks()

    @staticmethod
    def _labels(page: Any) -> list[list[int]]:
        if "key" in page.column_names:
            keys = page.column("key").to_pylist()
            return [np.frombuffer(k, np.int8).tolist() for k in keys]
        return [list(v) for v in page.column("labels").to_pylist()]


def _plain(value: Any) -> Any:
    if isinstance(value, float) and not np.isfinite(value):
        return None
    return value
