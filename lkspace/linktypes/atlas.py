"""The atlas of a design space: every knot and link type it realizes (``lkspace atlas``).

Every design (one per orbit of the rotation group: rotations keep the type and the
chirality) is identified by invariant key (:func:`lkspace.knots.batch.identify_chunk`:
diagrams from labels, one full naming per distinct key, in ``processes`` worker
processes; the keys judged are kept on disk, :func:`lkspace.knots.key_names.disk_cache`),
in the order of :class:`~lkspace.linktypes.candidates.OrderedWalk`.
Designs are grouped by **type**: the name (``3_1``; both mirror images together, counted
apart in ``chirality``), ``split: 0_1 + 3_1`` for a split link with named pieces, or
``unknown (N components)``.  Per type: designs, assignments (the orbit sizes summed),
the **simplest design** (smallest ``sum |t|``, then fewest non-zero labels, then
smallest largest ``|t|``) and the table that named it.

A design that differs from one already identified only on edges of degree 1 takes its
type without a second identification (:func:`~lkspace.linktypes.screen.type_labels`).

Resumable: each identified design is appended to ``cache.jsonl`` in the output folder
(one JSON line, flushed at once; a torn last line is ignored), headed by a line naming
the space; a rerun reads it and identifies only the rest.  A catalog written by
``enumerate --identify`` is summed from its ``knot_name`` column without identifying
(:mod:`~lkspace.linktypes.atlas_catalog`).
"""

from __future__ import annotations

import json
import os
import re
import time
from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal, TextIO, TypeAlias

import numpy as np

from ..errors import CatalogError, TooLargeError, UsageError
from ..model.scaffold import Scaffold
from ..runtime.progress import task
from .candidates import OrderedWalk
from .examples import Examples, costs
from .fields import JsonObject
from .records import AtlasResult, AtlasRun, AtlasType, ChiralityCounts, DesignRecord
from .screen import type_labels

if TYPE_CHECKING:
    from ..knots.batch import ChunkNames, Namer
    from ..knots.key_names import KeyCache

CACHE = "cache.jsonl"

PARTIAL_BATCH = 16
"""Designs identified between two looks at the clock when the atlas has a deadline (``stop_after``)."""

Source: TypeAlias = Literal["cache", "identified", "reused", "skipped", "unwalked"]
"""Where an atlas took a design's record from (``skipped``, ``unwalked``: nowhere, past the deadline)."""

MAX_DESIGNS = 20_000_000
"""Largest design space an atlas walks to its end; a bigger one needs ``stop_after`` (``--stop-after``)."""


def type_key(ident: dict[str, Any]) -> str:
    """Return the atlas type of an identification: its name, ``split: A + B`` or ``unknown (N components)``."""
    if ident.get("name"):
        return str(ident["name"])
    pieces = ident.get("pieces")
    if ident.get("split") and pieces and all(pieces):
        return "split: " + " + ".join(sorted(pieces))
    return f"unknown ({ident.get('components')} components)"


def record_of(row: dict[str, Any]) -> DesignRecord:
    """Return the few fields the atlas keeps of a row of :func:`~lkspace.knots.batch.identify_chunk`."""
    ident = {"name": row.get("knot_name"), **row}
    components, mirror, crossings = row.get("components"), row.get("mirror"), row.get("crossings")
    return DesignRecord(
        type=type_key(ident),
        components=None if components is None else int(components),
        table=row.get("table"),
        mirror=None if mirror is None else bool(mirror),
        crossings=None if crossings is None else int(crossings),
        status=row.get("status"),
    )


def records_of(chunk: ChunkNames) -> list[DesignRecord]:
    """:func:`record_of` each design of ``chunk``, made once per distinct fields and number of components."""
    shared = [f.to_json() for f in chunk.fields]
    made: dict[tuple[int, int], DesignRecord] = {}
    out = []
    for i, c in zip(chunk.which.tolist(), chunk.components.tolist(), strict=True):
        if (i, c) not in made:
            made[i, c] = record_of({**shared[i], "components": None if c < 0 else c})
        out.append(made[i, c])
    return out


@dataclass
class TypeEntry:
    """One type of the atlas."""

    name: str
    components: int | None
    table: str | None = None
    crossings: int | None = None
    designs: int = 0
    assignments: int = 0
    simplest: list[int] = field(default_factory=list)
    cost: tuple[int, int, int] = (1 << 62, 0, 0)
    chirality: dict[str, int] = field(default_factory=lambda: {"table": 0, "mirror": 0, "undetermined": 0})
    examples: Examples = field(default_factory=Examples)

    def add(self, labels: np.ndarray, orbit: int, rec: DesignRecord, cost: tuple[int, int, int]) -> None:
        """Count one design of this type (``cost``: its :func:`~lkspace.linktypes.examples.costs` entry)."""
        self.designs += 1
        self.assignments += int(orbit)
        if cost < self.cost:
            self.cost, self.simplest = cost, [int(x) for x in labels]
        self.examples.add(labels, cost, rec)
        crossings = rec.crossings
        if crossings is not None and (self.crossings is None or crossings < self.crossings):
            self.crossings = crossings
        self.table = self.table or rec.table
        self.chirality["undetermined" if rec.mirror is None else "mirror" if rec.mirror else "table"] += 1

    def record(self) -> AtlasType:
        """Return the type as the atlas reports it (``examples``: the simplest designs of each chirality)."""
        return AtlasType(
            name=self.name,
            components=self.components,
            table=self.table,
            crossings=self.crossings,
            designs=self.designs,
            assignments=self.assignments,
            simplest=tuple(self.simplest),
            simplest_sum_abs=self.cost[0],
            simplest_nonzero=self.cost[1],
            chirality=ChiralityCounts(**self.chirality),
            examples=self.examples.records(),
        )


UNNAMED = ("unknown", "split", "not in the tables")
"""How the atlas types without a name begin (``unknown (2 components)``, ``split: 0_1 + 3_1``, ...)."""


def is_named(type_name: str) -> bool:
    """Whether an atlas type is a name (``3_1``, ``L2a1#L4a1``), not a group of unnamed designs (:data:`UNNAMED`)."""
    return not type_name.startswith(UNNAMED)


def sort_types(types: dict[str, TypeEntry]) -> list[TypeEntry]:
    """Return the types by components, then named before the rest, then crossing number and name."""
    return sorted(
        types.values(), key=lambda t: (t.components or 0, not is_named(t.name), crossing_number(t.name), t.name)
    )


def crossing_number(name: str) -> int:
    """Return the crossing number a name states (``3_1``: 3, ``L6a4``: 6, ``11a_1``: 11, ``3_1#4_1``: 7; else 0).

    For a sum it is the sum of the factors' (additivity is proved for alternating
    factors, conjectured in general): a sort key, not a bound.
    """
    total = 0
    for part in name.split("#"):
        m = re.match(r"m?[KL]?(\d+)", part)
        total += int(m[1]) if m else 0
    return total


def read_cache(path: str, header: JsonObject) -> dict[tuple[int, ...], DesignRecord]:
    """Return the records of a previous run (``{labels: record}``); empty if none or if it was for another space."""
    if not os.path.exists(path):
        return {}
    out: dict[tuple[int, ...], DesignRecord] = {}
    with open(path, encoding="utf-8") as fh:
        first = fh.readline()
        try:
            if json.loads(first) != header:
                return {}
        except json.JSONDecodeError:
            return {}
        for line in fh:
            try:
                item = json.loads(line)
                out[tuple(item["labels"])] = DesignRecord.from_json(item["record"])
            except (json.JSONDecodeError, KeyError, TypeError, CatalogError):
                continue  # a line torn by an interrupted run
    return out


@dataclass(frozen=True)
class AtlasOptions:
    """How :func:`atlas` walks and identifies a space (every field optional).

    Attributes
    ----------
    no_zero : bool
        Leave label 0 out of the space.
    processes : int
        Worker processes identifying (>= 1).
    seed : int
        Projection seed.
    time_limit : float or None
        Seconds per identification (past it: an unknown type); ``None``: no limit.
    stop_after : float or None
        Seconds after which nothing more is identified (``None``: identify every design).
    tolerance : float or None
        The symmetry search's, in mesh units (default: 1/100 of the shortest edge).
    """

    no_zero: bool = False
    processes: int = 1
    seed: int = 0
    time_limit: float | None = 60.0
    stop_after: float | None = None
    tolerance: float | None = None

    def __post_init__(self) -> None:
        if self.processes < 1:
            raise UsageError(f"processes {self.processes}: at least 1", parameter="processes")


def atlas(
    scaffold: Scaffold, label_set: np.ndarray, folder: str | None = None, options: AtlasOptions = AtlasOptions()
) -> AtlasResult:
    """Identify every design of the space; return its types (``to_json()``: ``{"types": [...], "designs": n, ...}``).

    ``folder``: keep the resumable cache there (``cache.jsonl``).  ``options.stop_after``:
    seconds after which nothing more is identified; the answer then covers the designs
    identified so far (the simplest ones: the walk goes simplest first), ``complete`` is
    false and ``skipped`` counts the designs walked but not identified (the walk itself
    stops at the deadline too, so there may be more).  A rerun with the same folder continues.

    Examples
    --------
    >>> from lkspace import load
    >>> out = atlas(load("dihedron:3"), np.array([0, 1]))
    >>> [(t.name, t.designs, t.simplest) for t in out.types]
    [('0_1', 1, (0, 0, 1)), ('3_1', 1, (1, 1, 1)), ('L2a1', 1, (0, 1, 1)), ('split: 0_1 + 0_1', 1, (0, 0, 0))]
    """
    t0 = time.monotonic()
    if not options.stop_after:
        _check_size(scaffold, label_set, options.tolerance)
    header: JsonObject = {
        "scaffold": scaffold.name,
        "hash": scaffold.content_hash(),
        "labels": [int(x) for x in label_set],
        "no_zero": options.no_zero,
        "seed": options.seed,
    }
    cache_path = os.path.join(folder, CACHE) if folder else None
    cached = read_cache(cache_path, header) if cache_path else {}
    types: dict[str, TypeEntry] = {}
    how: Counter[str] = Counter()
    sink = _open_cache(cache_path, header, bool(cached)) if cache_path else None
    deadline = None if not options.stop_after else t0 + options.stop_after
    try:
        with task(f"atlas of {scaffold.name}") as step:
            for labels, orbit, source, rec, cost in _records(scaffold, label_set, cached, options, deadline):
                how[source] += 1
                if rec is None:  # skipped or unwalked
                    continue
                if source != "cache" and sink is not None:
                    sink.write(json.dumps({"labels": labels.tolist(), "record": rec.to_json()}) + "\n")
                    sink.flush()
                types.setdefault(rec.type, TypeEntry(rec.type, rec.components)).add(labels, orbit, rec, cost)
                how["designs"] += 1
                if how["designs"] % 1024 == 0:  # a note per design would cost more than the rest of this loop
                    step.note(f"{how['designs']:,} designs, {len(types)} types")
    finally:
        if sink is not None:
            sink.close()
    listed = tuple(t.record() for t in sort_types(types))
    complete = how["skipped"] == 0 and not how["unwalked"]
    wall_time = round(time.monotonic() - t0, 3)
    run = AtlasRun(how["identified"], how["reused"], how["cache"], complete, how["skipped"], wall_time)
    return AtlasResult(
        scaffold.name, tuple(int(x) for x in label_set), how["designs"], sum(t.assignments for t in listed), listed, run
    )


def _check_size(scaffold: Scaffold, label_set: np.ndarray, tolerance: float | None) -> None:
    """Refuse a space too big to walk to its end (:data:`MAX_DESIGNS`)."""
    from ..design.counting import count_designs

    n = count_designs(scaffold, label_set, tolerance=tolerance).designs
    if n > MAX_DESIGNS:
        raise TooLargeError(
            f"{scaffold.name}: {n:,} designs with labels {label_set.tolist()} > {MAX_DESIGNS:,} (MAX_DESIGNS); "
            "an atlas would identify them all: give `stop_after=S` for the simplest ones, or a smaller label set",
        )


def _open_cache(path: str, header: JsonObject, resume: bool) -> TextIO:
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    fh = open(path, "a" if resume else "w", encoding="utf-8")  # noqa: SIM115 - closed by the caller
    if not resume:
        fh.write(json.dumps(header) + "\n")
        fh.flush()
    return fh


def _names(
    scaffold: Scaffold,
    rows: np.ndarray,
    label_set: np.ndarray,
    cache: KeyCache,
    namer: Namer,
    seed: int,
    deadline: float | None,
) -> Iterator[ChunkNames]:
    """Names of ``rows`` chunk by chunk; past ``deadline`` none more (chunks of :data:`PARTIAL_BATCH` then)."""
    from ..knots.batch import identify_chunk, iter_names

    if deadline is None:
        yield from iter_names(scaffold, rows, None, seed, cache=cache, label_values=label_set, namer=namer)
        return
    for start in range(0, len(rows), PARTIAL_BATCH):
        if time.monotonic() > deadline:
            return
        yield identify_chunk(scaffold, rows[start : start + PARTIAL_BATCH], seed, cache, namer, label_set)


def _records(
    scaffold: Scaffold,
    label_set: np.ndarray,
    cached: dict[tuple[int, ...], DesignRecord],
    options: AtlasOptions,
    deadline: float | None,
) -> Iterator[tuple[np.ndarray, int, Source, DesignRecord | None, tuple[int, int, int]]]:
    """``(labels, orbit size, source, record, cost)`` of every design; ``source`` says where the record came from.

    ``"cache"`` (a previous run), ``"identified"`` (identified now) or ``"reused"``: a design
    that differs from one identified before only on edges of degree 1 has its type
    (:func:`~lkspace.linktypes.screen.type_labels`).  Past ``deadline`` (``time.monotonic()``)
    nothing more is identified: the rest is ``"skipped"`` (still counted).
    """
    from ..knots.batch import Namer
    from ..knots.key_names import disk_cache

    cache = disk_cache()
    known: dict[tuple[int, ...], DesignRecord] = {}  # by type labels; kept only where edges of degree 1 make families
    families = bool(np.any(np.asarray(scaffold.edge_degrees) == 1))
    walk = OrderedWalk(
        scaffold, label_set, None, no_zero=options.no_zero, deadline=deadline, tolerance=options.tolerance
    )
    with Namer(options.processes, False, options.time_limit) as namer:
        for batch in walk:
            labels64 = batch.labels.astype(np.int64)
            cost_of = costs(labels64)
            orbits = batch.orbit_sizes.tolist()
            keys = [tuple(r) for r in batch.labels.tolist()]
            zkeys = [tuple(r) for r in type_labels(scaffold, batch.labels).tolist()]
            for k, z in zip(keys, zkeys, strict=True):
                if k in cached and families:
                    known.setdefault(z, cached[k])
            todo = list(
                dict.fromkeys(z for k, z in zip(keys, zkeys, strict=True) if k not in cached and z not in known)
            )
            rows = np.array(todo, np.int64).reshape(len(todo), scaffold.n_edges)
            fresh: list[DesignRecord] = []
            for chunk in _names(scaffold, rows, label_set, cache, namer, options.seed, deadline):
                fresh.extend(records_of(chunk))
            made = iter(fresh)
            for i, (k, z) in enumerate(zip(keys, zkeys, strict=True)):
                source: Source
                rec: DesignRecord | None
                if k in cached:
                    source, rec = "cache", cached[k]
                elif z in known:
                    source, rec = "reused", known[z]
                else:  # the first design of its family: the next identification, in order
                    rec = next(made, None)
                    source = "skipped" if rec is None else "identified"
                    if rec is not None and families:
                        known[z] = rec
                yield labels64[i], orbits[i], source, rec, cost_of[i]
    if not walk.complete:
        yield np.zeros(0, np.int64), 0, "unwalked", None, (0, 0, 0)
