"""Writing the parts of a catalog, in this process or in a pool of worker processes.

Workers are started with the ``forkserver`` method where there is one (Linux, macOS)
and ``spawn`` elsewhere (Windows), never by forking a running program: each worker
imports lkspace afresh, receives the run's state once (:func:`init_worker`) and writes
whole parts (:func:`write_part`).  Workers ignore SIGINT and leave the decisions to the
main process, which on Ctrl-C or SIGTERM terminates them at once (queued parts never
start) and removes their temporary files; a worker whose main process has died exits
within :data:`ORPHAN_POLL` seconds.
"""

from __future__ import annotations

import contextlib
import multiprocessing as mp
import os
import pickle
import signal
import tempfile
import threading
import time
from collections.abc import Callable, Generator, Iterator
from typing import Any

from ..engine import is_dask, run_tasks
from ..errors import require
from ..workers import Terminated, context, ignore_interrupts, in_main_thread
from .batches import space_batches
from .lock import pid_alive
from .transaction import file_sha256
from .writer import write_batches

KILL_ONCE = "LKSPACE_KILL_WORKER_ONCE"

ORPHAN_POLL = 0.5
"""Seconds between a worker's checks that the main process still runs."""

_STATE: dict[str, Any] = {}


def init_worker(state: bytes, main_pid: int) -> None:
    """Worker start: ignore SIGINT, take the run's state, exit when the main process is gone.

    The arguments are plain bytes and an int, so a worker started just before its main
    process stopped still starts cleanly (and then exits).
    """
    ignore_interrupts()
    threading.Thread(target=_exit_with, args=(main_pid,), daemon=True).start()
    _STATE.clear()
    _STATE.update(pickle.loads(state))


def _exit_with(main_pid: int) -> None:
    while pid_alive(main_pid) and os.getppid() != 1:
        time.sleep(ORPHAN_POLL)
    os._exit(1)  # an orphan: nobody will use what it writes


def write_part(i: int) -> tuple[int, dict[str, Any]]:
    """Write part ``i`` of the run in ``_STATE``; return ``(i, summary with file and sha256)``."""
    return write_part_with(_STATE, i)


def write_part_with(st: dict[str, Any], i: int) -> tuple[int, dict[str, Any]]:
    """Write part ``i`` of the run ``st`` (a Dask task, or :func:`write_part` in a pool worker)."""
    if st.get("on_dask"):
        fault_hook()
    if st.get("remote") is not None:
        return write_part_remote(st, i)
    path = os.path.join(st["folder"], st["files"][i])
    meta = {**st["meta"], "shard": {"index": i, "count": len(st["files"]), "plan": st["plan"], "run": st["run"]}}
    ids = st["ranges"][i] if st["ranges"] is not None else None
    batches = space_batches(st["space"], st["mode"], ids, *st["walk"])
    summary = write_batches(path, st["schema"], meta, batches, st.get("on_rows"))
    return i, {**summary, "file": st["files"][i], "sha256": file_sha256(path)}


def write_part_remote(st: dict[str, Any], i: int) -> tuple[int, dict[str, Any]]:
    """Write part ``i`` to a local temporary file, upload it under its final name (fsspec); return its summary."""
    fsspec = require("fsspec", "dask", f"writing to {st['remote']}")
    fs, root = fsspec.core.url_to_fs(st["remote"])
    dest = root if st["files"] is None else f"{root}/{st['files'][i]}"
    shard = {"index": i, "count": st["count"], "plan": st["plan"]}
    meta = {**st["meta"], "shard": shard if st["files"] is None else {**shard, "run": st["run"]}}
    ids = st["ranges"][i] if st["ranges"] is not None else None
    with tempfile.TemporaryDirectory(prefix="lkspace-part-") as tmp:
        local = os.path.join(tmp, "part.parquet")
        summary = write_batches(local, st["schema"], meta, space_batches(st["space"], st["mode"], ids, *st["walk"]))
        digest = file_sha256(local)
        fs.put_file(local, dest)
    name = os.path.basename(dest) if st["files"] is None else st["files"][i]
    return i, {**summary, "file": name, "sha256": digest}


def fault_hook() -> None:
    """Kill this worker once, for tests of lost workers (Dask runs only).

    With ``$LKSPACE_KILL_WORKER_ONCE`` set to a path that does not exist yet, the first
    part to start creates it and kills its own worker process (SIGKILL), as a lost
    machine would.
    """
    flag = os.environ.get(KILL_ONCE)
    if flag:
        try:
            fd = os.open(flag, os.O_CREAT | os.O_EXCL | os.O_WRONLY)
        except FileExistsError:
            return
        os.close(fd)
        os.kill(os.getpid(), signal.SIGKILL)


def run_parts(
    state: dict[str, Any], todo: list[int], jobs: int, tick: Callable[[int], object], scheduler: str = "local"
) -> Generator[tuple[int, dict[str, Any]], None, None]:
    """Write the parts ``todo`` with ``jobs`` processes; yield ``(i, summary)`` as each finishes.

    ``tick(rows written so far)`` is called as rows are written (in this process) or at
    least every quarter second (rows of the finished parts, with workers).  An exception
    (KeyboardInterrupt included) terminates the workers before it propagates.  With a
    Dask ``scheduler`` (:mod:`lkspace.engine`) each part is a Dask task.
    """
    if is_dask(scheduler):
        rows_done = 0
        shared = {**state, "on_dask": True}
        for _, done in run_tasks(write_part_with, shared, todo, scheduler, jobs, name="lkspace-part"):
            rows_done += int(done[1]["rows"])
            yield done
            tick(rows_done)
        return
    if jobs <= 1 or len(todo) <= 1:  # in this process: rows counted as they are written
        rows = [0]

        def on_rows(n: int) -> None:
            rows[0] += n
            tick(rows[0])

        _STATE.clear()
        _STATE.update(state, on_rows=on_rows)
        try:
            for i in todo:
                yield write_part(i)
        finally:
            _STATE.clear()
        return
    rows_done = 0
    payload = pickle.dumps(state)
    with deferred_signals():  # a pool half made cannot be stopped: finish making it, then stop
        pool = context().Pool(min(jobs, len(todo)), initializer=init_worker, initargs=(payload, os.getpid()))
    try:
        results = pool.imap_unordered(write_part, todo)
        for _ in todo:
            while True:
                try:
                    done = results.next(timeout=0.25)
                    break
                except mp.TimeoutError:
                    tick(rows_done)
            rows_done += int(done[1]["rows"])
            yield done
            tick(rows_done)
        pool.close()
    except BaseException:
        pool.terminate()
        raise
    finally:
        pool.join()


@contextlib.contextmanager
def ignored_signals() -> Iterator[None]:
    """Within the body (a cleanup or a rename, milliseconds), SIGINT and SIGTERM are ignored."""
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
    """Within the body, SIGINT and SIGTERM wait; one that came is raised when the body ends.

    The signal wins over an error of the body (which it may have caused: a worker or
    the fork server stopped by the same signal to the process group breaks the pool).
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
