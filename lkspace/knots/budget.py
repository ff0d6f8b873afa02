"""Budgets of identification: a time limit and size bounds, checked before and during the work.

Naming a diagram (simplification, Jones and HOMFLY-PT polynomials, SnapPy, knot Floer
homology) can take minutes and gigabytes on a big diagram, inside C extensions that
cannot be interrupted.  So :func:`run_in_time` runs it in a forked child process that is
killed when the time limit is reached; the caller then reports the status
``"unknown: time limit 60 s reached (during simplification)"`` instead of waiting.

The limit counts the child's **CPU time** (user + system, read from ``/proc`` every
:data:`POLL_SECONDS`; elsewhere the kernel's ``RLIMIT_CPU`` in whole seconds), so a busy
machine answers what an idle one answers, only later.  A child that gets no CPU at all
for :data:`WALL_FACTOR` times the limit of wall time is stopped too (a backstop, never
reached by work that runs).
A child whose parent is killed (a pool worker stopped at once) exits within
:data:`~lkspace.runtime.workers.ORPHAN_POLL` seconds.
Sizes are bounded before any work: :func:`twist_crossings` estimates the crossings the
twists alone make, and :data:`MAX_CROSSINGS` bounds the projected diagram.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import signal
import threading
import time
from collections.abc import Callable
from typing import Any, TypeVar

import numpy as np

from ..errors import LkspaceError
from ..runtime.progress import Step, install
from ..runtime.workers import exit_with

TIME_LIMIT = 60.0
"""Default seconds for identifying one design (``identify --time-limit``; 0 or ``None``: no limit)."""

MAX_CROSSINGS = 2000
"""Most crossings of a projected diagram that identification simplifies and names.

Beyond it the status is ``unknown: diagram too large``; and twists whose estimated
crossings (:func:`twist_crossings`) exceed it are refused before anything is realized.
The tables end at 13 crossings, so such diagrams are named only if simplification
removes nearly all of their crossings, which takes longer than any sensible limit.
"""

INLINE_CROSSINGS = 30
"""Projected diagrams up to this many crossings are named in this process, without a child.

They take milliseconds (every bounded invariant included), less than forking a child
process costs; the time limit guards the bigger ones.
"""

POLL_SECONDS = 0.1
"""How often the parent reads the child's CPU time (seconds of wall time)."""

WALL_FACTOR = 20.0
"""A child still running after this many times its CPU limit in wall time is stopped (load past 20 per core)."""

T = TypeVar("T")


class TimeLimitReached(Exception):
    """The time limit ran out; ``stage`` is what was running."""

    def __init__(self, stage: str) -> None:
        super().__init__(stage)
        self.stage = stage


def twist_crossings(degrees: np.ndarray, labels: np.ndarray) -> int:
    """Estimate the crossings the twists make: ``sum |t| (K - 1)`` over the edges.

    An edge of degree K with twist t turns its K strands by ``2 pi t / K``: every pair of
    the K strands crosses about twice per full turn in a generic projection.
    """
    k = np.asarray(degrees, np.float64)
    t = np.abs(np.asarray(labels, np.float64))  # floats: no overflow for labels near 2**63
    return int(np.sum(np.where(k > 1, t * (k - 1), 0.0)))


def cpu_seconds(pid: int) -> float | None:
    """Return the CPU time (user + system, seconds) process ``pid`` has used; ``None`` without ``/proc``."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as fh:
            data = fh.read()
        fields = data[data.rindex(b")") + 2 :].split()  # after the command name, which may hold spaces
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")  # utime, stime
    except (OSError, ValueError, IndexError):
        return None


def _limit_cpu(seconds: float) -> None:
    """In the child: let the kernel end it with SIGXCPU past ``seconds`` of CPU (where ``/proc`` cannot be read)."""
    with contextlib.suppress(ImportError, ValueError, OSError):
        import math
        import resource

        hard = resource.getrlimit(resource.RLIMIT_CPU)[1]
        soft = max(1, math.ceil(seconds))
        if hard == resource.RLIM_INFINITY or soft <= hard:
            resource.setrlimit(resource.RLIMIT_CPU, (soft, hard))


def run_in_time(func: Callable[[Callable[[str], None]], T], time_limit: float | None, step: Step | None = None) -> T:
    """Return ``func(stage)``, run in a forked child process killed after ``time_limit`` seconds of its CPU time.

    ``func`` calls ``stage("simplification")`` etc. as it goes; the stages are shown on
    ``step``.  Raises :class:`TimeLimitReached` when time runs out.  Without a limit (or
    without ``os.fork``) ``func`` runs in this process.
    """

    def note(text: str) -> None:
        if step is not None:
            step.note(text)

    if not time_limit or not hasattr(os, "fork"):
        return func(note)
    recv, send = multiprocessing.Pipe(duplex=False)
    parent = os.getpid()
    pid = os.fork()
    if pid == 0:  # pragma: no cover - the child: its coverage is not collected
        recv.close()
        install(None)
        threading.Thread(target=exit_with, args=(parent,), daemon=True).start()  # a parent killed never kills it
        if cpu_seconds(os.getpid()) is None:
            _limit_cpu(time_limit)
        try:
            send.send(("done", func(lambda text: send.send(("stage", text)))))
        except BaseException as exc:  # noqa: BLE001 - everything goes back to the parent
            send.send(("error", (type(exc).__name__, str(exc), getattr(exc, "exit_code", None))))
        finally:
            os._exit(0)
    send.close()
    stage = "starting the worker"
    started = noted = time.monotonic()
    reaped = False
    try:
        while True:
            used = cpu_seconds(pid)
            if (used is not None and used >= time_limit) or time.monotonic() - started >= WALL_FACTOR * time_limit:
                raise TimeLimitReached(stage)
            if not recv.poll(POLL_SECONDS):
                if time.monotonic() - noted >= 1.0:
                    note(stage)  # keeps the plain progress lines coming
                    noted = time.monotonic()
                continue
            try:
                kind, value = recv.recv()
            except EOFError:
                status = os.waitpid(pid, 0)[1]
                reaped = True
                if os.WIFSIGNALED(status) and os.WTERMSIG(status) == getattr(signal, "SIGXCPU", None):
                    raise TimeLimitReached(stage) from None
                raise LkspaceError(f"identification ended without an answer during {stage} (out of memory?)") from None
            if kind == "stage":
                stage = value
                note(stage)
            elif kind == "done":
                return value
            else:
                _reraise(*value)
    finally:
        if not reaped:
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
        recv.close()


def _reraise(kind: str, message: str, exit_code: Any) -> None:
    """Raise in this process the error the child reported."""
    if kind == "KeyboardInterrupt":
        raise KeyboardInterrupt
    if kind == "MemoryError":
        raise MemoryError(message)
    if exit_code is not None:
        raise LkspaceError(message, usage=exit_code == 2)
    raise RuntimeError(f"{kind} in the identification worker: {message}")
