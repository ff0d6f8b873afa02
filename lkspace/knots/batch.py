"""Identifying many designs of one scaffold: keyed by invariants, named once per key.

:func:`identify_batch` sets apart the designs that cannot be identified (open strands,
twists too large), keys the rest in compiled code (:mod:`lkspace.knots.keyed`), and names
in full, in worker processes under the time limit, only what the keys leave
(:mod:`lkspace.knots.key_names`).
"""

from __future__ import annotations

import contextlib
import json
from collections.abc import Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from ..model.scaffold import Scaffold
from ..runtime.pools import WorkerPool, worker_pool
from ..runtime.progress import task
from .budget import MAX_CROSSINGS, TIME_LIMIT, TimeLimitReached
from .identification import Json, NameFields
from .key_names import KeyCache, share_names
from .keyed import DesignKeys, keys_of
from .keys_ahead import KeysAhead
from .naming import name_in_time, presimplified, status_of
from .recognition import check_identifiable
from .tables import knot_modules, regina_module, tables

if TYPE_CHECKING:
    import pandas as pd

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

BATCH = 4096
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
    by_key : bool
        Name by key only, never in full (:func:`~lkspace.knots.key_names.share_names`):
        a design whose invariants match no table type is filed ``unknown: not in the
        tables ...``, one that table types share lists them; for spaces too big to name.
    """

    processes: int = 1
    time_limit: float | None = TIME_LIMIT
    isolate: bool = False
    by_key: bool = False


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
    import pandas as pd

    chunks = name_batch(scaffold, labels_2d, options, seed, progress, cache=cache, label_values=label_values)
    return pd.DataFrame({c: [v for chunk in chunks for v in chunk.column(c)] for c in COLUMNS}, columns=COLUMNS)


def name_batch(
    scaffold: Scaffold,
    labels_2d: ArrayLike,
    options: NamerOptions | None = None,
    seed: int = 0,
    progress: bool | None = None,
    *,
    cache: KeyCache | None = None,
    label_values: ArrayLike | None = None,
) -> list[ChunkNames]:
    """:func:`identify_batch`'s names as they are found: one :class:`ChunkNames` per :data:`BATCH` designs."""
    labels_2d = np.asarray(labels_2d, np.int64).reshape(-1, scaffold.n_edges)
    chunks: list[ChunkNames] = []
    with task("identifying", total=len(labels_2d)) as step:
        for names in iter_names(scaffold, labels_2d, options, seed, cache=cache, label_values=label_values):
            chunks.append(names)
            if progress is not False:
                step.advance(len(names))
    return chunks


def iter_names(
    scaffold: Scaffold,
    labels_2d: np.ndarray,
    options: NamerOptions | None = None,
    seed: int = 0,
    *,
    cache: KeyCache | None = None,
    label_values: ArrayLike | None = None,
    namer: Namer | None = None,
) -> Iterator[ChunkNames]:
    """Yield the names of ``labels_2d`` ``(n, n_edges)`` chunk by chunk (:data:`BATCH` designs).

    Each chunk's keys are computed while the one before is named
    (:class:`~lkspace.knots.keys_ahead.KeysAhead`).  ``namer``: one already open (its
    workers kept across calls), else one for this call made from ``options``.
    """
    check_identifiable(scaffold)
    cache = cache if cache is not None else KeyCache()
    opts = options or NamerOptions()
    chunks = [labels_2d[start : start + BATCH] for start in range(0, len(labels_2d), BATCH)]
    fits = [keyable(scaffold, chunk) for chunk in chunks]
    with contextlib.ExitStack() as stack:
        if namer is None:
            namer = stack.enter_context(Namer(opts.processes, opts.isolate, opts.time_limit))
        ahead = stack.enter_context(KeysAhead(scaffold, seed, label_values))
        if chunks:
            ahead.submit(chunks[0][fits[0]])
            if len(chunks) > 1:
                regina_module()  # imported (0.09 s) while the first chunk is keyed: a whole space has designs to simplify
        for i, chunk in enumerate(chunks):
            found = ahead.result()
            if i + 1 < len(chunks):
                ahead.submit(chunks[i + 1][fits[i + 1]])
            yield names_of_chunk(scaffold, chunk, fits[i], found, cache, namer, opts.by_key)


@dataclass(frozen=True)
class ChunkNames:
    """Names of a chunk of designs, shared: design ``d`` takes the fields ``fields[which[d]]``.

    Attributes
    ----------
    fields : list of NameFields
        The distinct row fields of the chunk (designs of one trusted key share one).
    which : (n,) int64
        Each design's entry of ``fields``.
    components : (n,) int64
        Each design's number of components; ``-1`` where it was refused before keying.
    linking : (n,) object
        Each design's linking matrix as JSON text; ``None`` where refused.
    """

    fields: list[NameFields]
    which: np.ndarray
    components: np.ndarray
    linking: np.ndarray

    def __len__(self) -> int:
        return len(self.which)

    def values(self, key: str) -> list[Json]:
        """Return the values of one :class:`NameFields` key, one per entry of :attr:`fields` (tuples as lists)."""
        values = [getattr(f, key) for f in self.fields]  # to_json()'s values, without building each dict
        return [list(v) if isinstance(v, tuple) else v for v in values]

    def column(self, key: str) -> list[Json]:
        """One value per design: a :class:`NameFields` key, ``components`` or ``linking_matrix``."""
        if key == "components":
            return [None if c < 0 else c for c in self.components.tolist()]
        if key == "linking_matrix":
            return self.linking.tolist()
        values = self.values(key)
        return [values[i] for i in self.which.tolist()]

    def rows(self) -> list[dict[str, Json]]:
        """One dict per design: :data:`COLUMNS` and the naming's ``pieces``, ``table``, ``chiral_name``, ``candidates``."""
        shared = [f.to_json() for f in self.fields]
        return [
            {**shared[i], "components": None if c < 0 else c, "linking_matrix": lm}
            for i, c, lm in zip(self.which.tolist(), self.components.tolist(), self.linking.tolist(), strict=True)
        ]


def identify_chunk(
    scaffold: Scaffold,
    labels_2d: np.ndarray,
    seed: int,
    cache: KeyCache,
    namer: Namer,
    label_values: ArrayLike | None,
    by_key: bool = False,
) -> ChunkNames:
    """Return the names of one chunk: refused designs set apart, the rest keyed and named by key (only, with ``by_key``)."""
    fits = keyable(scaffold, labels_2d)
    found = keys_of(scaffold, labels_2d[fits], seed, label_values)
    return names_of_chunk(scaffold, labels_2d, fits, found, cache, namer, by_key)


def keyable(scaffold: Scaffold, labels_2d: np.ndarray) -> np.ndarray:
    """Return ``(n,) bool``: the designs of ``labels_2d`` to key (the others are refused by :func:`names_of_chunk`)."""
    if _refusal(scaffold) is not None:
        return np.zeros(len(labels_2d), bool)
    return _estimate(scaffold, labels_2d) <= MAX_CROSSINGS


def _estimate(scaffold: Scaffold, labels_2d: np.ndarray) -> np.ndarray:
    """Return ``(n,) int64``: each design's crossings before simplification, about (sum of |t|(K-1) over the edges)."""
    return (np.abs(labels_2d) * np.maximum(scaffold.edge_degrees - 1, 0)).sum(axis=1)


def names_of_chunk(
    scaffold: Scaffold,
    labels_2d: np.ndarray,
    fits: np.ndarray,
    found: DesignKeys,
    cache: KeyCache,
    namer: Namer,
    by_key: bool,
) -> ChunkNames:
    """Return the names of one chunk whose designs ``fits`` (:func:`keyable`) have the keys ``found``."""
    n = len(labels_2d)
    fields: list[NameFields] = []
    which = np.zeros(n, np.int64)
    components = np.full(n, -1, np.int64)
    linking = np.full(n, None, dtype=object)
    refusal = _refusal(scaffold)
    estimate = _estimate(scaffold, labels_2d)
    for d in np.flatnonzero(~fits).tolist():
        reason = refusal or (
            f"{scaffold.name}: the twists make about {int(estimate[d]):,} crossings (sum of |t|(K-1) over the edges) "
            f"> {MAX_CROSSINGS:,} (MAX_CROSSINGS): too large to identify; use smaller twists"
        )
        which[d] = len(fields)
        fields.append(NameFields(status=f"unknown: {reason}", error=reason))
    todo = np.flatnonzero(fits)
    if len(todo):

        def name_designs(indices: list[int]) -> Iterator[NameFields]:
            return namer.name([found.diagram(d)[:2] for d in indices])

        shared = share_names(found, cache, name_designs, by_key)
        index: dict[int, int] = {}
        for f in shared:
            assert f is not None
            if id(f) not in index:
                index[id(f)] = len(fields)
                fields.append(f)
        which[todo] = [index[id(f)] for f in shared]
        components[todo] = found.components
        linking[todo] = linking_texts(found)
    return ChunkNames(fields, which, components, linking)


def linking_texts(found: DesignKeys) -> np.ndarray:
    """``(n,) object``: each design's linking matrix as JSON text (``[[0, 1], [1, 0]]``), one ``json.dumps`` per distinct matrix."""
    out = np.empty(len(found.components), dtype=object)
    sizes = found.components.astype(np.int64)
    for c in np.unique(sizes).tolist():
        rows = np.flatnonzero(sizes == c)
        starts = found.link_offsets[rows]
        matrices = found.link_values[starts[:, None] + np.arange(c * c)[None, :]]
        distinct, inverse = np.unique(matrices.reshape(len(rows), c * c), axis=0, return_inverse=True)
        texts = np.array([json.dumps(m.reshape(c, c).tolist()) for m in distinct], dtype=object)
        out[rows] = texts[inverse.reshape(-1)]
    return out


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

    def name(self, items: list[tuple[list[list[int]], int]]) -> Iterator[NameFields]:
        """Yield the row fields of each ``(pd, n_components)``, in order, as each is named (knot libraries load on first need)."""
        if not items:
            return
        knot_modules()
        tables()  # loaded here (workers load their own)
        with task("naming new keys in full", total=len(items)) as step:
            if self.isolate or (self.processes > 1 and len(items) >= POOL_MIN):
                size = max(1, min(16, len(items) // (4 * max(self.processes, 1)) or 1))
                chunks = [items[i : i + size] for i in range(0, len(items), size)]
                for named in self._pool().ordered(_name_chunk, chunks):
                    yield from named
                    step.advance(len(named))
            else:
                for item in items:
                    yield _name_fields(item)
                    step.advance()

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
