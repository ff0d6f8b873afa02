"""Writing the parts of a catalog, in this process or in a pool of worker processes.

Workers are started with the ``forkserver`` method where there is one (Linux, macOS)
and ``spawn`` elsewhere (Windows), never by forking a running program: each worker
imports lkspace afresh, receives the run's job once (:class:`PartsJob`) (:func:`init_worker`) and writes
whole parts (:func:`write_part`) in a :func:`~lkspace.runtime.pools.worker_pool`.  Workers
ignore SIGINT and leave the decisions to the main process, which on Ctrl-C or SIGTERM kills
them at once (queued parts never start) and removes their temporary files; a worker that
dies ends the run with one line (never a wait for its part); a worker whose main process
has died exits within :data:`~lkspace.runtime.workers.ORPHAN_POLL` seconds.
"""

from __future__ import annotations

import os
import pickle
import tempfile
from collections.abc import Callable, Generator, Iterator
from dataclasses import dataclass, replace

import pyarrow as pa

from ..design.space import DesignSpace
from ..errors import require
from ..runtime.pools import worker_pool
from ..runtime.schedulers import is_dask, run_tasks
from .batches import space_batches
from .metadata import CatalogMetadata
from .options import Selection
from .plan import Plan
from .records import PartFooter, PartSummary, Shard
from .schema import expected_schema
from .transaction import file_sha256
from .writer import write_batches


@dataclass(frozen=True)
class PartsJob:
    """What every part of a run needs: sent once to each worker (pickled).

    Attributes
    ----------
    space : DesignSpace
    selection : Selection
        Which rows the catalog holds.
    settings : CatalogMetadata
        The ``lkspace`` metadata common to every part (:func:`~lkspace.catalog.settings.catalog_metadata`).
    plan : Plan
        The parts: each one's representative classes, and the plan's fingerprint.
    files : tuple of str, or None
        The parts' file names (``None``: a one-file catalog on a URL).
    run : str or None
        The run id (``None``: a one-file catalog on a URL).
    folder : str or None
        The local build folder the parts go to; ``None`` when they go to ``remote``.
    remote : str or None
        The fsspec URL of a catalog written to an object store.
    """

    space: DesignSpace
    selection: Selection
    settings: CatalogMetadata
    plan: Plan
    files: tuple[str, ...] | None = None
    run: str | None = None
    folder: str | None = None
    remote: str | None = None

    @property
    def schema(self) -> pa.Schema:
        """The catalog's columns."""
        return expected_schema(self.settings)

    def batches(self, i: int) -> Iterator[pa.RecordBatch]:
        """Record batches of part ``i``."""
        ranges = self.plan.ranges
        return selected_batches(self.space, self.selection, ranges[i] if ranges is not None else None)

    def header(self, i: int) -> PartFooter:
        """Return the ``lkspace`` metadata part ``i`` is written with (its footer adds its totals)."""
        return PartFooter(self.settings, Shard(i, self.plan.parts, self.plan.fingerprint, self.run))


def selected_batches(
    space: DesignSpace, selection: Selection, class_ids: list[int] | None = None
) -> Iterator[pa.RecordBatch]:
    """Record batches of the rows ``selection`` picks from ``space`` (of the classes ``class_ids``; ``None``: all)."""
    sel = selection
    return space_batches(space, sel.mode, class_ids, sel.components, sel.max_designs, sel.sample, sel.seed)


_JOB: list[PartsJob] = []
"""In a pool worker: the run's job (set once by :func:`init_worker`)."""


def init_worker(job: bytes) -> None:
    """Worker start: take the run's job (:func:`~lkspace.runtime.pools.worker_pool` ignores SIGINT and watches the main process).

    The argument is plain bytes, so a worker started just before its main process
    stopped still starts cleanly (and then exits).
    """
    _JOB[:] = [pickle.loads(job)]


def write_part(i: int) -> tuple[int, PartSummary]:
    """In a pool worker: write part ``i`` of the job of :func:`init_worker`; return ``(i, summary)``."""
    return write_part_with(_JOB[0], i)


def write_part_with(job: PartsJob, i: int, on_rows: Callable[[int], object] | None = None) -> tuple[int, PartSummary]:
    """Write part ``i`` of ``job``; return ``(i, summary with file and sha256)``.

    A Dask task, :func:`write_part` in a pool worker, or a call in this process (which
    passes ``on_rows(rows written)``).
    """
    if job.remote is not None:
        return write_part_remote(job, i)
    assert job.folder is not None and job.files is not None, "a local part needs its folder and file names"
    path = os.path.join(job.folder, job.files[i])
    summary = write_batches(path, job.schema, job.header(i), job.batches(i), on_rows)
    return i, replace(summary, file=job.files[i], sha256=file_sha256(path))


def write_part_remote(job: PartsJob, i: int) -> tuple[int, PartSummary]:
    """Write part ``i`` to a local temporary file, upload it under its final name (fsspec); return its summary."""
    assert job.remote is not None
    fsspec = require("fsspec", "dask", f"writing to {job.remote}")
    fs, root = fsspec.core.url_to_fs(job.remote)
    dest = root if job.files is None else f"{root}/{job.files[i]}"
    with tempfile.TemporaryDirectory(prefix="lkspace-part-") as tmp:
        local = os.path.join(tmp, "part.parquet")
        summary = write_batches(local, job.schema, job.header(i), job.batches(i))
        digest = file_sha256(local)
        fs.put_file(local, dest)
    name = os.path.basename(dest) if job.files is None else job.files[i]
    return i, replace(summary, file=name, sha256=digest)


def run_parts(
    job: PartsJob, todo: list[int], jobs: int, tick: Callable[[int], object], scheduler: str = "local"
) -> Generator[tuple[int, PartSummary], None, None]:
    """Write the parts ``todo`` of ``job`` with ``jobs`` processes; yield ``(i, summary)`` as each finishes.

    ``tick(rows written so far)`` is called as rows are written (in this process) or at
    least every quarter second (rows of the finished parts, with workers).  An exception
    (KeyboardInterrupt included) terminates the workers before it propagates.  With a
    Dask ``scheduler`` (:mod:`lkspace.runtime.schedulers`) each part is a Dask task.
    """
    if is_dask(scheduler):
        rows_done = 0
        for _, done in run_tasks(write_part_with, job, todo, scheduler, jobs, name="lkspace-part"):
            rows_done += done[1].rows
            yield done
            tick(rows_done)
        return
    if jobs <= 1 or len(todo) <= 1:  # in this process: rows counted as they are written
        rows = [0]

        def on_rows(n: int) -> None:
            rows[0] += n
            tick(rows[0])

        for i in todo:
            yield write_part_with(job, i, on_rows)
        return
    finished = [0]  # rows of the parts finished so far
    with worker_pool(min(jobs, len(todo)), init_worker, (pickle.dumps(job),)) as pool:
        for done in pool.unordered(write_part, todo, lambda: tick(finished[0])):
            finished[0] += done[1].rows
            yield done
            tick(finished[0])
