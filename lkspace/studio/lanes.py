"""Bounded work: the lane exports run in (apart from the threads that redraw), and the busy answer.

An export (a realization written as SVG, STL, ...) can take seconds of CPU.  Run in the
thread pool that answers edits, twenty of them at once held a redraw for 38 s; here they
wait in a lane of their own, whose daemon thread hands them one at a time to a worker
process (:meth:`~lkspace.studio.jobs.Jobs.run`), at most :data:`MAX_WAITING` in line; the
request past that is answered 429 (:class:`Busy`) at once.
"""

from __future__ import annotations

import asyncio
import concurrent.futures
import queue
import threading
from collections.abc import Callable
from typing import Any

from ..errors import UsageError

MAX_WAITING = 16
"""Exports waiting in line behind the one running (one more is refused: :class:`Busy`)."""


class Busy(UsageError):
    """The studio is running as much as it takes at once: wait, or cancel a job (HTTP 429)."""

    status = 429


class Lane:
    """Runs one kind of work in order on ``threads`` daemon threads, with at most ``waiting`` requests in line."""

    def __init__(self, what: str, threads: int = 1, waiting: int = MAX_WAITING) -> None:
        self.what = what
        self._threads, self._waiting = threads, waiting
        self._work: queue.Queue[tuple[concurrent.futures.Future[Any], Callable[..., Any], tuple[Any, ...]]]
        self._work = queue.Queue()
        self._pending = 0
        self._lock = threading.Lock()
        self._started = False

    @property
    def pending(self) -> int:
        """Requests running or waiting."""
        return self._pending

    async def run(self, fn: Callable[..., Any], *args: Any) -> Any:
        """Return ``fn(*args)`` computed in the lane; :class:`Busy` at once when the line is full."""
        with self._lock:
            if self._pending >= self._threads + self._waiting:
                n = self._pending
                things = self.what if n == 1 else f"{self.what}s"
                raise Busy(f"the studio is busy: {n} {things} running or in line; wait for them to finish")
            self._pending += 1
            if not self._started:
                for i in range(self._threads):
                    threading.Thread(target=self._serve, name=f"lane-{self.what}-{i}", daemon=True).start()
                self._started = True
        future: concurrent.futures.Future[Any] = concurrent.futures.Future()
        self._work.put((future, fn, args))
        return await asyncio.wrap_future(future)

    def _serve(self) -> None:
        """Take work in order (a lane thread); skip work whose request went away."""
        while True:
            future, fn, args = self._work.get()
            try:
                if future.set_running_or_notify_cancel():
                    try:
                        future.set_result(fn(*args))
                    except BaseException as exc:  # noqa: BLE001 - handed to the request, which answers it
                        future.set_exception(exc)
            finally:
                with self._lock:
                    self._pending -= 1
