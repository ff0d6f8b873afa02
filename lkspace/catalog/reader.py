"""Reading catalogs: their ``lkspace`` metadata and, efficiently, their rows.

:func:`read_catalog` returns a :class:`Catalog`: the scalar columns as a pandas
DataFrame with Arrow-backed dtypes (no Python objects per row) and the label vectors as
one ``(n_designs, n_edges) int8`` array, decoded from the fixed-width ``key`` column
(``--mode residues`` catalogs, which have none, decode the ``labels`` list column's
values buffer).  Both are far cheaper than ``pandas.read_parquet``, which turns every
list cell into a Python object.  :func:`catalog_batches` streams the same, a record
batch at a time, for readers whose memory must not grow with the rows (``atlas CATALOG``).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, TypeVar

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq
from numpy.typing import ArrayLike

from ..errors import CatalogError
from ..model.scaffold import Scaffold
from ..strands.tracing import Trace, trace
from ..words import noun
from .arrow_values import label_rows
from .metadata import JsonObject
from .records import PartFooter
from .schema import ROW_GROUP
from .settings import catalog_scaffold
from .transaction import load_manifest
from .verify import CatalogParts, damaged, open_catalog

if TYPE_CHECKING:
    import pandas as pd

LABEL_COLUMNS = ("labels", "key")
"""Columns read into :attr:`Catalog.labels` rather than into the frame."""


T = TypeVar("T")

READ_ATTEMPTS = 3
"""Times :func:`read_catalog` reads a folder again when it was replaced by a new run while being read."""


def read_metadata(path: str | os.PathLike[str]) -> JsonObject:
    """Return the ``lkspace`` metadata of a catalog (of its first part, for a folder) as JSON, its structure checked.

    It is read from the file footer, which holds the file's totals as well
    (:class:`~lkspace.catalog.records.PartFooter`); the checks are
    :func:`~lkspace.catalog.verify.open_catalog`'s.
    """
    return open_catalog(path).footer.to_json()


@dataclass(frozen=True, eq=False, repr=False)
class Catalog:
    """The rows of a catalog, column by column.

    Attributes
    ----------
    frame : pandas.DataFrame
        Every column except the label vectors, with Arrow-backed dtypes.
    labels : (n_designs, n_edges) int8
        The canonical twist labels of each row, in edge order (row ``i`` of ``frame``).
    footer : PartFooter
        The ``lkspace`` metadata (scaffold, label set, symmetry, group order, ...; of the first part).
    path : str
    """

    frame: pd.DataFrame
    labels: np.ndarray
    footer: PartFooter
    path: str

    def __len__(self) -> int:
        return len(self.frame)

    def __repr__(self) -> str:
        settings = self.footer.settings
        return (
            f"Catalog({settings.scaffold.name}: {len(self):,} rows, label set {list(settings.label_set)}, "
            f"symmetry {settings.symmetry}; columns {', '.join(self.frame.columns)})"
        )

    @cached_property
    def metadata(self) -> JsonObject:
        """The ``lkspace`` metadata as JSON (:meth:`~lkspace.catalog.records.PartFooter.to_json`)."""
        return self.footer.to_json()

    def __getitem__(self, rows: slice | ArrayLike | pd.Series) -> Catalog:
        """Return the catalog restricted to ``rows``: a boolean mask, an index array or a slice."""
        import pandas as pd

        if isinstance(rows, pd.Series) and pd.api.types.is_bool_dtype(rows.dtype):
            rows = rows.to_numpy(dtype=bool)  # Arrow-backed masks too
        elif not isinstance(rows, slice):
            rows = np.asarray(rows)
        frame = self.frame.iloc[rows].reset_index(drop=True)
        return Catalog(frame, self.labels[rows], self.footer, self.path)

    @cached_property
    def scaffold(self) -> Scaffold:
        """The catalog's scaffold: stored in its metadata, else loaded by name; hash checked."""
        return catalog_scaffold(self.footer, self.path)

    def trace(self, row: int) -> Trace:
        """Trace the design in row ``row``: its :class:`~lkspace.strands.tracing.Trace`."""
        return trace(self.scaffold, self.labels[row])


def _labels_of(table: pa.Table | pa.RecordBatch) -> np.ndarray:
    """``(n_rows, n_edges) int8`` from the ``key`` column, else from the ``labels`` list column."""
    if "key" in table.column_names:
        column = table.column("key")
        width = column.type.byte_width
        out = np.empty((table.num_rows, width), np.int8)
        at = 0
        for chunk in column.chunks if isinstance(column, pa.ChunkedArray) else [column]:
            data = np.frombuffer(chunk.buffers()[1], np.int8, count=len(chunk) * width, offset=chunk.offset * width)
            out[at : at + len(chunk)] = data.reshape(-1, width)
            at += len(chunk)
        return out
    return label_rows(table.column("labels")).astype(np.int8, copy=False)


def read_catalog(path: str | os.PathLike[str], columns: list[str] | None = None) -> Catalog:
    """Read a catalog (a file or a folder of parts) written by ``lkspace enumerate``.

    The catalog is checked first (:mod:`lkspace.catalog.verify`): its structure, every
    part's SHA-256 and, as they are read, the data pages' checksums; a damaged,
    swapped, missing, extra or foreign part is a :class:`~lkspace.errors.CatalogError`.

    Parameters
    ----------
    path : str or os.PathLike
    columns : list of str, optional
        Frame columns to read (default all); the label vectors are always read.

    Examples
    --------
    >>> import lkspace, tempfile, os
    >>> out = os.path.join(tempfile.mkdtemp(), "t.parquet")
    >>> _ = lkspace.write_catalog("tetrahedron", out, label_set="-2,2")
    >>> cat = lkspace.read_catalog(out)
    >>> len(cat), cat.labels.shape, int(cat.frame.orbit_size.sum())
    (12, (12, 6), 64)
    """
    path = os.fspath(path)
    return reread(path, lambda: _read(path, columns))


def reread(path: str, read: Callable[[], T]) -> T:
    """Return ``read()``, called again (up to :data:`READ_ATTEMPTS` times) when a new run replaced the folder ``path`` meanwhile."""
    for attempt in range(READ_ATTEMPTS):
        run = _run_of(path)
        try:
            return read()
        except (FileNotFoundError, CatalogError):  # a new run may have replaced the folder while we read it
            if attempt == READ_ATTEMPTS - 1 or not os.path.exists(path) or _run_of(path) == run:
                raise
    raise AssertionError("unreachable")  # pragma: no cover


def catalog_batches(
    parts: CatalogParts, columns: list[str], batch_rows: int = ROW_GROUP
) -> Iterator[tuple[pa.RecordBatch, np.ndarray]]:
    """Yield a catalog's rows as ``(batch, labels)``, part by part, at most ``batch_rows`` rows at a time.

    ``batch`` holds ``columns`` (frame columns, as for :func:`read_catalog`), ``labels``
    the batch's ``(n_rows, n_edges) int8`` twist labels.  Each part's SHA-256 is checked
    just before its rows are read, and the data pages' checksums as they are; only one
    batch is in memory at a time.  ``parts``: :func:`~lkspace.catalog.verify.open_catalog`'s;
    wrap the whole reading in :func:`reread` to survive a folder replaced meanwhile.
    """
    schema = pq.read_schema(parts.files[0])
    unknown = sorted(set(columns) - set(schema.names) | set(columns) & set(LABEL_COLUMNS))
    if unknown:
        raise CatalogError(
            f"{parts.path}: no {noun(len(unknown), 'frame column')} {unknown}; columns are {schema.names}"
        )
    label_column = "key" if "key" in schema.names else "labels"
    for part, file in enumerate(parts.files):
        parts.verify(part)
        try:
            with pq.ParquetFile(file, page_checksum_verification=True) as parquet:
                for batch in parquet.iter_batches(batch_size=batch_rows, columns=[*columns, label_column]):
                    yield batch.select(columns), _labels_of(batch)
        except FileNotFoundError:
            raise
        except (OSError, pa.ArrowException) as exc:
            raise damaged(file, exc) from None


def _run_of(path: str) -> object:
    """Return the run id in the manifest of the folder ``path`` (``None``: a file, or no readable manifest)."""
    manifest = load_manifest(path) if os.path.isdir(path) else None
    return None if manifest is None else manifest.run


def _read(path: str, columns: list[str] | None) -> Catalog:
    import pandas as pd  # here, not at the top: writing a catalog imports this module and needs no pandas

    parts = open_catalog(path)
    parts.verify_all()
    schema = pq.read_schema(parts.files[0])
    names = [n for n in schema.names if n not in LABEL_COLUMNS and (columns is None or n in columns)]
    unknown = sorted(set(columns or []) - set(schema.names))
    if unknown:
        raise CatalogError(f"{path}: no {noun(len(unknown), 'column')} {unknown}; columns are {schema.names}")
    label_column = "key" if "key" in schema.names else "labels"
    tables = []
    for file in parts.files:
        try:
            tables.append(pq.read_table(file, columns=[*names, label_column], page_checksum_verification=True))
        except FileNotFoundError:
            raise
        except (OSError, pa.ArrowException) as exc:
            raise damaged(file, exc) from None
    try:
        table = pa.concat_tables(tables)
    except pa.ArrowException as exc:
        raise CatalogError(f"{path}: its parts do not share one schema: {exc}") from None
    labels = _labels_of(table)
    frame = table.select(names).to_pandas(types_mapper=pd.ArrowDtype)
    return Catalog(frame, labels, parts.footer, path)
