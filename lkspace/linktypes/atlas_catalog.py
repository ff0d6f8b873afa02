"""The atlas of a catalog that ``enumerate --identify`` wrote: its ``knot_name`` column summed into types.

The catalog streams by a record batch at a time (:func:`~lkspace.catalog.reader.catalog_batches`,
only the columns the sums need); each batch is summed with numpy into running per-type
arrays, and only each type's few simplest designs of each chirality are carried from
batch to batch.  Memory grows with the number of types, not of rows: the cube's -2..2
space (10 million rows) sums in a few hundred megabytes.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import pyarrow as pa
import pyarrow.compute as pc
import pyarrow.parquet as pq

from ..catalog.reader import LABEL_COLUMNS, catalog_batches, reread
from ..catalog.schema import ROW_GROUP
from ..catalog.settings import catalog_scaffold
from ..catalog.verify import open_catalog
from ..errors import CatalogError
from ..knots.key_names import NOT_IN_TABLES
from .atlas import TypeEntry, sort_types
from .examples import EXAMPLES
from .records import AtlasResult, DesignRecord

SIDES = ("table", "mirror", "undetermined")
"""Chiralities by their code in the sums (``mirror`` column: false, true, null)."""

FALLBACKS = ("split", "not in the tables", "unknown")
"""What an unnamed row is grouped as, by code: split, named by key only and no table type, the rest."""

COLUMNS = ("components", "orbit_size", "knot_name", "crossings", "mirror", "split", "identify_status")
"""The catalog columns the sums read (``key`` or ``labels`` besides); the last four where the catalog has them."""

NO_CROSSINGS = np.iinfo(np.int64).max
"""A type's crossings while none of its designs has any."""


def atlas_of_catalog(path: str, batch_rows: int = ROW_GROUP) -> AtlasResult:
    """Sum a catalog identified by ``enumerate --identify`` (its ``knot_name`` column) into atlas types.

    Rows without a name are grouped as ``split (N components)``, ``not in the tables (N
    components)`` (named by key only: no table type has their invariants) or ``unknown (N
    components)``; a type's ``crossings`` is the fewest its designs' simplified diagrams
    keep; its examples are the few simplest designs of each chirality (ties: the earlier
    row).  ``batch_rows``: rows summed at a time (memory, not the answer, depends on it).
    """
    return reread(path, lambda: _atlas(path, batch_rows))


def _atlas(path: str, batch_rows: int) -> AtlasResult:
    parts = open_catalog(path)
    names = pq.read_schema(parts.files[0]).names
    if "knot_name" not in names:
        for _ in catalog_batches(parts, [n for n in names if n not in LABEL_COLUMNS], batch_rows):
            pass  # a damaged catalog is refused as such first (parts' SHA-256, pages' checksums)
        raise CatalogError(
            f"{path}: no knot_name column: its designs are not named; write it with `identify=True`, or give a mesh"
        )
    scaffold = catalog_scaffold(parts.footer, path)
    sums = Sums()
    for batch, labels in catalog_batches(parts, [c for c in COLUMNS if c in names], batch_rows):
        sums.add(batch, labels)
    listed = tuple(t.record() for t in sort_types(sums.entries()))
    return AtlasResult(
        scaffold.name,
        parts.footer.settings.label_set,
        sums.rows,
        sum(t.assignments for t in listed),
        listed,
        from_catalog=os.path.abspath(path),
    )


def _flags(batch: pa.RecordBatch, column: str, test: Callable[[pa.Array, bool], pa.Array]) -> np.ndarray:
    """``(n_rows,) bool``: ``test(column, False)`` of ``batch``'s ``column`` (nulls false); all false without one."""
    if column not in batch.schema.names:
        return np.zeros(batch.num_rows, bool)
    return np.asarray(test(batch.column(column), False), bool)


@dataclass
class Batch:
    """One batch's rows as the sums see them, each array ``(n_rows,)``."""

    types: np.ndarray  # int64: the type number (:attr:`Sums.names`)
    sides: np.ndarray  # int64: the chirality (:data:`SIDES`)
    components: np.ndarray  # int64
    orbits: np.ndarray  # int64
    crossings: np.ndarray  # int64, -1 where the row has none


@dataclass
class Sums:
    """Running sums by type of the batches seen so far, and each type's simplest rows of each chirality.

    ``best`` holds up to :data:`~lkspace.linktypes.examples.EXAMPLES` rows per (type,
    chirality): the smallest by (sum |t|, non-zero labels, largest |t|, row), as columns
    ``group`` (type × 3 + chirality), ``sum_abs``, ``nonzero``, ``max_abs``, ``row``,
    ``crossings`` (-1: none) and ``labels`` (``(n, n_edges) int8``).
    """

    names: dict[str, int] = field(default_factory=dict)
    components: list[int] = field(default_factory=list)
    designs: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    assignments: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    crossings: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    sides: np.ndarray = field(default_factory=lambda: np.zeros((0, len(SIDES)), np.int64))
    best: dict[str, np.ndarray] = field(default_factory=dict)
    rows: int = 0

    def add(self, batch: pa.RecordBatch, labels: np.ndarray) -> None:
        """Sum one batch of rows (``labels``: their ``(n_rows, n_edges) int8`` twist labels)."""
        rows = self.classify(batch)
        n = len(self.names)
        grow = n - len(self.designs)
        self.designs = np.concatenate([self.designs, np.zeros(grow, np.int64)])
        self.assignments = np.concatenate([self.assignments, np.zeros(grow, np.int64)])
        self.crossings = np.concatenate([self.crossings, np.full(grow, NO_CROSSINGS)])
        self.sides = np.concatenate([self.sides, np.zeros((grow, len(SIDES)), np.int64)])
        np.add.at(self.designs, rows.types, 1)
        np.add.at(self.assignments, rows.types, rows.orbits)
        np.add.at(self.sides, (rows.types, rows.sides), 1)
        known = rows.crossings >= 0
        np.minimum.at(self.crossings, rows.types[known], rows.crossings[known])
        new = np.flatnonzero(rows.types >= len(self.components))
        firsts = np.unique(rows.types[new], return_index=True)[1]
        self.components += [int(c) for c in rows.components[new[firsts]]]  # the new types' first rows, by type number
        a = np.abs(labels.astype(np.int64))
        offered = {
            "group": rows.types * len(SIDES) + rows.sides,
            "sum_abs": a.sum(axis=1),
            "nonzero": (a != 0).sum(axis=1),
            "max_abs": a.max(axis=1, initial=0),
            "row": self.rows + np.arange(len(labels), dtype=np.int64),
            "crossings": rows.crossings,
            "labels": labels,
        }
        if self.best:
            offered = {k: np.concatenate([self.best[k], v]) for k, v in offered.items()}
        self.best = simplest(offered, EXAMPLES)
        self.rows += len(labels)

    def classify(self, batch: pa.RecordBatch) -> Batch:
        """Return the type, chirality and counts of each row of ``batch``, numbering the new types."""
        components = batch.column("components").to_numpy().astype(np.int64)
        named = batch.column("knot_name").dictionary_encode()
        first = np.asarray(pc.fill_null(named.indices, -1), np.int64)
        split = _flags(batch, "split", pc.fill_null)
        beyond = _flags(batch, "identify_status", lambda c, f: pc.fill_null(pc.starts_with(c, NOT_IN_TABLES.status), f))
        fallback = np.where(split, 0, np.where(beyond, 1, 2))
        width = int(components.max(initial=0)) + 1
        codes = np.where(first >= 0, first, len(named.dictionary) + fallback * width + components)
        distinct, inverse = np.unique(codes, return_inverse=True)
        numbers = np.empty(len(distinct), np.int64)
        for i, code in enumerate(distinct.tolist()):
            if code < len(named.dictionary):
                key = named.dictionary[code].as_py()
            else:
                f, c = divmod(code - len(named.dictionary), width)
                key = f"{FALLBACKS[f]} ({c} components)"
            numbers[i] = self.names.setdefault(key, len(self.names))
        mirror = batch.column("mirror") if "mirror" in batch.schema.names else None
        if mirror is None:
            sides = np.full(len(first), 2, np.int64)
        else:
            sides = np.where(
                np.asarray(mirror.is_null(), bool), 2, np.asarray(pc.fill_null(mirror, False), bool).astype(np.int64)
            )
        if "crossings" in batch.schema.names:
            crossings = np.asarray(pc.fill_null(batch.column("crossings"), -1), np.int64)
        else:
            crossings = np.full(len(first), -1, np.int64)
        orbits = batch.column("orbit_size").to_numpy().astype(np.int64)
        return Batch(numbers[inverse.ravel()], sides, components, orbits, crossings)

    def entries(self) -> dict[str, TypeEntry]:
        """Return the types summed so far, each with its simplest design and examples."""
        types: dict[str, TypeEntry] = {}
        for name, t in self.names.items():
            entry = TypeEntry(
                name,
                self.components[t],
                crossings=None if self.crossings[t] == NO_CROSSINGS else int(self.crossings[t]),
                designs=int(self.designs[t]),
                assignments=int(self.assignments[t]),
            )
            entry.chirality = {side: int(n) for side, n in zip(SIDES, self.sides[t], strict=True)}
            types[name] = entry
        listing = list(self.names)
        best = self.best
        firsts: dict[int, tuple[tuple[int, int, int], int]] = {}
        for i in range(len(best.get("row", ()))):  # simplest first within each (type, chirality)
            t, side = divmod(int(best["group"][i]), len(SIDES))
            entry = types[listing[t]]
            cost = (int(best["sum_abs"][i]), int(best["nonzero"][i]), int(best["max_abs"][i]))
            labels = best["labels"][i]
            row = int(best["row"][i])
            if t not in firsts or (cost, row) < firsts[t]:  # the simplest: the earliest row among equals
                firsts[t] = (cost, row)
                entry.cost, entry.simplest = cost, [int(x) for x in labels]
            crossings = int(best["crossings"][i])
            mirror = (False, True, None)[side]
            record = DesignRecord(entry.name, entry.components, None, mirror, None if crossings < 0 else crossings)
            entry.examples.add(labels, cost, record)
        return types


def simplest(rows: dict[str, np.ndarray], k: int) -> dict[str, np.ndarray]:
    """Return the first ``k`` rows of each group by (sum |t|, non-zero labels, largest |t|, row), sorted so."""
    order = np.lexsort((rows["row"], rows["max_abs"], rows["nonzero"], rows["sum_abs"], rows["group"]))
    groups = rows["group"][order]
    starts = np.flatnonzero(np.r_[True, groups[1:] != groups[:-1]])
    rank = np.arange(len(order)) - np.repeat(starts, np.diff(np.r_[starts, len(order)]))
    keep = order[rank < k]
    return {name: column[keep] for name, column in rows.items()}
