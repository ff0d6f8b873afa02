"""How lkspace starts worker processes (never by forking a running program) and stops on signals.

``forkserver`` where the platform has it (Linux, macOS), ``spawn`` elsewhere (Windows):
a worker starts from a clean interpreter (or a clean fork server), so threads, locks and
open files of the main program are never copied into it.  Worker entry points are
top-level functions and their arguments are pickled.  This module imports nothing of
lkspace, so every layer may use it.

Ctrl-C in a terminal signals the whole process group: the fork server and every worker
too, not only the main process.  The main process alone decides what an interrupt
does (it stops its workers itself), so the fork server is started with SIGINT blocked
(:func:`start_fork_server`): it and the workers forked from it never see a Ctrl-C, not
even while they are starting up and have not yet ignored it (a fork server killed while
it starts breaks the pool being made; a worker killed while it imports prints a
traceback).
"""

from __future__ import annotations

import atexit
import contextlib
import os
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from typing import TYPE_CHECKING, TypeVar

if TYPE_CHECKING:
    import multiprocessing.context

T = TypeVar("T")

IMPORTED_IN = os.getpid()
"""The process that imported this module; a fork of it (a Dask worker of our LocalCluster) has another pid."""


def context(preload: Sequence[str] = ()) -> multiprocessing.context.BaseContext:
    """Return the multiprocessing context of lkspace's workers: ``forkserver`` where available, else ``spawn``.

    A process forked from one that had imported lkspace (the workers of the LocalCluster
    that ``--scheduler dask`` starts) uses ``spawn``: the fork server it would inherit is
    its parent's, which it can neither wait for nor reach.  The fork server is started
    here (:func:`start_fork_server`), importing the modules ``preload`` if this call
    starts it.
    """
    import multiprocessing as mp  # here: importing it costs every command tens of milliseconds

    forked = os.getpid() != IMPORTED_IN
    if "forkserver" not in mp.get_all_start_methods() or forked:
        return mp.get_context("spawn")
    start_fork_server(preload)
    return mp.get_context("forkserver")


def start_fork_server(preload: Sequence[str] = ()) -> None:
    """Start multiprocessing's fork server (if it is not running) with SIGINT blocked, so that its workers never see Ctrl-C.

    The signal mask is inherited through fork and exec: the fork server and every
    process it forks keep SIGINT blocked.  In this process the block lasts only while
    the server is launched (not while it starts up); a Ctrl-C that came meanwhile is
    delivered right after.  The server imports only ``preload`` (by default nothing, not
    even the main script), so it is ready in a moment and making a pool (which waits
    for it, with signals deferred) stays short; each worker imports what it needs.
    """
    from multiprocessing import forkserver, resource_tracker

    resource_tracker.ensure_running()  # first: starting it unblocks SIGINT
    forkserver.set_forkserver_preload(list(preload))  # ignored once the server runs
    if not in_main_thread():
        forkserver.ensure_running()
        return
    old = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        forkserver.ensure_running()
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


def ignore_interrupts() -> None:
    """In a worker: leave Ctrl-C to the main process, which stops the workers itself."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised in the main thread like Ctrl-C's KeyboardInterrupt (``signum`` 15)."""

    signum = int(signal.SIGTERM)


_FORK_HOOK: list[bool] = []
"""Whether :func:`_forked_child_defaults` is registered (once per process)."""


def _raise_terminated(signum: int, frame: object) -> None:
    raise Terminated()


def in_main_thread() -> bool:
    """Return whether this is the main thread (the only one that may set signal handlers)."""
    return threading.current_thread() is threading.main_thread()


QUICK_SIZE = 50_000
"""Jobs of fewer elements than this (points, samples) end in milliseconds: :func:`interruptible` runs them in place."""


def interruptible(call: Callable[[], T], size: int | None = None) -> T:
    """Return ``call()``, run in a thread while this one waits in short joins (main thread only).

    Python runs its signal handlers in the main thread between bytecodes, never inside one
    long C call: a KD-tree of millions of points would hold Ctrl-C back for seconds.  Here
    the interrupt goes on up at once; the call itself (it must release the GIL, as scipy's
    KD-trees do) finishes in its thread and its result is dropped.  A job whose ``size``
    is below :data:`QUICK_SIZE` runs in place: starting and joining a thread would cost
    more than it (milliseconds on a loaded machine) and Ctrl-C waits for it no longer.
    """
    if not in_main_thread() or (size is not None and size < QUICK_SIZE):
        return call()
    done: list[T] = []
    failed: list[BaseException] = []

    def run() -> None:
        try:
            done.append(call())
        except BaseException as exc:  # handed to the waiting thread
            failed.append(exc)

    worker = threading.Thread(target=run, name="lkspace-call", daemon=True)
    worker.start()
    while worker.is_alive():
        worker.join(0.05)
    if failed:
        raise failed[0]
    return done[0]


ORPHAN_POLL = 0.5
"""Seconds between a worker's (or a naming child's) checks that the process it works for still runs."""


def alive(pid: int) -> bool:
    """Whether process ``pid`` still runs: a zombie (ended, its parent yet to reap it) has ended (Linux's ``/proc``)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's process now holds the number
        return True
    try:
        with open(f"/proc/{pid}/stat", "rb") as fh:
            state = fh.read().rsplit(b")", 1)[1].split()[0]  # after the command name, which may hold spaces
    except (OSError, IndexError):  # no /proc (macOS): a zombie counts as running
        return True
    return state not in (b"Z", b"X")


def exit_with(owner: int) -> None:
    """Exit this process (status 1) once process ``owner`` is gone: an orphan's results reach nobody (run in a thread)."""
    while alive(owner) and os.getppid() != 1:
        time.sleep(ORPHAN_POLL)
    os._exit(1)


def _forked_child_defaults() -> None:
    """In a child forked within :func:`interrupt_signals`: default SIGTERM, SIGINT ignored.

    SIGTERM then kills the child (a Dask worker of our LocalCluster) without a
    :class:`Terminated` traceback, and Ctrl-C is left to the main process.
    """
    if signal.getsignal(signal.SIGTERM) is _raise_terminated:
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        signal.signal(signal.SIGINT, signal.SIG_IGN)


@contextlib.contextmanager
def interrupt_signals() -> Iterator[None]:
    """Within the body, SIGTERM stops the run like Ctrl-C does (main thread only).

    For programs (the command line wraps every command in it); library functions never
    install it, so a Python caller keeps its own SIGTERM handling.  A process forked
    meanwhile gets the default SIGTERM and ignores SIGINT: the main process stops it
    (:func:`_forked_child_defaults`).
    """
    if not in_main_thread():
        yield
        return
    if not _FORK_HOOK:
        os.register_at_fork(after_in_child=_forked_child_defaults)
        _FORK_HOOK.append(True)
    old = signal.signal(signal.SIGTERM, _raise_terminated)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, old)


@contextlib.contextmanager
def ignored_signals() -> Iterator[None]:
    """Within the body (a cleanup or a rename, milliseconds), SIGINT and SIGTERM are ignored (main thread only).

    The caller's handlers are put back when the body ends.
    """
    if not in_main_thread():
        yield
        return
    old = {s: signal.signal(s, signal.SIG_IGN) for s in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for s, handler in old.items():
            signal.signal(s, handler)


@contextlib.contextmanager
def deferred_signals() -> Iterator[None]:
    """Within the body, SIGINT and SIGTERM wait; one that came is raised when the body ends (main thread only).

    The caller's handlers are put back when the body ends; the signal is then raised as
    ``KeyboardInterrupt`` (SIGINT) or :class:`Terminated` (SIGTERM).  The signal wins over
    an error of the body (which it may have caused: a worker or the fork server stopped
    by the same signal to the process group breaks the pool).
    """
    if not in_main_thread():
        yield
        return
    caught: list[int] = []
    old = {s: signal.signal(s, lambda signum, frame: caught.append(signum)) for s in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for s, handler in old.items():
            signal.signal(s, handler)
        if caught:
            raise Terminated() if caught[0] == signal.SIGTERM else KeyboardInterrupt()


@contextlib.contextmanager
def kept_interrupt_handler() -> Iterator[None]:
    """Within the body (an import of SnapPy), SIGINT keeps its handler: put back if the body replaced it (main thread only).

    SnapPy's PARI (cypari's copy of cysignals) installs a C-level SIGINT handler and a
    Python-level one that raises only what that C handler recorded.  Once
    :func:`ignored_signals` or :func:`deferred_signals` put the Python-level one back,
    Python's C handler is in place again, that handler finds nothing recorded, and every
    later Ctrl-C is lost.  PARI runs in lkspace's own process for milliseconds only (longer
    naming runs in children that ignore Ctrl-C), so Python's handling is kept instead.
    """
    if not in_main_thread():
        yield
        return
    old = signal.getsignal(signal.SIGINT)
    try:
        yield
    finally:
        if old is not None and signal.getsignal(signal.SIGINT) is not old:
            signal.signal(signal.SIGINT, old)


INTERRUPTED = (128 + signal.SIGINT, 128 + signal.SIGTERM)
"""Exit statuses of a program stopped by Ctrl-C (130) or SIGTERM (143)."""


def exit_now(code: int) -> None:
    """End the program with status ``code`` after an interrupt, without the interpreter's teardown.

    The output is flushed, then the atexit handlers run (multiprocessing stops and joins
    its children there) with stderr silenced: the interrupt was reported in one line, and
    a library's teardown of what the interrupt cut short (a Dask cluster half started)
    has nothing to add.  What is skipped is freeing every module, which takes seconds on
    a busy machine once numba, pyarrow and pandas are loaded.
    """
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError, ValueError):  # a closed pipe, a closed file
            stream.flush()
    with contextlib.suppress(OSError):
        os.dup2(os.open(os.devnull, os.O_WRONLY), 2)
    atexit._run_exitfuncs()
    os._exit(code)
