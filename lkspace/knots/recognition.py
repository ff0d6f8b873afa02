"""Knot and link identification of realized strands (extra ``[knots]``).

Pipeline: :func:`lkspace.geometry.realization.realize` -> :func:`lkspace.knots.diagram.project`
(generic projection, PD code) -> :func:`lkspace.knots.naming.name_pd` (spherogram
``simplify('global')``, then the tables of :mod:`lkspace.knots.tables`) -> names.

Naming.  The Jones polynomial (regina, no Sage) of the simplified diagram, evaluated
exactly at ``sqrt(t) = 2/3`` and ``3/2`` (its mirror), is looked up in the KnotInfo
(knots up to 13 crossings) and LinkInfo (links up to 11 crossings, every orientation)
tables of ``database_knotinfo``.  Candidates are narrowed by the HOMFLY-PT polynomial
(regina, computed on our diagram and on the table's own PD code, so conventions agree)
and by SnapPy's ``identify()`` of the exterior.  A single remaining table entry is
accepted only if the hyperbolic volume agrees (zero for torus and satellite knots and
links, which ``identify()`` cannot name); otherwise ``name`` is ``None`` and the
invariants are returned.  Names: ``"0_1"``, Rolfsen ``"3_1"``..., Thistlethwaite
``"L2a1"``...; ``mirror`` says whether the structure is the table diagram's mirror image
(``None`` when the knot or link equals its mirror as far as HOMFLY-PT tells).
KnotInfo's ``3_1`` is the right-handed (positive) trefoil.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd
from numpy.typing import ArrayLike

from ..errors import LkspaceError, TooLargeError, UsageError
from ..geometry.params import GeometryParams, RealizeOptions
from ..geometry.realization import realize
from ..model.scaffold import Scaffold
from ..progress import Step, task
from ..strands.tracing import trace
from ..workers import context, ignore_interrupts
from .budget import INLINE_CROSSINGS, MAX_CROSSINGS, TIME_LIMIT, TimeLimitReached, run_in_time, twist_crossings
from .diagram import project, project_generic
from .keyed import KeyCache, disk_cache, keys_of, share_names
from .naming import name_pd
from .tables import knot_modules, tables


@dataclass(frozen=True, repr=False)
class Identification:
    """The knot or link type of a closed structure.

    Attributes
    ----------
    components : int
    name : str or None
        ``"0_1"``, Rolfsen (``"3_1"``) or Thistlethwaite (``"L6a4"``) name; ``None`` if unknown.
    linking_matrix : list of list of int
    mirror : bool or None
        The structure is the table diagram's mirror image (``None``: the tables cannot tell).
    split : bool or None
    crossings : int or None
        Crossings of the simplified diagram.
    details : dict
        Everything else: ``jones``, ``homfly``, ``volume``, ``candidates``, ``pieces``, ...
    status : str
        ``"identified"`` (named, or a split link with every piece named) or
        ``"unknown: <why>"``: not in the tables, several entries match, ``diagram too
        large: N crossings > 2000`` or ``time limit 60 s reached (during ...)``.
    """

    components: int
    name: str | None
    linking_matrix: list[list[int]]
    mirror: bool | None = None
    split: bool | None = None
    crossings: int | None = None
    details: dict[str, Any] = field(default_factory=dict)
    status: str = "identified"

    def __repr__(self) -> str:
        chirality = {True: ", mirror", False: "", None: ""}[self.mirror]
        return f"Identification({self.name or 'unknown'}{chirality}: {self.components} components, {self.crossings} crossings)"

    def to_dict(self) -> dict[str, Any]:
        """Return the JSON form (``status``, ``components``, ``name``, ``linking_matrix``, and every invariant)."""
        return {
            "status": self.status,
            "components": self.components,
            "name": self.name,
            "linking_matrix": self.linking_matrix,
            "mirror": self.mirror,
            "split": self.split,
            "crossings": self.crossings,
            **self.details,
        }


def status_of(named: dict[str, Any]) -> str:
    """Return the status of a :func:`~lkspace.knots.naming.name_pd` result: identified or why not."""
    if named.get("name") is not None:
        return "identified"
    pieces = named.get("pieces")
    if named.get("split") and pieces and all(p is not None for p in pieces):
        return "identified"
    if named.get("split"):
        return "unknown: a piece of the split link is not in the tables"
    candidates = named.get("candidates") or []
    if len(candidates) > 1:
        return f"unknown: {len(candidates)} table entries match ({', '.join(candidates[:4])})"
    if named.get("note"):
        return f"unknown: {named['note']}"
    return "unknown: not in the tables (KnotInfo/LinkInfo: knots up to 13 crossings, links up to 11; HTLinkExteriors: hyperbolic knots up to 15, links up to 14)"


def identify_curves(curves: Sequence[np.ndarray], seed: int = 0) -> dict[str, Any]:
    """Identify the link formed by closed polylines ``curves`` (list of ``(n_k, 3)``), without a time limit.

    Returns
    -------
    dict
        ``components``, ``name``, ``linking_matrix``, ``projected_crossings`` and the
        results of :func:`name_pd` (invariants, see the module docstring).
    """
    diagram = project(curves, seed=seed)
    out = {
        "components": len(curves),
        "linking_matrix": diagram.linking_matrix().tolist(),
        "projected_crossings": diagram.n_crossings,
    }
    out.update(name_pd(diagram.pd, len(curves)))
    return out


def check_identifiable(scaffold: Scaffold) -> None:
    """Refuse a periodic scaffold: its strands are infinite structures, not knots or links.

    The loops of one module are not the structure (they link their neighbours), so naming
    them would mislead; ``export --block`` shows a block of the structure instead.
    """
    if scaffold.periodic:
        raise UsageError(
            f"{scaffold.name}: a periodic scaffold; identify names knots and links of finite "
            "scaffolds only (its loops link their lattice translates; use export --block to look at a block)"
        )


def identify(
    scaffold: Scaffold,
    labels: ArrayLike | None = None,
    nulls: ArrayLike | None = None,
    params: GeometryParams | None = None,
    seed: int = 0,
    *,
    time_limit: float | None = TIME_LIMIT,
) -> Identification:
    """Knot or link type of a scaffold labelled by twist ``labels`` (extra ``[knots]``).

    Parameters
    ----------
    scaffold : Scaffold
        A finite scaffold (periodic ones are refused, :func:`check_identifiable`);
        ``lkspace.identify`` also takes a path or a built-in name (:func:`lkspace.load`).
    labels, nulls : as for :func:`lkspace.trace`
    params : GeometryParams, optional
        Realization parameters.
    seed : int
        Seed of the generic projection.
    time_limit : float or None
        Seconds for the whole identification (default
        :data:`~lkspace.knots.budget.TIME_LIMIT`); past it the status is ``unknown: time
        limit ... reached`` with the invariants known so far.  ``None`` or 0: no limit.

    Raises
    ------
    TooLargeError
        When the twists alone would make more than
        :data:`~lkspace.knots.budget.MAX_CROSSINGS` crossings (checked before realizing).

    Examples
    --------
    >>> import lkspace
    >>> lkspace.identify("dihedron:3", 1)
    Identification(3_1: 1 components, 3 crossings)
    """
    t0 = time.monotonic()
    check_identifiable(scaffold)
    with task(f"identifying {scaffold.name}") as step:
        step.note("tracing")
        tr = trace(scaffold, labels, nulls)
        if not tr.closed.all():
            raise LkspaceError(f"{scaffold.name}: cannot identify a structure with open strands (null edge-sides)")
        estimate = twist_crossings(scaffold.edge_degrees, tr.labels)
        if estimate > MAX_CROSSINGS:
            raise TooLargeError(
                f"{scaffold.name}: the twists make about {estimate:,} crossings (sum of |t|(K-1) over the edges) "
                f"> {MAX_CROSSINGS:,} (MAX_CROSSINGS): too large to identify; use smaller twists"
            )
        step.note("realizing")
        # the construction polylines (smoothing off unless asked): isotopic to the smoothed strands, cheaper
        real = realize(
            scaffold, tr.labels, nulls, params or GeometryParams(smooth=False), options=RealizeOptions(trace=tr)
        )
        step.note("diagram")
        diagram = project_generic(real.curves, seed)
        head = {
            "components": len(real.curves),
            "linking_matrix": diagram.linking_matrix().tolist(),
            "projected_crossings": diagram.n_crossings,
        }
        out: dict[str, Any]
        if diagram.n_crossings > MAX_CROSSINGS:
            status = f"unknown: diagram too large: {diagram.n_crossings:,} crossings > {MAX_CROSSINGS:,}"
            out = {**head, "name": None}
        else:
            left = None if not time_limit else max(time_limit - (time.monotonic() - t0), 1e-3)
            try:
                out = {**head, **_name_in_time(diagram.pd, diagram.n_components, left, step)}
                status = status_of(out)
            except TimeLimitReached as exc:
                status = f"unknown: time limit {time_limit:g} s reached (during {exc.stage})"
                out = {**head, "name": None}
    out["min_distance"] = real.min_distance
    main = {k: out.pop(k, None) for k in ("components", "name", "linking_matrix", "mirror", "split", "crossings")}
    return Identification(**main, details=out, status=status)


def _name_in_time(
    pd: list[list[int]], n_components: int, time_limit: float | None, step: Step | None
) -> dict[str, Any]:
    """Name the PD code ``pd`` within ``time_limit`` seconds (:func:`~lkspace.knots.budget.run_in_time`).

    Diagrams of at most :data:`~lkspace.knots.budget.INLINE_CROSSINGS` crossings are
    named in this process: they take milliseconds.
    """
    knot_modules()
    tables()  # loaded here, shared with the forked child

    def work(stage: Callable[[str], None]) -> dict[str, Any]:
        return name_pd(pd, n_components, stage)

    return run_in_time(work, None if len(pd) <= INLINE_CROSSINGS else time_limit, step)


_WORKER: dict[str, Any] = {}


def _init_worker(time_limit: float | None = TIME_LIMIT, worker: bool = False) -> None:
    if worker:
        ignore_interrupts()
    _WORKER.update(time_limit=time_limit)


def _name_fields(item: tuple[list[list[int]], int]) -> dict[str, Any]:
    """Name one design's PD code under the time limit: its row fields but ``components`` and ``linking_matrix``."""
    pd, n_components = item
    time_limit = _WORKER.get("time_limit", TIME_LIMIT)
    if len(pd) > MAX_CROSSINGS:
        status = f"unknown: diagram too large: {len(pd):,} crossings > {MAX_CROSSINGS:,}"
        return {"knot_name": None, "status": status, "error": status.removeprefix("unknown: ")}
    try:
        named = _name_in_time(pd, n_components, time_limit or None, None)
    except TimeLimitReached as exc:
        status = f"unknown: time limit {time_limit:g} s reached (during {exc.stage})"
        return {"knot_name": None, "status": status, "error": status.removeprefix("unknown: ")}
    return {
        "knot_name": named.get("name"),
        "split": named.get("split"),
        "mirror": named.get("mirror"),
        "crossings": named.get("crossings"),
        "jones": named.get("jones"),
        "status": status_of(named),
        "error": None,
    }


COLUMNS = ["knot_name", "components", "split", "mirror", "crossings", "jones", "linking_matrix", "status", "error"]

BATCH = 20_000
"""Designs keyed per call of the compiled kernel (bounds the memory of one call)."""


def identify_batch(
    scaffold: Scaffold,
    labels_2d: ArrayLike,
    processes: int = 1,
    seed: int = 0,
    progress: bool | None = None,
    *,
    time_limit: float | None = TIME_LIMIT,
    isolate: bool = False,
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
    processes : int
        Worker processes naming the designs named in full (``1``: in this process).
        Workers are started by :func:`lkspace.workers.context` (never a fork of this
        program).
    seed : int
        Seed of the generic projection.
    progress : bool, optional
        Count the designs on the progress display (:mod:`lkspace.progress`; default on).
    time_limit : float or None
        Seconds per design named in full, as for :func:`identify` (default 60); a
        design that runs out gets the status ``unknown: time limit ...`` and the same
        text in ``error``.
    isolate : bool
        Name in worker processes even when ``processes`` is 1.  For callers that run
        in a thread other than the main one (a Dask task): SnapPy's PARI works only in a
        process's main thread, and a thread would leave exteriors undecided.
    cache : KeyCache, optional
        Names found by earlier calls (default: :func:`~lkspace.knots.keyed.disk_cache`,
        the keys trusted by earlier runs, kept under ``$LKSPACE_CACHE``).
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
    cache = cache if cache is not None else disk_cache()
    rows: list[dict[str, Any]] = []
    with _Namer(processes, isolate, time_limit) as namer, task("identifying", total=len(labels_2d)) as step:
        for start in range(0, len(labels_2d), BATCH):
            chunk = labels_2d[start : start + BATCH]
            rows.extend(_identify_chunk(scaffold, chunk, seed, cache, namer, label_values))
            if progress is not False:
                step.advance(len(chunk))
    return pd.DataFrame(rows, columns=COLUMNS)


def _identify_chunk(
    scaffold: Scaffold,
    labels_2d: np.ndarray,
    seed: int,
    cache: KeyCache,
    namer: _Namer,
    label_values: ArrayLike | None,
) -> list[dict[str, Any]]:
    """The rows of one chunk: refused designs first set apart, the rest keyed and named."""
    rows: list[dict[str, Any]] = [dict.fromkeys(COLUMNS) for _ in range(len(labels_2d))]
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

    def name_designs(indices: list[int]) -> list[dict[str, Any]]:
        return namer.name([found.diagram(d)[:2] for d in indices])

    for i, (d, fields) in enumerate(zip(todo.tolist(), share_names(found, cache, name_designs), strict=True)):
        assert fields is not None
        rows[d].update(fields, components=int(found.components[i]), linking_matrix=json.dumps(found.linking_matrix(i)))
    return rows


def _refusal(scaffold: Scaffold) -> str | None:
    """Why no design of ``scaffold`` can be identified (its default null edge-sides open strands), or ``None``."""
    if scaffold.nulls is not None and np.any(scaffold.nulls):
        return f"{scaffold.name}: cannot identify a structure with open strands (null edge-sides)"
    return None


class _Namer:
    """Names designs in full: in this process, or in worker processes started on first need."""

    def __init__(self, processes: int, isolate: bool, time_limit: float | None) -> None:
        self.processes, self.isolate, self.time_limit = processes, isolate, time_limit
        self.pool: Any = None

    def __enter__(self) -> _Namer:
        _init_worker(self.time_limit)
        return self

    def name(self, items: list[tuple[list[list[int]], int]]) -> list[dict[str, Any]]:
        """Row fields of each ``(pd, n_components)``, in order (the knot libraries load on first need)."""
        if not items:
            return []
        knot_modules()
        tables()  # loaded here (workers load their own)
        if self.processes > 1 or self.isolate:
            if self.pool is None:
                self.pool = context().Pool(
                    max(self.processes, 1), initializer=_init_worker, initargs=(self.time_limit, True)
                )
            chunk = max(1, min(16, len(items) // (4 * max(self.processes, 1)) or 1))
            return list(self.pool.imap(_name_fields, items, chunksize=chunk))
        return [_name_fields(item) for item in items]

    def __exit__(self, kind: object, *exc: object) -> None:
        if self.pool is not None:
            if kind is not None:  # Ctrl-C or an error: stop the workers now, not after their queue
                self.pool.terminate()
            self.pool.close()
            self.pool.join()
