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
:func:`lkspace.workers.interrupt_signals`); a Python caller's Ctrl-C (KeyboardInterrupt)
cleans up the same way.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Callable
from dataclasses import asdict, dataclass, replace
from typing import TYPE_CHECKING, Any, TypeAlias

import pyarrow as pa
import pyarrow.parquet as pq

from ..design.space import DesignSpace, WalkMode, make_space
from ..engine import check_scheduler, resolve_scheduler
from ..errors import CatalogError
from ..io.atomic import remove_path, replace_path
from ..io.scaffold_json import scaffold_to_dict
from ..model.scaffold import Scaffold
from ..model.specs import LabelSetSpec
from ..progress import task
from ..symmetry.group import SymmetryMode
from ..symmetry.tolerance import resolve_tolerance
from ..words import plural
from ..workers import context, ignored_signals
from .jobs import PartsJob, run_parts, selected_batches
from .lock import catalog_lock
from .options import Execution, Selection
from .plan import Plan, check_jobs, make_plan
from .reader import read_metadata
from .records import Manifest, PartSummary
from .remote import check_remote, remote_url, write_remote
from .schema import FORMAT_VERSION, design_schema, residue_schema
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
    same_settings,
    save_manifest,
    seed_build,
    verified_parts,
)
from .writer import write_batches

if TYPE_CHECKING:
    from .identified import Identified

CANONICAL_RULE = (
    "orbit member smallest in (t mod K per edge, then t per edge), lexicographic in edge order; see docs/catalog.md"
)
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

    def to_dict(self) -> dict[str, Any]:
        """JSON form: the ``lkspace enumerate --json`` fields (``by_components`` keyed by strings)."""
        out = asdict(self)
        out["by_components"] = {str(k): v for k, v in self.by_components.items()}
        if self.identified is None:
            del out["identified"]
        return out


def catalog_metadata(space: DesignSpace, selection: Selection) -> dict[str, Any]:
    """Return the ``lkspace`` metadata common to every part of a catalog (its signature for resuming)."""
    sc = space.scaffold
    return {
        "format_version": FORMAT_VERSION,
        "scaffold": {
            "name": sc.name,
            "content_hash": sc.content_hash(),
            "edges": sc.n_edges,
            "faces": sc.n_faces,
            "periodic": sc.periodic,
            "data": {k: v for k, v in scaffold_to_dict(sc).items() if k not in ("labels", "nulls")},  # geometry only
        },
        "label_set": space.label_set.tolist(),
        "symmetry": space.mode,
        "symmetry_tolerance": None if space.mode == "none" else resolve_tolerance(sc, space.tolerance),
        "group_order": space.group_order,
        "acting_order": space.n_actions,
        "assignments": space.assignments,
        "mode": selection.mode,
        "filters": {"components": selection.components, "no_zero": space.no_zero, "max_designs": selection.max_designs},
        "sample": selection.sample,
        "seed": selection.seed if selection.sample is not None else None,
        "canonical_rule": CANONICAL_RULE,
    }


def write_catalog(
    space: DesignSpace | Scaffold,
    path: str | os.PathLike[str],
    label_set: LabelSetSpec = "-2..2",
    symmetry: SymmetryMode = "rotations",
    *,
    no_zero: bool = False,
    selection: Selection | None = None,
    execution: Execution | None = None,
    identify: bool = False,
    allow_large: bool = False,
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
        Which rows (:class:`~lkspace.catalog.options.Selection`; default every design).
    execution : Execution, optional
        How the run executes (:class:`~lkspace.catalog.options.Execution`: ``jobs``,
        ``shards``, ``scheduler``, ``resume``; default one process, local).
    identify : bool
        Add knot/link columns before the catalog is put in place.
    allow_large : bool
        Go ahead with a run estimated past :data:`~lkspace.catalog.plan.ROW_LIMIT` rows or
        :data:`~lkspace.catalog.plan.BYTE_LIMIT` bytes (refused otherwise, before any work).
    progress : callable, optional
        ``progress(total)`` may return a callable taking the rows written so far.

    The catalog is a transaction: it is built beside ``path`` and put there only when
    complete (an old catalog at ``path`` stays readable until then), and a lock file stops
    a second run writing the same ``path``.  Up to :data:`~lkspace.catalog.plan.PART_ROWS`
    rows it is one Parquet file; larger design walks (or ``shards`` > 1) make a folder of
    parts with a manifest ``_lkspace.json`` that pandas and pyarrow open as one table.
    ``jobs`` worker processes write the parts; ``resume`` keeps the parts of an
    interrupted run whose checksums still match and redoes the rest.

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
    execution = execution or Execution()
    if not isinstance(space, DesignSpace):
        space = make_space(space, label_set, symmetry, no_zero)
    jobs, resume = execution.jobs, execution.resume
    check_jobs(jobs)
    engine = resolve_scheduler(execution.scheduler)
    check_scheduler(engine)
    if jobs > 1 and engine == "local":
        context()  # starts the fork server now: it is ready when the pool is made (a wait Ctrl-C cannot cut)
    remote = remote_url(path)
    if remote is None:
        target = catalog_target(path)
    elif identify:
        raise CatalogError(
            "identify rewrites the files of a local catalog; write to a local path", usage=True, parameter="identify"
        )
    else:
        check_remote(remote)
    try:  # planning loads compiled kernels: an interrupt now stops the run cleanly too
        plan = make_plan(space, selection, execution.shards, allow_large)
    except KeyboardInterrupt as exc:
        shown = remote or target.shown
        raise CatalogInterrupted(
            f"interrupted; nothing was written to {shown}", 128 + getattr(exc, "signum", 2)
        ) from None
    meta = catalog_metadata(space, selection)
    periodic = space.scaffold.periodic
    schema = (
        design_schema(space.scaffold.n_edges, periodic) if selection.mode == "designs" else residue_schema(periodic)
    )
    if remote is not None:
        summaries, kept = write_remote(space, remote, plan, meta, schema, selection, jobs, engine, resume)
        return _totals(space, meta, summaries, remote, plan.parts, kept)
    run = _Run(space, target, plan, meta, schema, selection, identify, engine)
    with catalog_lock(target.lock, target.shown), task("writing catalog", plan.rows) as step:
        advance = progress(plan.rows) if progress is not None else None

        def tick(rows: int) -> None:
            step.update(completed=rows)
            if plan.parts > 1:
                step.note(f"{len(run.parts)}/{plan.parts} parts")
            if advance is not None:
                advance(rows)

        remove_temporaries(target, keep_build=resume)
        try:
            summaries, kept = run.single(resume, jobs, tick) if plan.parts == 1 else run.sharded(resume, jobs, tick)
        except KeyboardInterrupt as exc:
            with ignored_signals():
                remove_temporaries(target, keep_build=plan.parts > 1)
            raise run.interrupted(128 + getattr(exc, "signum", 2)) from None
    totals = _totals(space, meta, summaries, os.fspath(path), plan.parts, kept)
    return replace(totals, identified=run.identified) if identify else totals


class _Run:
    """One catalog run: what :func:`write_catalog` planned, and the parts finished so far."""

    def __init__(
        self,
        space: DesignSpace,
        target: Destination,
        plan: Plan,
        meta: dict[str, Any],
        schema: pa.Schema,
        selection: Selection,
        identify: bool,
        scheduler: str = "local",
    ) -> None:
        self.space, self.target, self.plan, self.meta, self.schema = space, target, plan, meta, schema
        self.selection, self.identify, self.scheduler = selection, identify, scheduler
        self.signature = {**meta, "shards": plan.parts, "plan": plan.fingerprint, "identify": identify}
        self.parts: dict[str, PartSummary] = {}
        self.identified: Identified | None = None
        self.jobs = 1

    def single(self, resume: bool, jobs: int, tick: Callable[[int], object]) -> tuple[list[PartSummary], int]:
        """Write (or, resuming, keep) a one-file catalog."""
        self.jobs = jobs
        target, build = self.target, self.target.build
        part_meta = {**self.meta, "shard": {"index": 0, "count": 1, "plan": self.plan.fingerprint}}
        for candidate in (build, target.path) if resume else ():
            found = _matching(candidate, part_meta)
            if found is not None:
                footer, summary = found
                tick(summary.rows)
                if self.identify and not footer.get("identified"):
                    self._identify(candidate)
                if candidate == build:
                    with ignored_signals():
                        replace_path(build, target.path, target.aside)
                return [summary], 1
        remove_path(build)
        rows = [0]

        def on_rows(n: int) -> None:
            rows[0] += n
            tick(rows[0])

        summary = write_batches(build, self.schema, part_meta, selected_batches(self.space, self.selection), on_rows)
        if self.identify:
            self._identify(build)
        with ignored_signals():
            replace_path(build, target.path, target.aside)
        return [summary], 0

    def sharded(self, resume: bool, jobs: int, tick: Callable[[int], object]) -> tuple[list[PartSummary], int]:
        """Write a folder of parts in the build, then put it in place."""
        build, n = self.target.build, self.plan.parts
        self.jobs = jobs
        old = Manifest.from_json(load_manifest(build)) if resume and os.path.isdir(build) else None
        if old is not None and same_settings(old.signature, self.signature):
            run_id = old.run
            self.parts = verified_parts(build, old)
        else:
            remove_path(build)
            os.mkdir(build)
            run_id, self.parts = seed_build(self.target, build, self.signature) if resume else (new_run(), {})
        prune_build(build, self.parts)
        self._save(run_id)
        kept = len(self.parts)
        base = sum(p.rows for p in self.parts.values())
        tick(base)
        files = tuple(part_name(i, run_id) for i in range(n))
        plan = self.plan
        job = PartsJob(
            self.space, self.selection, self.schema, self.meta, plan.fingerprint, plan.ranges, n, files, run_id, build
        )
        todo = [i for i in range(n) if str(i) not in self.parts]
        parts = run_parts(job, todo, jobs, lambda rows: tick(base + rows), self.scheduler)
        with contextlib.closing(parts) as finished:
            for i, summary in finished:
                self.parts[str(i)] = summary
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
        return [self.parts[str(i)] for i in range(n)], kept

    def _save(self, run_id: str, complete: bool = False) -> None:
        """Write the build's manifest: this run's settings and the parts finished so far."""
        manifest = Manifest(self.signature, run_id, dict(self.parts), complete)
        save_manifest(self.target.build, manifest.to_json())

    def _identify(self, path: str) -> None:
        from .identified import identify_catalog

        self.identified = identify_catalog(path, self.space.scaffold, processes=self.jobs, scheduler=self.scheduler)

    def interrupted(self, exit_code: int) -> CatalogInterrupted:
        """Return the interrupt that says what the run left (and whether it can be resumed)."""
        if self.plan.parts == 1:
            left = f"interrupted; nothing was written to {self.target.shown} (an old catalog there is unchanged)"
            return CatalogInterrupted(left, exit_code)
        left = f"interrupted; {len(self.parts)} of {self.plan.parts} parts are finished in {self.target.build}"
        return CatalogInterrupted(left, exit_code, resumable=True)


def _matching(part: str, meta: dict[str, Any]) -> tuple[dict[str, Any], PartSummary] | None:
    """Return the footer metadata and totals of the catalog file ``part`` if it has the metadata ``meta`` and reads to the end."""
    if not os.path.isfile(part):
        return None
    try:
        footer = read_metadata(part)
        summary = PartSummary.from_json(footer)
        if summary is None or not same_settings(footer, meta):
            return None
        pq.ParquetFile(part).read()
    except (CatalogError, OSError, pa.ArrowException):
        return None
    return footer, summary


def _totals(
    space: DesignSpace, meta: dict[str, Any], summaries: list[PartSummary], path: str, shards: int, skipped: int
) -> CatalogWritten:
    by: dict[int, int] = {}
    covered = [s.assignments_covered for s in summaries] or [0]
    for s in summaries:
        for k, v in s.by_components.items():
            by[int(k)] = by.get(int(k), 0) + v
    return CatalogWritten(
        designs=sum(s.rows for s in summaries),
        assignments=space.assignments,
        assignments_covered=-1 if min(covered) < 0 else sum(covered),
        by_components=dict(sorted(by.items())),
        output=path if remote_url(path) else os.path.abspath(path),
        shards=shards,
        shards_resumed=skipped,
        group_order=space.group_order,
        acting_order=space.n_actions,
        symmetry=space.mode,
        label_set=space.label_set.tolist(),
        mode=meta["mode"],
    )
