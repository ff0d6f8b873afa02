"""Pools of worker processes that never wait for ever: a worker that died is noticed, a signal stops them at once.

``multiprocessing.Pool`` loses the task of a worker that dies (killed by a signal to the
process group, by the out-of-memory killer, or crashed in a C extension) and waits for its
result for ever; its ``terminate`` can even hang on a queue lock the dead worker held.  A
:class:`WorkerPool` is a ``concurrent.futures.ProcessPoolExecutor`` of workers started by
:func:`~lkspace.runtime.workers.context`: a worker that dies breaks the pool, and the
waiting caller gets :class:`WorkerLost` (one line), or the interrupt of the signal that
killed the worker when that signal reached this process too (Ctrl-C, SIGTERM to the
group).  Results are awaited in slices of :data:`POLL` seconds, so that a signal handler
runs at once whichever thread of this process the signal reached.  A body that ends by
an exception (an interrupt included) kills the workers before it goes on: running tasks
stop, queued ones never start.
"""

from __future__ import annotations

import contextlib
import os
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures import TimeoutError as FutureTimeout
from concurrent.futures.process import BrokenProcessPool
from typing import Any, TypeVar

from ..errors import LkspaceError
from .workers import context, deferred_signals, exit_with, ignore_interrupts

T = TypeVar("T")

POLL = 0.25
"""Seconds between a waiting caller's looks at its results (and calls of its ``waiting``)."""

GRACE = 1.0
"""Seconds a broken pool waits for the signal that may have killed its worker to reach this process."""


class WorkerLost(LkspaceError):
    """A worker process ended without an answer (killed, out of memory, crashed)."""


def _start_worker(owner: int, initializer: Callable[..., object] | None, initargs: tuple[Any, ...]) -> None:
    """Worker start: leave Ctrl-C to the owner, exit when the owner is gone, then ``initializer(*initargs)``."""
    ignore_interrupts()
    threading.Thread(target=exit_with, args=(owner,), name="lkspace-orphan", daemon=True).start()
    if initializer is not None:
        initializer(*initargs)


class WorkerPool:
    """Worker processes running top-level functions (:func:`worker_pool`)."""

    def __init__(self, executor: ProcessPoolExecutor) -> None:
        self.executor = executor

    def submit(self, fn: Callable[[Any], T], items: Sequence[Any]) -> list[Future[T]]:
        """Queue ``fn(item)`` for every item, the workers started whole before a signal is handled."""
        with deferred_signals():
            return [self.executor.submit(fn, item) for item in items]

    def ordered(self, fn: Callable[[Any], T], items: Sequence[Any]) -> Iterator[T]:
        """Yield ``fn(item)`` for every item, in order."""
        for future in self.submit(fn, items):
            yield self.result(future)

    def unordered(
        self, fn: Callable[[Any], T], items: Sequence[Any], waiting: Callable[[], object] | None = None
    ) -> Iterator[T]:
        """Yield ``fn(item)`` for every item as each finishes; ``waiting()`` is called every :data:`POLL` seconds meanwhile."""
        pending = set(self.submit(fn, items))
        while pending:
            done, pending = wait(pending, POLL, FIRST_COMPLETED)
            if not done and waiting is not None:
                waiting()
            for future in done:
                yield self.result(future)

    def result(self, future: Future[T]) -> T:
        """Return the result of ``future``, awaited in slices of :data:`POLL` seconds; :class:`WorkerLost` if its worker died."""
        while True:
            try:
                return future.result(POLL)
            except FutureTimeout:
                continue
            except BrokenProcessPool:
                time.sleep(GRACE)  # Ctrl-C or SIGTERM to the group kills workers too: its interrupt goes first
                raise WorkerLost("a worker process ended without an answer (killed, or out of memory?)") from None

    def kill(self) -> None:
        """Stop every worker now: running tasks end, queued ones never start."""
        processes = dict(self.executor._processes or {})  # no public way before Python 3.14 (terminate_workers)
        for process in processes.values():
            process.kill()
        self.executor.shutdown(wait=True, cancel_futures=True)


@contextlib.contextmanager
def worker_pool(
    processes: int, initializer: Callable[..., object] | None = None, initargs: tuple[Any, ...] = ()
) -> Iterator[WorkerPool]:
    """Yield a :class:`WorkerPool` of ``processes`` workers, each started by ``initializer(*initargs)``.

    Workers ignore Ctrl-C (the caller decides) and exit when this process is gone.  The
    pool is shut down when the body ends, its workers killed at once when the body
    raises (Ctrl-C and a caller stopping early included).
    """
    executor = ProcessPoolExecutor(
        processes, mp_context=context(), initializer=_start_worker, initargs=(os.getpid(), initializer, initargs)
    )
    pool = WorkerPool(executor)
    try:
        yield pool
    except BaseException:
        pool.kill()
        raise
    executor.shutdown(wait=True)
