"""One writer per catalog: a lock file beside the target.

``.NAME.lkspace-lock`` is created with ``O_CREAT | O_EXCL`` (atomic on every local file
system) and holds the writer's pid, host and start time as JSON.  A second run finds it
and stops with :class:`~lkspace.errors.CatalogLockedError` naming the first.  A lock
left by a run that was killed (its pid no longer runs on this host) is stale and taken
over; a lock from another host is never guessed at: the message says which file to
delete once that run is known to be gone.

A process may take a lock it holds again (nested: the command line takes it before any
work, the writer once more around the build); only the outer hold removes it.
"""

from __future__ import annotations

import contextlib
import json
import os
import socket
import stat
import sys
import time
from collections.abc import Iterator
from dataclasses import dataclass

from ..errors import CatalogLockedError

HELD: set[str] = set()
"""Lock files this process holds (absolute paths): taking one again is a no-op."""

TORN_LOCK_SECONDS = 10.0
"""A lock file still empty or unreadable after this many seconds is stale (its writer died while creating it)."""


def pid_alive(pid: int) -> bool:
    """Return whether process ``pid`` runs on this machine (``True`` when it cannot be told)."""
    if pid <= 0:
        return False
    if sys.platform == "win32":  # os.kill(pid, 0) would terminate it there
        try:
            import psutil  # type: ignore[import-untyped]
        except ImportError:
            return True
        return bool(psutil.pid_exists(pid))
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # it exists, owned by someone else
        return True
    return True


@dataclass(frozen=True)
class LockHolder:
    """Who holds a catalog's lock, as its lock file records it (JSON).

    Attributes
    ----------
    pid : int
        The writer's process id.
    host : str
        The writer's host name.
    started : str
        When it took the lock, ``YYYY-MM-DD HH:MM:SS`` local time.
    """

    pid: int
    host: str
    started: str

    @classmethod
    def this_process(cls) -> LockHolder:
        """Return the record of this process, now."""
        return cls(os.getpid(), socket.gethostname(), time.strftime("%Y-%m-%d %H:%M:%S"))

    def to_json(self) -> str:
        """Return the lock file's text."""
        return json.dumps({"pid": self.pid, "host": self.host, "started": self.started})


def _holder(lock: str) -> LockHolder | None:
    """Return the lock's holder, or ``None`` when the file is empty, torn or not a lock record."""
    try:
        if not stat.S_ISREG(os.stat(lock).st_mode):  # a FIFO would block the read
            return None
        with open(lock, encoding="utf-8") as fh:
            data = json.load(fh)
    except (OSError, ValueError, RecursionError):  # RecursionError: nested past the stack
        return None
    if not isinstance(data, dict):
        return None
    pid, host, started = data.get("pid"), data.get("host"), data.get("started")
    if isinstance(pid, bool) or not isinstance(pid, int) or not 0 < pid < 2**31 or not isinstance(host, str):
        return None  # not a process number (os.kill overflowed past a C int)
    return LockHolder(pid, host, str(started))


def _is_stale(lock: str, holder: LockHolder | None) -> bool:
    if holder is None:
        try:
            return time.time() - os.stat(lock).st_mtime > TORN_LOCK_SECONDS
        except FileNotFoundError:
            return True
    return holder.host == socket.gethostname() and not pid_alive(holder.pid)


@contextlib.contextmanager
def catalog_lock(lock: str, target: str) -> Iterator[None]:
    """Hold the lock file ``lock`` of catalog ``target`` for the body; remove it afterwards (module docstring)."""
    key = os.path.abspath(lock)
    if key in HELD:
        yield
        return
    record = LockHolder.this_process().to_json()
    for _ in range(3):
        try:
            fd = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
        except FileExistsError:
            holder = _holder(lock)
            if _is_stale(lock, holder):
                with contextlib.suppress(FileNotFoundError):
                    os.remove(lock)
                continue
            who = f"pid {holder.pid} on {holder.host}, started {holder.started}" if holder else "a run that is starting"
            raise CatalogLockedError(
                f"{target}: another lkspace run is writing this catalog ({who}); wait for it to finish, "
                f"or delete {lock} if that run is gone"
            ) from None
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(record)
        break
    else:  # pragma: no cover - three stale locks in a row: a race with other writers
        raise CatalogLockedError(f"{target}: could not take the lock {lock}; try again")
    HELD.add(key)
    try:
        yield
    finally:
        HELD.discard(key)
        with contextlib.suppress(FileNotFoundError):
            os.remove(lock)
