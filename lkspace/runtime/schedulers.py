"""Where the shards of a big run execute: ``--scheduler local``, ``dask`` or ``tcp://HOST:PORT``.

``local`` (the default) runs shards in this process (``jobs`` = 1) or in a pool of
``jobs`` worker processes (:mod:`lkspace.runtime.workers`).  ``dask`` starts a
``distributed.LocalCluster`` of ``jobs`` single-threaded worker processes; ``tcp://...``
connects to a running Dask scheduler (a cluster started by ``dask-jobqueue``, Kubernetes
or ``dask scheduler`` / ``dask worker`` by hand).  Left unset, the scheduler is read from
the environment variable ``DASK_SCHEDULER_ADDRESS`` when it is set, else ``local``.

A named scheduler address is always contacted first (:func:`check_scheduler`): one that
does not answer within :data:`CONNECT_TIMEOUT` seconds is a usage error (exit 2) before any
work, never a silent local run.  Work too small to split (a one-file catalog, a count
that needs no census) runs in this process even then; the command says so.  The
LocalCluster serves no dashboard.

Under Dask every shard is one task; a task whose worker dies is run again on another
worker (``distributed``'s own retry of lost tasks, up to :data:`ALLOWED_FAILURES` worker
deaths per task), so a lost worker costs only its shard.  Dask is imported only here and
only when a Dask scheduler is asked for (the extra ``lkspace[dask]``).

This module imports nothing of lkspace but :mod:`lkspace.errors` and :mod:`lkspace.runtime.workers`.
"""

from __future__ import annotations

import contextlib
import logging
import os
import sys
from collections.abc import Callable, Iterator, Sequence
from typing import Any

from ..errors import MissingDependencyError, UsageError, require
from .pools import worker_pool

SCHEDULERS = ("local", "dask")
"""Named schedulers; anything else must be a ``tcp://HOST:PORT`` (or ``tls://``) address."""

ENV_ADDRESS = "DASK_SCHEDULER_ADDRESS"
CONNECT_TIMEOUT = 10
"""Seconds to wait for a named Dask scheduler to answer."""

NO_DASHBOARD = {"dashboard": False, "dashboard_address": "127.0.0.1:0"}
"""Scheduler options of our LocalCluster: no dashboard.  A ``distributed.Scheduler`` always
opens a web server (``dashboard_address=None`` alone still binds port 8787 and serves status
pages and metrics); this one listens on a free local port, and with no HTTP routes
(``distributed.scheduler.http.routes``) it answers every request with 404."""

ALLOWED_FAILURES = 3
"""Worker deaths a Dask task survives before the run fails (``distributed.scheduler.allowed-failures``)."""


def resolve_scheduler(spec: str | None) -> str:
    """Return the scheduler to use: ``spec``, else ``$DASK_SCHEDULER_ADDRESS``, else ``"local"``.

    Examples
    --------
    >>> resolve_scheduler("local"), resolve_scheduler("tcp://10.0.0.5:8786")
    ('local', 'tcp://10.0.0.5:8786')
    """
    text = (spec if spec is not None else os.environ.get(ENV_ADDRESS, "") or "local").strip()
    if text in SCHEDULERS or text.startswith(("tcp://", "tls://", "ucx://", "inproc://")):
        return text
    raise UsageError(
        f"scheduler {text!r}: use local, dask or a scheduler address like tcp://HOST:8786", parameter="scheduler"
    )


def is_dask(scheduler: str) -> bool:
    """Whether ``scheduler`` (resolved) runs shards on Dask."""
    return scheduler != "local"


def check_scheduler(scheduler: str) -> None:
    """Before any work: check that Dask is installed if ``scheduler`` needs it, and that a named scheduler answers.

    Raises :class:`~lkspace.errors.MissingDependencyError` without the extra ``lkspace[dask]``
    and :class:`~lkspace.errors.UsageError` when no scheduler answers at the address
    within :data:`CONNECT_TIMEOUT` seconds.
    """
    if not is_dask(scheduler):
        return
    distributed = import_distributed(f"scheduler {scheduler}", "scheduler")
    if scheduler != "dask":
        with _connect(distributed, scheduler):
            pass


@contextlib.contextmanager
def _connect(distributed: Any, address: str) -> Iterator[Any]:
    """Yield a ``distributed.Client`` of the scheduler at ``address``; one line if none answers in time.

    A ``tcp://`` address that refuses connections fails at once (``distributed`` would retry
    until the timeout).
    """
    try:
        if address.startswith("tcp://"):
            _knock(address[len("tcp://") :])
        client = distributed.Client(address, timeout=f"{CONNECT_TIMEOUT}s")
    except (OSError, TimeoutError) as exc:
        raise UsageError(
            f"scheduler {address}: no Dask scheduler answers there ({exc})", parameter="scheduler"
        ) from None
    with client:
        yield client


def import_distributed(purpose: str, parameter: str | None = None) -> Any:
    """Import ``distributed`` (extra ``lkspace[dask]``) although SnapPy's module is also named ``snappy``.

    Without the extra: :class:`~lkspace.errors.MissingDependencyError` for ``purpose``,
    naming ``parameter`` (the argument that asked for Dask).

    ``distributed`` probes ``import snappy`` for python-snappy compression and fails on
    SnapPy (extra ``lkspace[knots]``), which has no ``compress``; so ``snappy`` is hidden
    while ``distributed`` is imported, then put back (SnapPy stays importable).
    """
    if sys.modules.get("distributed") is not None:
        return sys.modules["distributed"]
    saved = sys.modules.get("snappy")
    if saved is None or not hasattr(saved, "compress"):
        sys.modules["snappy"] = None  # type: ignore[assignment]  # makes `import snappy` raise ImportError
    try:
        require("dask", "dask", purpose)
        return require("distributed", "dask", purpose)
    except MissingDependencyError as exc:
        exc.parameter = parameter
        raise
    finally:
        if saved is None:
            sys.modules.pop("snappy", None)
        else:
            sys.modules["snappy"] = saved


@contextlib.contextmanager
def dask_client(scheduler: str, jobs: int) -> Iterator[Any]:
    """Yield a ``distributed.Client`` of a new LocalCluster (``"dask"``, ``jobs`` workers) or of a running scheduler.

    The LocalCluster's worker processes are forked from this process once ``distributed``
    is imported (:func:`import_distributed`; a fresh interpreter would trip on SnapPy).
    """
    distributed = import_distributed(f"scheduler {scheduler}", "scheduler")
    import dask

    settings = {
        "distributed.scheduler.allowed-failures": ALLOWED_FAILURES,
        "distributed.worker.multiprocessing-method": "fork",
        "distributed.worker.daemon": False,  # a task may start processes (identification does)
        "distributed.scheduler.http.routes": [],  # the web servers serve nothing (see NO_DASHBOARD)
        "distributed.worker.http.routes": [],
    }
    with dask.config.set(settings):
        if scheduler == "dask":
            with quiet("distributed", logging.CRITICAL):  # its log, here and in the workers forked from here
                cluster = distributed.LocalCluster(
                    n_workers=jobs,
                    threads_per_worker=1,
                    processes=True,
                    dashboard_address=None,
                    scheduler_kwargs=NO_DASHBOARD,
                )
                try:
                    with distributed.Client(cluster) as client:
                        yield client
                except BaseException:  # Ctrl-C, SIGTERM, an error, the caller stopping early
                    stop_workers(cluster)
                    cluster.close()
                    raise
                cluster.close()
        else:
            with _connect(distributed, scheduler) as client:
                yield client


def _knock(host_port: str) -> None:
    """Open and close a TCP connection to ``HOST[:PORT]`` (Dask's port 8786 by default); ``OSError`` if refused."""
    import socket

    host, _, port = host_port.rpartition(":")
    if not port.isdigit() or host.endswith(":"):  # no port (an IPv6 host has colons of its own)
        host, port = host_port, "8786"
    with socket.create_connection((host.strip("[]") or "127.0.0.1", int(port)), timeout=CONNECT_TIMEOUT):
        pass


def run_tasks(
    fn: Callable[..., Any],
    shared: Any,
    items: Sequence[Any],
    scheduler: str,
    jobs: int,
    name: str = "lkspace",
    setup: Callable[[], object] | None = None,
) -> Iterator[tuple[int, Any]]:
    """Run ``fn(shared, item)`` for every item; yield ``(position, result)`` as each finishes.

    ``fn`` must be a top-level function (it is pickled).  ``shared`` goes to each worker
    once.  ``setup()`` runs first on every Dask worker (joining ones too) in its main
    thread, where libraries that install signal handlers must be imported.  Interrupting
    the iteration (Ctrl-C) stops the workers: the pool is terminated, or the Dask futures
    are cancelled.
    """
    if not items:
        return
    if not is_dask(scheduler):
        if jobs <= 1 or len(items) <= 1:
            for i, item in enumerate(items):
                yield i, fn(shared, item)
            return
        with worker_pool(min(jobs, len(items)), _init_local, (fn, shared)) as pool:
            yield from pool.unordered(_run_local, list(enumerate(items)))
        return
    distributed = import_distributed(f"scheduler {scheduler}", "scheduler")
    with dask_client(scheduler, jobs) as client:
        if setup is not None:
            client.register_plugin(_setup_plugin(distributed, setup), name=f"{name}-setup")
        [shared_future] = client.scatter([shared], broadcast=True, hash=False)
        futures = {
            client.submit(fn, shared_future, item, key=f"{name}-{i}-{os.getpid()}", pure=False): i
            for i, item in enumerate(items)
        }
        try:
            for future in distributed.as_completed(futures):
                yield futures[future], future.result()
        finally:
            client.cancel(list(futures))


STOP_SECONDS = 0.5
"""Seconds a worker of our LocalCluster is given to stop when a run ends early, before it is killed."""


def stop_workers(cluster: Any) -> None:
    """Close the workers of a LocalCluster at once, without waiting for their running tasks.

    A worker busy in a task does not answer a polite close (``LocalCluster.close`` waits
    four seconds before killing it); a run that ends early needs none of their results.
    """
    import asyncio

    async def close_all() -> None:
        await asyncio.gather(*(w.close(timeout=STOP_SECONDS) for w in list(cluster.workers.values())))

    cluster.sync(close_all)


@contextlib.contextmanager
def quiet(logger: str, level: int) -> Iterator[None]:
    """Within the body, the logger ``logger`` shows only records of ``level`` and above."""
    log = logging.getLogger(logger)
    old = log.level
    log.setLevel(level)
    try:
        yield
    finally:
        log.setLevel(old)


def _setup_plugin(distributed: Any, setup: Callable[[], object]) -> Any:
    class Setup(distributed.WorkerPlugin):
        def setup(self, worker: Any) -> None:
            setup()

    return Setup()


_LOCAL: list[tuple[Callable[..., Any], Any]] = []
"""In a pool worker of :func:`run_tasks`: the function and the shared argument (set once by :func:`_init_local`)."""


def _init_local(fn: Callable[..., Any], shared: Any) -> None:
    _LOCAL[:] = [(fn, shared)]


def _run_local(job: tuple[int, Any]) -> tuple[int, Any]:
    i, item = job
    fn, shared = _LOCAL[0]
    return i, fn(shared, item)
