"""Identify, relax, measure, solve and exports in worker processes: never blocking an edit, cancelled by terminating.

Each job runs :func:`run_job` in a fresh process of lkspace's worker context
(:func:`lkspace.runtime.workers.context`; the fork server preloads the heavy modules, so a job
starts in milliseconds after the first).  Progress of the library's long steps
(:mod:`lkspace.runtime.progress`) and the result come back through a pipe the server drains
when the page polls.  The server keeps only the pipe's reading end, so a worker that dies
(or is stopped) mid-message is read as the end of the pipe, never waited for.

Jobs are bounded: one job of each kind at a time per page, and a new one stops the page's
one running (an identification, relaxation or clearance measurement of an older design is
stale; a new solve is the page asking again with other settings, and the page follows only
its latest solve).  A page is named by the id it sends (``X-Lkspace-Page``), so two tabs on
one studio never cancel each other's jobs.  So at most :data:`MAX_RUNNING` workers run at once; a job past a lower
cap is refused with :class:`~lkspace.studio.lanes.Busy` (HTTP 429) naming what runs, so
the user can wait or cancel one.  Exports run here too (their CPU apart from the threads
that redraw), one at a time from the export lane (:mod:`~lkspace.studio.lanes`), which
bounds them: they neither count against the cap nor show by id.
"""

from __future__ import annotations

import itertools
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from .. import Scaffold
from ..errors import LkspaceError, UsageError
from ..runtime.progress import Step, install
from ..runtime.workers import context, ignore_interrupts
from .answers import (
    Clearance,
    Exported,
    IdentifyAnswer,
    JobKind,
    JobProgress,
    JobResult,
    JobState,
    JobStatus,
    RelaxedCurves,
    Solved,
    table_crossings,
)
from .lanes import Busy
from .requests import SolveRequest

if TYPE_CHECKING:
    from multiprocessing.connection import Connection

    from ..geometry.realization import Realization

PRELOAD = [
    "lkspace.studio.jobs",
    "lkspace.strands.tracing",
    "lkspace.inverse.pipeline",
    "lkspace.knots.recognition",
    "lkspace.geometry.relax",
    "lkspace.studio.designs",
]
"""Modules the fork server imports once, so jobs start without importing them."""

IDENTIFY_SECONDS = 30.0
"""Time limit of one identification."""

REPLACED: tuple[JobKind, ...] = ("identify", "relax", "solve", "clearance")
"""The page's job kinds, run one at a time: starting one cancels the one running."""

MAX_RUNNING = 2 * len(REPLACED)
"""Most workers running at once over all pages (one of each kind for two pages); a studio may set a lower cap."""

MAX_JOBS = 64
"""Finished jobs remembered (the oldest are forgotten)."""


class ExportFailed(LkspaceError):
    """The export worker could not write the design (HTTP 422)."""

    status = 422


class PipeReporter:
    """Sends the progress of a worker's long steps to the server."""

    def __init__(self, channel: Connection) -> None:
        self._channel = channel

    def show(self, step: Step) -> None:
        """Send the state of ``step``."""
        self._channel.send(("progress", JobProgress(step.description, step.done, step.text)))

    def close(self, step: Step) -> None:
        """Nothing to remove."""


def identify_payload(scaffold: Scaffold, labels: np.ndarray, nulls: np.ndarray | None) -> IdentifyAnswer:
    """Return the knot or link type of a design (:func:`lkspace.identify`) as the page shows it.

    The one place the studio reads an identification.
    """
    from .. import identify
    from ..linktypes.common_names import common_name

    found = identify(scaffold, labels, nulls, time_limit=IDENTIFY_SECONDS)
    pieces = found.details.get("pieces")
    name = found.name
    if name is None and found.split and isinstance(pieces, list) and pieces and all(pieces):
        name = "split: " + " + ".join(sorted(str(p) for p in pieces))  # the atlas type (lookup finds it)
    return IdentifyAnswer(
        name=name,
        common_name=common_name(name, found.mirror) if name else None,
        status=found.status,
        components=found.components,
        linking_matrix=found.linking_matrix,
        mirror=found.mirror,
        split=found.split,
        crossings=found.crossings,
        least_crossings=table_crossings(name),
    )


def solve_payload(scaffold: Scaffold, query: SolveRequest) -> Solved:
    """Designs answering the page's query (:func:`lkspace.solve`): two CP-SAT workers, solutions told apart as designs."""
    from .. import SolveOptions, solve

    search = SolveOptions(count=query.count, distinct_up_to="none", time_limit=query.time_limit, workers=2)
    result = solve(scaffold, **query.options(), options=search)  # type: ignore[arg-type]
    designs = tuple((s.labels.tolist(), s.components) for s in result.solutions)
    return Solved(result.to_dict(), designs)


def relax_payload(real: Realization) -> RelaxedCurves:
    """Return the curves of ``real`` relaxed (:func:`lkspace.relax`), with their tube and clearance."""
    from .. import relax

    out = relax(real)
    return RelaxedCurves(tuple(out.curves), out.tube_radius, out.min_distance, out.closest)


def relaxed(real: Realization, answer: RelaxedCurves) -> Realization:
    """Return ``real`` with the curves of a :func:`relax_payload`."""
    curves = [np.array(c, dtype="<f8").copy() for c in answer.curves]
    return replace(
        real,
        curves=curves,
        tube_radius=answer.tube_radius,
        min_distance=answer.min_distance,
        closest=answer.closest,
    )


def export_payload(scaffold: Scaffold, labels: np.ndarray, nulls: np.ndarray | None, fmt: str) -> Exported:
    """Return the design written as ``fmt``: the file's content and name."""
    from .designs import export_bytes

    return Exported(*export_bytes(scaffold, labels, nulls, fmt))


def clearance_payload(real: Realization) -> Clearance:
    """Return the embedding check of ``real`` (:func:`lkspace.studio.designs.clearance`)."""
    from .designs import clearance

    return clearance(real)


TASKS: dict[JobKind, Callable[..., JobResult]] = {
    "identify": identify_payload,
    "solve": solve_payload,
    "relax": relax_payload,
    "export": export_payload,
    "clearance": clearance_payload,
}
"""Job kinds -> the function a worker runs."""


def run_job(kind: JobKind, args: tuple[Any, ...], channel: Connection) -> None:
    """Worker entry point: run ``TASKS[kind](*args)`` and send ``("done", result)`` or ``("error", message)``."""
    ignore_interrupts()
    install(PipeReporter(channel))
    try:
        channel.send(("done", TASKS[kind](*args)))
    except LkspaceError as exc:
        channel.send(("error", str(exc)))
    except Exception as exc:  # noqa: BLE001 - reported to the page, the server keeps running
        channel.send(("error", f"internal error ({type(exc).__name__}: {exc})"))


@dataclass(eq=False)
class Job:
    """One job: its process, what it reported and its state (``running``, ``done``, ``error``, ``cancelled``)."""

    id: int
    kind: JobKind
    process: Any
    channel: Connection
    """The reading end of the worker's pipe."""
    started: float = field(default_factory=time.monotonic)
    ended: float | None = None
    state: JobStatus = "running"
    progress: JobProgress | None = None
    result: JobResult | None = None
    error: str | None = None
    stopping: bool = False
    """Set before a cancel stops the worker: its end is then read as the cancel, not as the worker dying."""
    guard: threading.Lock = field(default_factory=threading.Lock, repr=False)
    """Held while the worker's messages are read, so two polls never read one message in halves."""

    def poll(self) -> JobState:
        """Take what the worker sent; return the job's state."""
        with self.guard:
            self._take()
        if self.state != "running":
            self.ended = self.ended or time.monotonic()
            self.process.join(timeout=0.5)
        elapsed = round((self.ended or time.monotonic()) - self.started, 2)
        return JobState(self.id, self.kind, self.state, elapsed, self.progress, self.result, self.error)

    def _take(self) -> None:
        """Read the worker's messages into the state (``guard`` held).

        ``channel`` is the reading end only: once the worker has exited (or was stopped mid-message)
        reading it raises :class:`EOFError`, so a read never waits for a worker that is gone.
        """
        while self.state == "running":
            try:
                if not self.channel.poll():
                    break
                what, value = self.channel.recv()
            except (EOFError, OSError):
                self.process.join(timeout=1)
                if self.stopping:
                    self.state = "cancelled"
                else:
                    self.state, self.error = "error", f"the worker stopped (exit code {self.process.exitcode})"
                break
            if what == "progress":
                self.progress = value
            elif what == "done":
                self.state, self.result = "done", value
            else:
                self.state, self.error = "error", value

    def cancel(self) -> None:
        """Stop the worker (if running) and mark the job cancelled; never waits for a poll."""
        if self.state != "running":
            return
        self.stopping = True
        self.process.terminate()
        self.process.join(timeout=2)
        if self.process.is_alive():
            self.process.kill()
            self.process.join(timeout=2)
        if self.guard.acquire(timeout=5):  # a poll reading now meets the pipe's end at once
            try:
                if self.state == "running":
                    self.state = "cancelled"
            finally:
                self.guard.release()
        else:
            self.state = "cancelled"


class Jobs:
    """The jobs of one studio."""

    def __init__(self, max_running: int = MAX_RUNNING) -> None:
        self._ctx = context(PRELOAD)
        self._jobs: dict[int, Job] = {}
        self._ids = itertools.count(1)
        self._lock = threading.Lock()
        self._starting = threading.Lock()
        self.max_running = max_running
        self.closed = False
        self.latest: dict[tuple[str, JobKind], Job] = {}
        """The newest job of each page and kind: ``(page id, kind) -> job``."""

    def running(self) -> list[Job]:
        """Return the page's jobs whose worker is still at work (:data:`REPLACED` kinds)."""
        jobs = list(self._jobs.values())
        return [j for j in jobs if j.kind in REPLACED and j.state == "running" and j.process.is_alive()]

    def start(self, kind: JobKind, *args: Any, page: str = "") -> Job:
        """Start a ``kind`` job for ``page``, cancelling that page's one of that kind running (:data:`REPLACED`).

        Raises :class:`~lkspace.studio.lanes.Busy` when :attr:`max_running` other workers run.
        Starts are taken one at a time, so a burst of requests from one page leaves one job running.
        """
        with self._starting:
            if self.closed:
                raise Busy("the studio is stopping")
            if kind in REPLACED and (page, kind) in self.latest:
                self.latest[page, kind].cancel()
            running = self.running()
            if len(running) >= self.max_running:
                kinds = ", ".join(j.kind for j in running)
                n = len(running)
                raise Busy(f"the studio is busy: {n} job{'s' if n != 1 else ''} running ({kinds}); wait or cancel one")
            channel, sending = self._ctx.Pipe(duplex=False)
            process = self._ctx.Process(target=run_job, args=(kind, args, sending), daemon=True)  # type: ignore[attr-defined]
            process.start()
            sending.close()  # the worker holds the only sending end: its exit ends the pipe
            with self._lock:
                job = Job(next(self._ids), kind, process, channel)
                self._jobs[job.id] = job
                finished = [j for j in self._jobs.values() if j.state != "running"]
                for old in finished[: max(0, len(self._jobs) - MAX_JOBS)]:
                    del self._jobs[old.id]
            if kind in REPLACED:
                self.latest[page, kind] = job
                if len(self.latest) > MAX_JOBS:  # pages that went away: forget their ended jobs
                    self.latest = {k: j for k, j in self.latest.items() if j.process.is_alive()}
            return job

    def run(self, kind: JobKind, *args: Any) -> JobState:
        """Run a ``kind`` job to its end and forget it; return its final state (the export lane's jobs)."""
        job = self.start(kind, *args)
        try:
            return self.wait(job)
        finally:
            with self._lock:
                self._jobs.pop(job.id, None)

    def export(self, scaffold: Scaffold, labels: np.ndarray, nulls: np.ndarray | None, fmt: str) -> tuple[bytes, str]:
        """Return the design written as ``fmt`` by a worker: ``(content, file name)``; :class:`ExportFailed` if it could not."""
        from .designs import EXPORTS

        if fmt not in EXPORTS:
            raise UsageError(f"format {str(fmt)[:20]!r}: choose one of {', '.join(EXPORTS)}")
        state = self.run("export", scaffold, labels, nulls, fmt)
        if not isinstance(state.result, Exported):
            raise ExportFailed(f"cannot export this design: {state.error or state.state}")
        return state.result.content, state.result.name

    def stop(self, kind: JobKind, page: str = "") -> None:
        """Cancel ``page``'s newest ``kind`` job if it still runs (a newer design made its answer stale)."""
        if (page, kind) in self.latest:
            self.latest[page, kind].cancel()

    def wait(self, job: Job, pause: float = 0.05) -> JobState:
        """Return the state of ``job`` once it has ended (done, error or cancelled by a newer one)."""
        while (state := job.poll()).state == "running":
            time.sleep(pause)
        return state

    def get(self, job_id: object) -> Job | None:
        """Return the page's job with id ``job_id``, if known."""
        job = self._jobs.get(job_id) if isinstance(job_id, int) else None
        return job if job is not None and job.kind in REPLACED else None

    def shutdown(self) -> None:
        """Stop every running worker (all signalled at once, then waited for) and start no more."""
        with self._starting:
            self.closed = True
        jobs = [j for j in list(self._jobs.values()) if j.state == "running"]
        for job in jobs:
            job.process.terminate()
        for job in jobs:
            job.cancel()
