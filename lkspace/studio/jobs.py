"""Identify, relax, measure and solve in worker processes: never blocking an edit, cancelled by terminating.

Each job runs :func:`run_job` in a fresh process of lkspace's worker context
(:func:`lkspace.workers.context`; the fork server preloads the heavy modules, so a job
starts in milliseconds after the first).  Progress of the library's long steps
(:mod:`lkspace.progress`) and the result come back through a queue the server drains
when the page polls.  A new identify, relax or clearance measurement cancels the one before
it (its result would be stale; a new design stops a measurement too); a solve runs until it
ends or the page cancels it.
"""

from __future__ import annotations

import base64
import itertools
import queue as queues
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from .. import Scaffold
from ..errors import LkspaceError
from ..progress import Step, install
from ..workers import context, ignore_interrupts

if TYPE_CHECKING:
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

REPLACED = ("identify", "relax", "clearance")
"""Job kinds of which only the newest matters: starting one cancels the one before."""

MAX_JOBS = 64
"""Finished jobs remembered (the oldest are forgotten)."""


class QueueReporter:
    """Sends the progress of a worker's long steps to the server."""

    def __init__(self, channel: Any) -> None:
        self._channel = channel

    def show(self, step: Step) -> None:
        """Send the state of ``step``."""
        self._channel.put(("progress", {"step": step.description, "done": step.done, "note": step.text}))

    def close(self, step: Step) -> None:
        """Nothing to remove."""


def identify_payload(scaffold: Scaffold, labels: np.ndarray, nulls: np.ndarray | None) -> dict[str, Any]:
    """Return the knot or link type of a design (:func:`lkspace.identify`) as the page shows it."""
    from .. import identify

    found = identify(scaffold, labels, nulls, time_limit=IDENTIFY_SECONDS)
    return {
        "name": found.name,
        "status": found.status,
        "components": found.components,
        "linking_matrix": found.linking_matrix,
        "mirror": found.mirror,
        "split": found.split,
        "crossings": found.crossings,
    }


def solve_payload(scaffold: Scaffold, options: dict[str, Any]) -> dict[str, Any]:
    """Designs answering a query (:func:`lkspace.solve`); ``options`` are its keyword arguments."""
    from .. import solve

    result = solve(scaffold, **options)
    out = result.to_dict()
    out["solutions"] = [{"labels": s.labels.tolist(), "components": s.components} for s in result.solutions]
    return out


def relax_payload(real: Realization) -> dict[str, Any]:
    """Return the curves of ``real`` relaxed (:func:`lkspace.relax`): ``points`` (base64 ``float64``), ``counts``, tube, clearance."""
    from .. import relax

    out = relax(real)
    return {
        "points": base64.b64encode(np.vstack(out.curves).astype("<f8").tobytes()).decode("ascii"),
        "counts": [len(c) for c in out.curves],
        "tube_radius": out.tube_radius,
        "min_distance": out.min_distance,
        "closest": out.closest,
    }


def relaxed(real: Realization, payload: dict[str, Any]) -> Realization:
    """Return ``real`` with the curves of a :func:`relax_payload`."""
    points = np.frombuffer(base64.b64decode(payload["points"]), "<f8").reshape(-1, 3)
    curves = np.split(points, np.cumsum(payload["counts"])[:-1])
    fields = {k: payload[k] for k in ("tube_radius", "min_distance", "closest")}
    return replace(real, curves=[c.copy() for c in curves], **fields)


def clearance_payload(real: Realization) -> dict[str, Any]:
    """Return the embedding check of ``real`` (:func:`lkspace.studio.designs.clearance`)."""
    from .designs import clearance

    return clearance(real)


TASKS: dict[str, Callable[..., dict[str, Any]]] = {
    "identify": identify_payload,
    "solve": solve_payload,
    "relax": relax_payload,
    "clearance": clearance_payload,
}
"""Job kinds -> the function a worker runs."""


def run_job(kind: str, args: tuple[Any, ...], channel: Any) -> None:
    """Worker entry point: run ``TASKS[kind](*args)`` and send ``("done", result)`` or ``("error", message)``."""
    ignore_interrupts()
    install(QueueReporter(channel))
    try:
        channel.put(("done", TASKS[kind](*args)))
    except LkspaceError as exc:
        channel.put(("error", str(exc)))
    except Exception as exc:  # noqa: BLE001 - reported to the page, the server keeps running
        channel.put(("error", f"internal error ({type(exc).__name__}: {exc})"))


@dataclass(eq=False)
class Job:
    """One job: its process, what it reported and its state (``running``, ``done``, ``error``, ``cancelled``)."""

    id: int
    kind: str
    process: Any
    channel: Any
    started: float = field(default_factory=time.monotonic)
    ended: float | None = None
    state: str = "running"
    progress: dict[str, Any] = field(default_factory=dict)
    result: Any = None
    error: str | None = None

    def poll(self) -> dict[str, Any]:
        """Take what the worker sent; return the job's JSON view."""
        while self.state == "running":
            try:
                what, value = self.channel.get_nowait()
            except queues.Empty:
                if not self.process.is_alive():
                    time.sleep(0.05)  # a result sent just before exiting may still be in the pipe
                    if self.channel.empty():
                        self.state, self.error = "error", f"the worker stopped (exit code {self.process.exitcode})"
                break
            if what == "progress":
                self.progress = value
            elif what == "done":
                self.state, self.result = "done", value
            else:
                self.state, self.error = "error", value
        if self.state != "running":
            self.ended = self.ended or time.monotonic()
            self.process.join(timeout=0.5)
        return {
            "id": self.id,
            "kind": self.kind,
            "state": self.state,
            "elapsed": round((self.ended or time.monotonic()) - self.started, 2),
            "progress": self.progress,
            "result": self.result,
            "error": self.error,
        }

    def cancel(self) -> None:
        """Stop the worker (if running) and mark the job cancelled."""
        if self.state == "running":
            self.state = "cancelled"
            self.process.terminate()
            self.process.join(timeout=2)
            if self.process.is_alive():
                self.process.kill()
                self.process.join(timeout=2)


class Jobs:
    """The jobs of one studio."""

    def __init__(self) -> None:
        self._ctx = context(PRELOAD)
        self._jobs: dict[int, Job] = {}
        self._ids = itertools.count(1)
        self._lock = threading.Lock()
        self.latest: dict[str, Job] = {}

    def start(self, kind: str, *args: Any) -> Job:
        """Start a ``kind`` job; a new identify or relax cancels the previous one (:data:`REPLACED`)."""
        if kind in REPLACED and kind in self.latest:
            self.latest[kind].cancel()
        channel = self._ctx.Queue()
        process = self._ctx.Process(target=run_job, args=(kind, args, channel), daemon=True)  # type: ignore[attr-defined]
        process.start()
        with self._lock:
            job = Job(next(self._ids), kind, process, channel)
            self._jobs[job.id] = job
            finished = [j for j in self._jobs.values() if j.state != "running"]
            for old in finished[: max(0, len(self._jobs) - MAX_JOBS)]:
                del self._jobs[old.id]
        if kind in REPLACED:
            self.latest[kind] = job
        return job

    def stop(self, kind: str) -> None:
        """Cancel the newest ``kind`` job if it still runs (a newer design made its answer stale)."""
        if kind in self.latest:
            self.latest[kind].cancel()

    def wait(self, job: Job, pause: float = 0.05) -> dict[str, Any]:
        """Return the JSON view of ``job`` once it has ended (done, error or cancelled by a newer one)."""
        while (state := job.poll())["state"] == "running":
            time.sleep(pause)
        return state

    def get(self, job_id: object) -> Job | None:
        """Return the job with id ``job_id``, if known."""
        return self._jobs.get(job_id) if isinstance(job_id, int) else None

    def shutdown(self) -> None:
        """Stop every running worker."""
        for job in list(self._jobs.values()):
            job.cancel()
