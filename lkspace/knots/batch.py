"""Identifying many designs of one scaffold: keyed by invariants, named once per key.

:func:`identify_batch` sets apart the designs that cannot be identified (open strands,
twists too large), keys the rest in compiled code (:mod:`lkspace.knots.keyed`), and names
in full, in worker processes under the time limit, only what the keys leave
(:mod:`lkspace.knots.key_names`).
"""

from __future__ import annotations

import contextlib
import json
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd
from numpy.typing import ArrayLike

from ..model.scaffold import Scaffold
from ..runtime.pools import WorkerPool, worker_pool
from ..runtime.progress import task
from .budget import MAX_CROSSINGS, TIME_LIMIT, TimeLimitReached
from .identification import Json, NameFields
from .key_names import KeyCache, share_names
from .keyed import keys_of
from .naming import name_in_time, presimplified, status_of
from .recognition import check_identifiable
from .tables import knot_modules, tables

_WORKER: dict[str, float | None] = {}
"""The worker's time limit per design (``time_limit``), set by :func:`_init_worker`."""


def _init_worker(time_limit: float | None = TIME_LIMIT) -> None:
    _WORKER.update(time_limit=time_limit)


def _name_chunk(items: list[tuple[list[list[int]], int]]) -> list[NameFields]:
    """In a worker: :func:`_name_fields` of each item."""
    return [_name_fields(item) for item in items]


def _name_fields(item: tuple[list[list[int]], int]) -> NameFields:
    """Name one design's PD code under the time limit: its row fields but ``components`` and ``linking_matrix``."""
    pd, n_components = item
    time_limit = _WORKER.get("time_limit", TIME_LIMIT)
    if len(pd) > MAX_CROSSINGS:
        return NameFields.refused(f"unknown: diagram too large: {len(pd):,} crossings > {MAX_CROSSINGS:,}")
    try:  # simplified first, so that most diagrams are small enough to be named without a child process
        named = name_in_time(presimplified(pd), n_components, time_limit or None, None, floer=False)
    except TimeLimitReached as exc:
        return NameFields.refused(f"unknown: time limit {time_limit:g} s reached (during {exc.stage})")
    return NameFields.of(named, status_of(named))


COLUMNS = ["knot_name", "components", "split", "mirror", "crossings", "jones", "linking_matrix", "status", "error"]

BATCH = 20_000
"""Designs keyed per call of the compiled kernel (bounds the memory of one call)."""


@dataclass(frozen=True)
class NamerOptions:
    """How designs are named in full (:class:`Namer`).

    Attributes
    ----------
    processes : int
        Worker processes naming the designs named in full (``1``: in this process).
        Workers are started by :func:`lkspace.runtime.workers.context` (never a fork of this
        program).
    time_limit : float or None
        Seconds per design named in full, as for :func:`identify` (default 60); a
        design that runs out gets the status ``unknown: time limit ...`` and the same
        text in ``error``.
    isolate : bool
        Name in worker processes even when ``processes`` is 1.  For callers that run
        in a thread other than the main one (a Dask task): SnapPy's PARI works only in a
        process's main thread, and a thread would leave exteriors undecided.
    """

    processes: int = 1
    time_limit: float | None = TIME_LIMIT
    isolate: bool = False


def identify_batch(
    scaffold: Scaffold,
    labels_2d: ArrayLike,
    options: NamerOptions | None = None,
    seed: int = 0,
    progress: bool | None = None,
    *,
    cache: KeyCache | None = None,
    label_values: ArrayLike | None = None,
) -> pd.DataFrame:
    """Identify many designs of one scaffold: a ``pandas.DataFrame``, one row per design.

    Designs are keyed by invariants computed from their labels alone and named once per
    key (:mod:`lkspace.knots.keyed`): no geometry is realized.

    Parameters
    ----------
    scaffold : Scaffold
        A finite scaffold (periodic ones are refused before any work).
    labels_2d : (n_designs, n_edges) int
    options : NamerOptions, optional
        Worker processes, time limit per design named in full (default 60 s) and
        isolation (default: one process, no isolation).
    seed : int
        Seed of the generic projection.
    progress : bool, optional
        Count the designs on the progress display (:mod:`lkspace.runtime.progress`; default on).
    cache : KeyCache, optional
        Names found by earlier calls (default: none); :func:`~lkspace.knots.key_names.disk_cache`
        holds the keys judged by earlier runs, kept under ``$LKSPACE_CACHE``.
    label_values : array of int, optional
        Twists the designs take (the label set); designs keep one diagram template
        across calls when given.

    Returns
    -------
    pandas.DataFrame
        Columns ``knot_name`` (missing when unknown or split), ``components``, ``split``,
        ``mirror``, ``crossings`` (simplified diagram), ``jones``, ``linking_matrix`` (JSON
        text), ``status`` (as :attr:`Identification.status`) and ``error`` (missing unless
        the design could not be identified: open strands, twists too large, time limit,
        diagram too large), in the order of ``labels_2d``.

    Examples
    --------
    >>> from lkspace import load
    >>> identify_batch(load("dihedron:3"), [[1, 1, 1], [1, 0, 0]])["knot_name"].tolist()
    ['3_1', '0_1']
    """
    check_identifiable(scaffold)
    labels_2d = np.asarray(labels_2d, np.int64).reshape(-1, scaffold.n_edges)
    cache = cache if cache is not None else KeyCache()
    rows: list[dict[str, Json]] = []
    opts = options or NamerOptions()
    with (
        Namer(opts.processes, opts.isolate, opts.time_limit) as namer,
        task("identifying", total=len(labels_2d)) as step,
    ):
        for start in range(0, len(labels_2d), BATCH):
            chunk = labels_2d[start : start + BATCH]
            rows.extend(identify_chunk(scaffold, chunk, seed, cache, namer, label_values))
            if progress is not False:
                step.advance(len(chunk))
    return pd.DataFrame(rows, columns=COLUMNS)


def identify_chunk(
    scaffold: Scaffold,
    labels_2d: np.ndarray,
    seed: int,
    cache: KeyCache,
    namer: Namer,
    label_values: ArrayLike | None,
) -> list[dict[str, Json]]:
    """Return the rows of one chunk: refused designs first set apart, the rest keyed and named.

    A row holds :data:`COLUMNS` and, where the design was named, ``pieces``, ``table``,
    ``chiral_name`` and ``candidates`` (as :func:`~lkspace.knots.naming.name_pd` gives them).
    """
    rows: list[dict[str, Json]] = [dict.fromkeys(COLUMNS) for _ in range(len(labels_2d))]
    refusal = _refusal(scaffold)
    estimate = (np.abs(labels_2d) * np.maximum(scaffold.edge_degrees - 1, 0)).sum(axis=1)
    fits = estimate <= MAX_CROSSINGS if refusal is None else np.zeros(len(labels_2d), bool)
    for d in np.flatnonzero(~fits).tolist():
        reason = refusal or (
            f"{scaffold.name}: the twists make about {int(estimate[d]):,} crossings (sum of |t|(K-1) over the edges) "
            f"> {MAX_CROSSINGS:,} (MAX_CROSSINGS): too large to identify; use smaller twists"
        )
        rows[d].update(status=f"unknown: {reason}", error=reason)
    todo = np.flatnonzero(fits)
    if not len(todo):
        return rows
    found = keys_of(scaffold, labels_2d[todo], seed, label_values)

    def name_designs(indices: list[int]) -> list[NameFields]:
        return namer.name([found.diagram(d)[:2] for d in indices])

    for i, (d, fields) in enumerate(zip(todo.tolist(), share_names(found, cache, name_designs), strict=True)):
        assert fields is not None
        rows[d].update(fields.to_json())
        rows[d].update(components=int(found.components[i]), linking_matrix=json.dumps(found.linking_matrix(i)))
    return rows


def _refusal(scaffold: Scaffold) -> str | None:
    """Why no design of ``scaffold`` can be identified (its default null edge-sides open strands), or ``None``."""
    if scaffold.nulls is not None and np.any(scaffold.nulls):
        return f"{scaffold.name}: cannot identify a structure with open strands (null edge-sides)"
    return None


POOL_MIN = 16
"""Fewest designs to name at once that are worth starting worker processes for (a second or two)."""


class Namer:
    """Names designs in full: in this process, or in worker processes started on first need.

    The workers are a :class:`~lkspace.runtime.pools.WorkerPool`: one that dies is
    reported (:class:`~lkspace.runtime.pools.WorkerLost`), never waited for.
    """

    def __init__(self, processes: int, isolate: bool, time_limit: float | None) -> None:
        self.processes, self.isolate, self.time_limit = processes, isolate, time_limit
        self.workers: contextlib.ExitStack | None = None
        self.pool: WorkerPool | None = None

    def __enter__(self) -> Namer:
        _init_worker(self.time_limit)
        return self

    def within(self, seconds: float) -> None:
        """Name with at most ``seconds`` (> 0) per design from now on, in this process (workers keep their limit)."""
        _init_worker(seconds if self.time_limit is None else min(self.time_limit, seconds))

    def name(self, items: list[tuple[list[list[int]], int]]) -> list[NameFields]:
        """Row fields of each ``(pd, n_components)``, in order (the knot libraries load on first need)."""
        if not items:
            return []
        knot_modules()
        tables()  # loaded here (workers load their own)
        if self.isolate or (self.processes > 1 and len(items) >= POOL_MIN):
            size = max(1, min(16, len(items) // (4 * max(self.processes, 1)) or 1))
            chunks = [items[i : i + size] for i in range(0, len(items), size)]
            return [fields for chunk in self._pool().ordered(_name_chunk, chunks) for fields in chunk]
        return [_name_fields(item) for item in items]

    def _pool(self) -> WorkerPool:
        """Return the workers, started on first need."""
        if self.pool is None:
            self.workers = contextlib.ExitStack()
            self.pool = self.workers.enter_context(
                worker_pool(max(self.processes, 1), _init_worker, (self.time_limit,))
            )
        return self.pool

    def __exit__(self, *exc: Any) -> None:
        """Shut the workers down; on Ctrl-C or an error, kill them now (not after their queue)."""
        if self.workers is not None:
            self.workers.__exit__(*exc)
