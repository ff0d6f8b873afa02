"""Knot and link names for catalog rows: ``lkspace enumerate ... --identify``.

Identification runs as a second pass over a written catalog: each Parquet file (or each
part of a sharded folder) is read, its designs are identified by invariant key
(:func:`lkspace.knots.batch.identify_batch`: diagrams from labels, one full naming
per distinct key, in ``processes`` worker processes), and the file is rewritten
atomically with these extra columns:

``knot_name`` (string, null when unknown, split or open), ``crossings`` (int32, the
simplified diagram's), ``mirror`` (bool, null when the table does not tell),
``split`` (bool), ``jones`` (string), ``linking_matrix`` (JSON text) and
``identify_error`` (string, null unless the design could not be identified) and
``identify_status`` (string: ``identified``, or ``unknown: <why>`` — for example two
table entries that the checks could not tell apart).
The ``lkspace`` metadata gains ``"identified": true``.
"""

from __future__ import annotations

import multiprocessing
import os
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

from ..errors import CatalogError, UsageError
from ..io.atomic import atomic_path
from ..io.json_values import JsonObject
from ..model.scaffold import Scaffold
from ..runtime.progress import Step, task
from .arrow_values import label_rows
from .columns import numpy_column, value_column
from .schema import IDENTIFY_COLUMNS, METADATA_KEY
from .verify import file_metadata, open_catalog

if TYPE_CHECKING:
    from ..knots.batch import ChunkNames
    from ..knots.key_names import KeyCache


@dataclass(frozen=True)
class Identified:
    """What an identification pass found.

    Attributes
    ----------
    rows : int
        Rows identified (rows already identified are not counted again).
    named : int
        Rows with a knot or link name.
    names : dict of str -> int
        Rows by name (:func:`identify_catalog`: most frequent first).
    """

    rows: int = 0
    named: int = 0
    names: dict[str, int] = field(default_factory=dict)

    def to_json(self) -> JsonObject:
        """Return ``{rows, named, names}`` (the ``identified`` field of ``enumerate --json``)."""
        names: JsonObject = dict(self.names)
        return {"rows": self.rows, "named": self.named, "names": names}

    def __add__(self, other: Identified) -> Identified:
        """Both passes' totals (names in the order first seen)."""
        names = dict(self.names)
        for name, n in other.names.items():
            names[name] = names.get(name, 0) + n
        return Identified(self.rows + other.rows, self.named + other.named, names)


def identify_catalog(
    path: str | os.PathLike[str],
    scaffold: Scaffold,
    processes: int = 1,
    seed: int = 0,
    scheduler: str = "local",
    by_key: bool = False,
) -> Identified:
    """Add knot/link columns to every row of the catalog at ``path``; returns a summary.

    ``by_key``: name by key only (:attr:`~lkspace.knots.batch.NamerOptions.by_key`), marked in each file's footer.

    Progress (rows identified) is reported through :func:`lkspace.runtime.progress.task`.  With a
    Dask ``scheduler`` (:mod:`lkspace.runtime.schedulers`) each file (part) is one Dask task on one
    worker, and so it is over ``processes`` local processes when naming by key only; otherwise
    files go one after the other, each over ``processes`` processes.
    """
    from ..runtime.schedulers import is_dask, run_tasks

    path = os.fspath(path)
    totals = Identified()
    files = list(open_catalog(path).files)
    total = sum(pq.read_metadata(f).num_rows for f in files)
    with task("identifying designs", total) as step:
        if is_dask(scheduler) or (by_key and processes > 1 and len(files) > 1):
            found = run_tasks(
                identify_part, (scaffold, seed, by_key), files, scheduler, processes, "lkspace-identify", load_knots
            )
            for i, summary in found:
                totals += summary
                step.advance(pq.read_metadata(files[i]).num_rows)
        else:
            from ..knots.key_names import disk_cache

            cache = disk_cache()  # read once for every file of the catalog
            for file in files:
                totals += _summary(_identify_file(file, scaffold, processes, seed, step, cache=cache, by_key=by_key))
    return replace(totals, names=dict(sorted(totals.names.items(), key=lambda kv: -kv[1])))


def load_knots() -> None:
    """On a Dask worker, before its tasks: import the knot libraries in the main thread (PARI sets signal handlers)."""
    import snappy  # noqa: F401


def identify_part(shared: tuple[Scaffold, int, bool], file: str) -> Identified:
    """Task: identify the rows of one catalog file; return its summary.

    Names in full run in one child process, in its main thread (a Dask task runs in a
    worker thread, where SnapPy's PARI cannot decide between table entries); naming by
    key only (``shared[2]``) names nothing in full and runs where it is called.
    """
    scaffold, seed, by_key = shared
    if multiprocessing.current_process().daemon and not by_key:
        raise UsageError(
            "identifying on Dask needs workers that may start processes: start them with"
            " 'python -m lkspace.dask_worker' (or set distributed.worker.daemon: false)"
        )
    from ..knots.key_names import disk_cache

    with task("identifying designs", None) as step:
        found = _identify_file(file, scaffold, 1, seed, step, isolate=not by_key, cache=disk_cache(), by_key=by_key)
        return _summary(found)


def _summary(found: list[ChunkNames] | None) -> Identified:
    if found is None:
        return Identified()
    names: dict[str, int] = {}
    for chunk in found:
        counts = np.bincount(chunk.which, minlength=len(chunk.fields)).tolist()
        for f, n in zip(chunk.fields, counts, strict=True):
            if f.knot_name is not None and n:
                names[f.knot_name] = names.get(f.knot_name, 0) + n
    return Identified(sum(len(c) for c in found), sum(names.values()), names)


SOURCES = {"identify_error": "error", "identify_status": "status"}
"""Catalog columns named otherwise in :class:`~lkspace.knots.identification.NameFields`."""


def identify_column(chunks: list[ChunkNames], name: str, type_: pa.DataType) -> pa.Array:
    """One identify column (:data:`~lkspace.catalog.schema.IDENTIFY_COLUMNS`) of every design of ``chunks``, in order."""
    key = SOURCES.get(name, name)
    pieces = []
    for chunk in chunks:
        if key in ("components", "linking_matrix"):
            pieces.append(value_column(chunk.column(key), type_))
        else:  # one value per distinct fields, taken per design
            pieces.append(value_column(chunk.values(key), type_).take(numpy_column(chunk.which)))
    return pa.concat_arrays(pieces) if pieces else value_column([], type_)


def _identify_file(
    file: str,
    scaffold: Scaffold,
    processes: int,
    seed: int,
    step: Step,
    *,
    cache: KeyCache,
    isolate: bool = False,
    by_key: bool = False,
) -> list[ChunkNames] | None:
    """Identify the rows of one catalog file and rewrite it with the columns; ``None`` if it has them, named alike.

    ``cache``: the names by invariant key of this run (:func:`lkspace.knots.key_names.disk_cache`).
    """
    from ..knots.batch import NamerOptions, iter_names

    options = NamerOptions(processes, isolate=isolate, by_key=by_key)

    table = pq.ParquetFile(file).read()  # not read_table: its dataset module imports pandas
    if "labels" not in table.column_names:
        raise CatalogError(f"{file}: no 'labels' column to identify")
    footer = file_metadata(file)[0]
    if footer.identified and footer.by_key == by_key:
        step.advance(table.num_rows)
        return None
    labels = label_rows(table.column("labels"), scaffold.n_edges).astype(np.int64)
    values = np.unique(labels)
    found: list[ChunkNames] = []
    for names in iter_names(scaffold, labels, options, seed, cache=cache, label_values=values):
        found.append(names)
        step.advance(len(names))
    for name, type_ in IDENTIFY_COLUMNS.items():
        column = identify_column(found, name, type_)
        if name in table.column_names:
            table = table.drop_columns([name])
        table = table.append_column(pa.field(name, type_), column)
    footer = replace(footer, identified=True, by_key=by_key)  # its digest written anew
    table = table.replace_schema_metadata({**(table.schema.metadata or {}), METADATA_KEY: footer.encode()})
    with atomic_path(file, suffix=".parquet.tmp") as tmp:
        pq.write_table(table, tmp, compression="zstd", write_page_checksum=True)
    return found
