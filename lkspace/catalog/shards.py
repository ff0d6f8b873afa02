"""Writing whole catalogs: plan, lock, build, parts in parallel, resume, swap into place.

A run checks its output (:func:`~lkspace.catalog.transaction.catalog_target`), plans
its size and parts (:mod:`~lkspace.catalog.plan`, refused past the bounds), takes the
target's lock (:mod:`~lkspace.catalog.lock`), builds the catalog beside the target
(:mod:`~lkspace.catalog.transaction`: one Parquet file, or a folder of parts
``part-00000-RUN.parquet``, ... with a manifest ``_lkspace.json`` that records each
finished part's SHA-256), writes the parts in worker processes
(:mod:`~lkspace.catalog.jobs`) and, when every part is there, puts the build in place of
the target.  ``resume`` keeps the verified parts of an interrupted build and redoes the
rest.  Nothing here sets process-wide state: a program that wants SIGTERM to stop a run
as Ctrl-C does installs that itself (the command line does,
:func:`lkspace.runtime.workers.interrupt_signals`); a Python caller's Ctrl-C (KeyboardInterrupt)
cleans up the same way.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Callable
from dataclasses import asdict, dataclass, replace
from typing import TYPE_CHECKING, TypeAlias

import pyarrow as pa
import pyarrow.parquet as pq

from ..design.space import DesignSpace, WalkMode, make_space
from ..errors import CatalogError
from ..io.atomic import remove_path, replace_path
from ..model.scaffold import Scaffold
from ..model.specs import LabelSetSpec
from ..runtime.progress import task
from ..runtime.schedulers import check_scheduler, resolve_scheduler
from ..runtime.workers import context, ignored_signals
from ..symmetry.group import SymmetryMode
from ..words import plural
from .jobs import PartsJob, run_parts
from .lock import catalog_lock
from .metadata import FORMAT_VERSION, JsonObject
from .options import Execution, Selection
from .plan import check_jobs, make_plan
from .records import Manifest, PartFooter, PartSummary, Signature
from .remote import check_remote, remote_url, write_remote
from .settings import catalog_metadata
from .transaction import (
    CatalogInterrupted,
    Destination,
    catalog_target,
    file_sha256,
    load_manifest,
    new_run,
    part_name,
    prune_build,
    remove_temporaries,
    save_manifest,
    seed_build,
    verified_parts,
)
from .verify import open_catalog, part_footer
from .writer import write_batches

if TYPE_CHECKING:
    from .identified import Identified

Progress: TypeAlias = Callable[[int | None], Callable[[int], object] | None]
"""``progress(total)`` -> ``None`` or ``advance(rows written so far)``; ``total`` is ``None`` when unknown."""


@dataclass(frozen=True, repr=False)
class CatalogWritten:
    """What :func:`write_catalog` wrote: totals of the run and where it went.

    Attributes
    ----------
    designs : int
        Rows written (designs, or residue-class orbits in the other modes).
    assignments, assignments_covered : int
        ``|label set| ** n_edges``, and the assignments the rows stand for.
    by_components : dict of int -> int
        Rows by number of components.
    output : str
        Absolute path of the catalog file or folder.
    shards, shards_resumed : int
        Parts written, and parts kept from an earlier run (``resume=True``).
    group_order, acting_order : int
        Order of the symmetry group, and number of distinct signed edge permutations.
    symmetry : str
    mode : {"designs", "residues", "spanning-trees"}
    label_set : list of int
    identified : Identified, optional
        With ``identify=True``: rows identified, rows named, and rows by name.
    """

    designs: int
    assignments: int
    assignments_covered: int
    by_components: dict[int, int]
    output: str
    shards: int
    shards_resumed: int
    group_order: int
    acting_order: int
    symmetry: SymmetryMode
    label_set: list[int]
    mode: WalkMode
    format_version: int = FORMAT_VERSION
    identified: Identified | None = None

    def __repr__(self) -> str:
        return f"CatalogWritten({self.designs:,} rows to {self.output} in {plural(self.shards, 'part')})"

    def to_dict(self) -> JsonObject:
        """JSON form: the ``lkspace enumerate --json`` fields (``by_components`` keyed by strings)."""
        out: JsonObject = asdict(self)
        out["by_components"] = {str(k): v for k, v in self.by_components.items()}
        if self.identified is None:
            del out["identified"]
        return out


def write_catalog(
    space: DesignSpace | Scaffold,
    path: str | os.PathLike[str],
    label_set: LabelSetSpec = "-2..2",
    symmetry: SymmetryMode = "rotations",
    *,
    no_zero: bool = False,
    selection: Selection | None = None,
    execution: Execution | None = None,
    progress: Progress | None = None,
) -> CatalogWritten:
    """Walk a design space and write its catalog; return its totals (:class:`CatalogWritten`).

    Parameters
    ----------
    space : DesignSpace or Scaffold
        A scaffold's space is given by ``label_set``, ``symmetry`` and ``no_zero``
        (``lkspace.write_catalog`` also takes a path or a built-in name, :func:`lkspace.load`).
    path : str or os.PathLike
        The catalog: a ``.parquet`` file or folder, or an fsspec URL
        (``s3://bucket/cat.parquet``, ``memory://cat``: see :mod:`lkspace.catalog.remote`).
    selection : Selection, optional
        Which rows, and whether knot/link columns are added (``identify``; a local catalog
        only) (:class:`~lkspace.catalog.options.Selection`; default every design).
    execution : Execution, optional
        How the run executes (:class:`~lkspace.catalog.options.Execution`: ``jobs``,
        ``shards``, ``scheduler``, ``resume``, ``allow_large``; default one process, local).
    progress : callable, optional
        ``progress(total)`` may return a callable taking the rows written so far.

    The catalog is a transaction: it is built beside ``path`` and put there only when
    complete (an old catalog at ``path`` stays readable until then), and a lock file stops
    a second run writing the same ``path``.  Up to :data:`~lkspace.catalog.plan.PART_ROWS`
    rows it is one Parquet file; larger design walks (or ``shards`` > 1) make a folder of
    parts with a manifest ``_lkspace.json`` that pandas and pyarrow open as one table.
    ``jobs`` worker processes write the parts; ``resume`` keeps the parts of an
    interrupted run whose checksums still match and redoes the rest.  A run estimated past
    :data:`~lkspace.catalog.plan.ROW_LIMIT` rows or :data:`~lkspace.catalog.plan.BYTE_LIMIT`
    bytes is refused before any work unless ``allow_large``.

    Raises
    ------
    CatalogLockedError
        Another run is writing ``path``.
    CatalogTooLarge
        The run is past a documented bound (:mod:`lkspace.catalog.plan`).
    CatalogInterrupted
        Ctrl-C (or SIGTERM, where the program makes it raise): workers stopped,
        temporaries removed, finished parts kept.
    """
    selection = selection or Selection()
    if not isinstance(space, DesignSpace):
        space = make_space(space, label_set, symmetry, no_zero)
    execution = _started(execution or Execution())
    remote = remote_url(path)
    if remote is not None:
        if selection.identify:
            raise CatalogError(
                "identify rewrites the files of a local catalog; write to a local path",
                usage=True,
                parameter="identify",
            )
        check_remote(remote)
        job = _planned(space, selection, execution, remote)
        summaries, kept = write_remote(job, remote, execution)
        return _totals(job, summaries, kept, remote)
    target = catalog_target(path)
    with catalog_lock(target.lock, target.shown):  # before planning: a second run stops at once
        run = _Run(_planned(space, selection, execution, target.shown), target, execution)
        summaries, kept = run.write(progress)
    return replace(_totals(run.job, summaries, kept, os.path.abspath(path)), identified=run.identified)


def _started(execution: Execution) -> Execution:
    """Check ``execution`` before any work; return it with its scheduler resolved (:mod:`lkspace.runtime.schedulers`)."""
    check_jobs(execution.jobs)
    scheduler = resolve_scheduler(execution.scheduler)
    check_scheduler(scheduler)
    if execution.jobs > 1 and scheduler == "local":
        context()  # starts the fork server now: it is ready when the pool is made (a wait Ctrl-C cannot cut)
    return replace(execution, scheduler=scheduler)


def _planned(space: DesignSpace, selection: Selection, execution: Execution, shown: str) -> PartsJob:
    """Plan the run (refused past a bound) and return the job its parts are written from."""
    try:  # planning loads compiled kernels: an interrupt now stops the run cleanly too
        plan = make_plan(space, selection, execution)
    except KeyboardInterrupt as exc:
        code = 128 + getattr(exc, "signum", 2)
        raise CatalogInterrupted(f"interrupted; nothing was written to {shown}", code) from None
    return PartsJob(space, selection, catalog_metadata(space, selection), plan)


class _Run:
    """One local catalog run: its job, the build beside the target, and the parts finished so far."""

    def __init__(self, job: PartsJob, target: Destination, execution: Execution) -> None:
        self.job, self.target, self.execution = job, target, execution
        self.identify = job.selection.identify
        self.by_key = job.selection.by_key
        self.signature = Signature(job.settings, job.plan.parts, job.plan.fingerprint, self.identify, self.by_key)
        self.parts: dict[int, PartSummary] = {}
        self.identified: Identified | None = None

    def write(self, progress: Progress | None) -> tuple[list[PartSummary], int]:
        """Under the target's lock, build the catalog and put it in place; return the parts and how many were kept."""
        target, plan = self.target, self.job.plan
        with catalog_lock(target.lock, target.shown), task("writing catalog", plan.rows) as step:
            advance = progress(plan.rows) if progress is not None else None

            def tick(rows: int) -> None:
                step.update(completed=rows)
                if plan.parts > 1:
                    step.note(f"{len(self.parts)}/{plan.parts} parts")
                if advance is not None:
                    advance(rows)

            remove_temporaries(target, keep_build=self.execution.resume)
            try:
                return self.single(tick) if plan.parts == 1 else self.sharded(tick)
            except KeyboardInterrupt as exc:
                with ignored_signals():
                    remove_temporaries(target, keep_build=plan.parts > 1)
                raise self.interrupted(128 + getattr(exc, "signum", 2)) from None

    def single(self, tick: Callable[[int], object]) -> tuple[list[PartSummary], int]:
        """Write (or, resuming, keep) a one-file catalog."""
        target, build, header = self.target, self.target.build, self.job.header(0)
        for candidate in (build, target.path) if self.execution.resume else ():
            footer = _matching(candidate, header)
            if footer is not None and footer.totals is not None and footer.totals.counted:
                tick(footer.totals.rows)
                if self.identify and (not footer.identified or footer.by_key != self.by_key):
                    self._identify(candidate)
                if candidate == build:
                    with ignored_signals():
                        replace_path(build, target.path, target.aside)
                return [footer.totals], 1
        remove_path(build)
        rows = [0]

        def on_rows(n: int) -> None:
            rows[0] += n
            tick(rows[0])

        summary = write_batches(build, self.job.schema, header, self.job.batches(0), on_rows)
        if self.identify:
            self._identify(build)
        with ignored_signals():
            replace_path(build, target.path, target.aside)
        return [summary], 0

    def sharded(self, tick: Callable[[int], object]) -> tuple[list[PartSummary], int]:
        """Write a folder of parts in the build, then put it in place."""
        build, n = self.target.build, self.job.plan.parts
        run_id = self._start_build()
        kept = len(self.parts)
        base = sum(p.rows for p in self.parts.values())
        tick(base)
        job = replace(self.job, files=tuple(part_name(i, run_id) for i in range(n)), run=run_id, folder=build)
        todo = [i for i in range(n) if i not in self.parts]
        jobs, scheduler = self.execution.jobs, str(self.execution.scheduler)
        with contextlib.closing(run_parts(job, todo, jobs, lambda rows: tick(base + rows), scheduler)) as finished:
            for i, summary in finished:
                self.parts[i] = summary
                self._save(run_id)
        prune_build(build, self.parts)  # temporaries of a worker lost mid-part
        self._save(run_id, complete=True)  # every part is there
        if self.identify:
            self._identify(build)
            for index, entry in self.parts.items():
                self.parts[index] = replace(entry, sha256=file_sha256(os.path.join(build, str(entry.file))))
            self._save(run_id, complete=True)
        with ignored_signals():
            replace_path(build, self.target.path, self.target.aside)
        return [self.parts[i] for i in range(n)], kept

    def _start_build(self) -> str:
        """Make the build folder (resuming: keep its verified parts, or the target's); return the run id."""
        build = self.target.build
        old = load_manifest(build) if self.execution.resume and os.path.isdir(build) else None
        if old is not None and self.signature.resumes(old.signature):
            run_id = old.run
            self.parts = verified_parts(build, old, part_footer)
        else:
            remove_path(build)
            os.mkdir(build)
            run_id, self.parts = (
                seed_build(self.target, build, self.signature, part_footer)
                if self.execution.resume
                else (new_run(), {})
            )
        prune_build(build, self.parts)
        self._save(run_id)
        return run_id

    def _save(self, run_id: str, complete: bool = False) -> None:
        """Write the build's manifest: this run's settings and the parts finished so far."""
        save_manifest(self.target.build, Manifest(self.signature, run_id, dict(self.parts), complete))

    def _identify(self, path: str) -> None:
        from .identified import identify_catalog

        scaffold, processes, scheduler = self.job.space.scaffold, self.execution.jobs, str(self.execution.scheduler)
        self.identified = identify_catalog(path, scaffold, processes, scheduler=scheduler, by_key=self.by_key)

    def interrupted(self, exit_code: int) -> CatalogInterrupted:
        """Return the interrupt that says what the run left (and whether it can be resumed)."""
        if self.job.plan.parts == 1:
            left = f"interrupted; nothing was written to {self.target.shown} (an old catalog there is unchanged)"
            return CatalogInterrupted(left, exit_code)
        left = f"interrupted; {len(self.parts)} of {self.job.plan.parts} parts are finished in {self.target.build}"
        return CatalogInterrupted(left, exit_code, resumable=True)


def _matching(part: str, header: PartFooter) -> PartFooter | None:
    """Return the footer of the catalog file ``part`` if it was written with ``header`` and reads to the end."""
    if not os.path.isfile(part):
        return None
    try:
        footer = open_catalog(part).footer
        if not footer.has_settings(header.settings, header.shard):
            return None
        pq.ParquetFile(part).read()
    except (CatalogError, OSError, pa.ArrowException):
        return None
    return footer


def _totals(job: PartsJob, summaries: list[PartSummary], skipped: int, path: str) -> CatalogWritten:
    """Return the totals of the run of ``job`` from its parts' ``summaries`` (``skipped`` of them kept)."""
    space = job.space
    by: dict[int, int] = {}
    counts = [s.counts() for s in summaries]
    covered = [c for _, c in counts] or [0]
    for by_components, _ in counts:
        for k, v in by_components.items():
            by[int(k)] = by.get(int(k), 0) + v
    return CatalogWritten(
        designs=sum(s.rows for s in summaries),
        assignments=space.assignments,
        assignments_covered=-1 if min(covered) < 0 else sum(covered),
        by_components=dict(sorted(by.items())),
        output=path,
        shards=job.plan.parts,
        shards_resumed=skipped,
        group_order=space.group_order,
        acting_order=space.n_actions,
        symmetry=space.mode,
        label_set=space.label_set.tolist(),
        mode=job.settings.mode,
    )
