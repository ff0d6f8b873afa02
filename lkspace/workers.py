"""How lkspace starts worker processes (never by forking a running program) and stops on signals.

``forkserver`` where the platform has it (Linux, macOS), ``spawn`` elsewhere (Windows):
a worker starts from a clean interpreter (or a clean fork server), so threads, locks and
open files of the main program are never copied into it.  Worker entry points are
top-level functions and their arguments are pickled.  This module imports nothing of
lkspace, so every layer may use it.
"""

from __future__ import annotations

import contextlib
import multiprocessing as mp
import os
import signal
import threading
from collections.abc import Iterator

IMPORTED_IN = os.getpid()
"""The process that imported this module; a fork of it (a Dask worker of our LocalCluster) has another pid."""


def context() -> mp.context.BaseContext:
    """Return the multiprocessing context of lkspace's workers: ``forkserver`` where available, else ``spawn``.

    A process forked from one that had imported lkspace (the workers of the LocalCluster
    that ``--scheduler dask`` starts) uses ``spawn``: the fork server it would inherit is
    its parent's, which it can neither wait for nor reach.
    """
    forked = os.getpid() != IMPORTED_IN
    return mp.get_context("forkserver" if "forkserver" in mp.get_all_start_methods() and not forked else "spawn")


def ignore_interrupts() -> None:
    """In a worker: leave Ctrl-C to the main process, which stops the workers itself."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised in the main thread like Ctrl-C's KeyboardInterrupt (``signum`` 15)."""

    signum = int(signal.SIGTERM)


def _raise_terminated(signum: int, frame: object) -> None:
    raise Terminated()


def in_main_thread() -> bool:
    """Return whether this is the main thread (the only one that may set signal handlers)."""
    return threading.current_thread() is threading.main_thread()


@contextlib.contextmanager
def interrupt_signals() -> Iterator[None]:
    """Within the body, SIGTERM stops the run like Ctrl-C does (main thread only)."""
    if not in_main_thread():
        yield
        return
    old = signal.signal(signal.SIGTERM, _raise_terminated)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, old)
