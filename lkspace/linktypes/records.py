"""The atlas payloads that cross a boundary, one frozen record each (answers: :mod:`~lkspace.linktypes.answers`).

======================  ==========================================  ==============================
record                  travels as                                  read and written by
======================  ==========================================  ==============================
:class:`DesignRecord`   a design's line in an atlas's resumable     ``atlas.py``
                        ``cache.jsonl``
:class:`Example`        an entry of ``examples`` (JSON)             the two below
:class:`AtlasType`      an entry of ``types`` of ``atlas --json``   ``atlas.py``, ``lookup.py``,
                        and of ``atlas.json`` (build_atlas)         ``gallery.py``
:class:`IndexRow`       one row of an atlas index (Parquet;         ``lookup.py`` (``write_index``,
                        ``lkspace/data/atlas.parquet``)             ``read_index``), experiments
``LookupDesign``,       ``lookup --json``, ``/api/lookup``;         ``lookup.py``, ``search.py``,
``LookupAnswer``,       ``solutions`` of ``solve --type --json``    the CLI, the studio
``TargetSolution``      (:mod:`~lkspace.linktypes.answers`)
======================  ==========================================  ==============================

Each has exactly one reader (``from_json``, ``from_row`` for Parquet) that checks every
field and raises :class:`~lkspace.errors.CatalogError` naming the field and what arrived
(:mod:`~lkspace.linktypes.fields`), and one writer (``to_json``, ``to_row``) that gives
the fields in the order the JSON has always had.  Nothing here imports numpy or pyarrow:
``lkspace lookup`` stays light.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property

from ..errors import CatalogError
from .fields import (
    JsonObject,
    as_object,
    read_bool,
    read_float,
    read_int,
    read_ints,
    read_list,
    read_opt_bool,
    read_opt_int,
    read_opt_str,
    read_str,
)
from .spelling import Chirality


@dataclass(frozen=True)
class DesignRecord:
    """What an atlas keeps of one identified design: its type (:func:`~lkspace.linktypes.atlas.type_key`) and more.

    ``mirror``: the chirality identify found (``None``: not told); ``crossings``: of the
    simplified diagram; ``status``: identify's.
    """

    type: str
    components: int | None = None
    table: str | None = None
    mirror: bool | None = None
    crossings: int | None = None
    status: str | None = None

    @classmethod
    def from_json(cls, data: object, where: str = "design record") -> DesignRecord:
        """Read ``{type, components, table, mirror, crossings, status}``."""
        d = as_object(data, where)
        return cls(
            read_str(d, "type", where),
            read_opt_int(d, "components", where),
            read_opt_str(d, "table", where),
            read_opt_bool(d, "mirror", where),
            read_opt_int(d, "crossings", where),
            read_opt_str(d, "status", where),
        )

    def to_json(self) -> JsonObject:
        """Return ``{type, components, table, mirror, crossings, status}``."""
        return {
            "type": self.type,
            "components": self.components,
            "table": self.table,
            "mirror": self.mirror,
            "crossings": self.crossings,
            "status": self.status,
        }


@dataclass(frozen=True)
class Example:
    """One of the simplest designs of a type: its labels, ``sum |t|``, non-zero labels, crossings, chirality."""

    labels: tuple[int, ...]
    sum_abs: int
    nonzero: int
    crossings: int | None
    mirror: bool | None

    @classmethod
    def from_json(cls, data: object, where: str = "example") -> Example:
        """Read ``{labels, sum_abs, nonzero, crossings, mirror}``."""
        if type(data) is dict:  # the common case, checked at C speed: an atlas index holds ~10^4 examples
            labels, sum_abs, nonzero = data.get("labels"), data.get("sum_abs"), data.get("nonzero")
            crossings, mirror = data.get("crossings"), data.get("mirror")
            if (
                type(labels) is list
                and set(map(type, labels)) <= {int}
                and type(sum_abs) is int
                and type(nonzero) is int
                and (crossings is None or type(crossings) is int)
                and (mirror is None or type(mirror) is bool)
                and "crossings" in data
                and "mirror" in data
            ):
                return cls(tuple(labels), sum_abs, nonzero, crossings, mirror)
        d = as_object(data, where)  # anything else: field by field, naming the first that is wrong
        return cls(
            read_ints(d, "labels", where),
            read_int(d, "sum_abs", where),
            read_int(d, "nonzero", where),
            read_opt_int(d, "crossings", where),
            read_opt_bool(d, "mirror", where),
        )

    def to_json(self) -> JsonObject:
        """Return ``{labels, sum_abs, nonzero, crossings, mirror}``."""
        return {
            "labels": list(self.labels),
            "sum_abs": self.sum_abs,
            "nonzero": self.nonzero,
            "crossings": self.crossings,
            "mirror": self.mirror,
        }


def _examples(data: Mapping[str, object], key: str, where: str) -> tuple[Example, ...]:
    return tuple(Example.from_json(e, f"{where}, {key}[{i}]") for i, e in enumerate(read_list(data, key, where)))


@dataclass(frozen=True)
class ChiralityCounts:
    """Designs of a type per chirality identify reported: the table's diagram, its mirror, not told apart."""

    table: int = 0
    mirror: int = 0
    undetermined: int = 0

    def to_json(self) -> JsonObject:
        """Return ``{table, mirror, undetermined}``."""
        return {"table": self.table, "mirror": self.mirror, "undetermined": self.undetermined}


@dataclass(frozen=True)
class AtlasType:
    """One type of an atlas (``lkspace atlas``): how many designs realize it, and the simplest of them.

    ``simplest_sum_abs`` and ``simplest_nonzero`` are the cost of ``simplest``;
    ``picture`` the file of its PNG when the atlas was written to a folder.
    """

    name: str
    components: int | None
    table: str | None
    crossings: int | None
    designs: int
    assignments: int
    simplest: tuple[int, ...]
    simplest_sum_abs: int
    simplest_nonzero: int
    chirality: ChiralityCounts
    examples: tuple[Example, ...]
    picture: str | None = None

    @classmethod
    def from_json(cls, data: object, where: str = "atlas type") -> AtlasType:
        """Read one entry of ``types`` (:meth:`to_json`)."""
        d = as_object(data, where)
        name = read_str(d, "name", where)
        where = f"{where} {name!r}"
        chir = as_object(d.get("chirality"), f"{where}, chirality")
        return cls(
            name,
            read_opt_int(d, "components", where),
            read_opt_str(d, "table", where),
            read_opt_int(d, "crossings", where),
            read_int(d, "designs", where),
            read_int(d, "assignments", where),
            read_ints(d, "simplest", where),
            read_int(d, "simplest_sum_abs", where),
            read_int(d, "simplest_nonzero", where),
            ChiralityCounts(
                *(read_int(chir, side, f"{where}, chirality") for side in ("table", "mirror", "undetermined"))
            ),
            _examples(d, "examples", where),
            read_opt_str(d, "picture", where) if "picture" in d else None,
        )

    def to_json(self) -> JsonObject:
        """Return ``{name, components, table, crossings, designs, assignments, simplest, ..., examples}``."""
        out: JsonObject = {
            "name": self.name,
            "components": self.components,
            "table": self.table,
            "crossings": self.crossings,
            "designs": self.designs,
            "assignments": self.assignments,
            "simplest": list(self.simplest),
            "simplest_sum_abs": self.simplest_sum_abs,
            "simplest_nonzero": self.simplest_nonzero,
            "chirality": self.chirality.to_json(),
            "examples": [e.to_json() for e in self.examples],
        }
        if self.picture is not None:
            out["picture"] = self.picture
        return out


@dataclass(frozen=True)
class AtlasRun:
    """How an atlas of a mesh was made: designs identified now, reused, read from the cache, skipped."""

    identified_now: int
    reused: int
    from_cache: int
    complete: bool
    skipped: int
    wall_time: float


@dataclass(frozen=True)
class AtlasResult:
    """An atlas (``lkspace atlas --json``; ``atlas.json`` of ``experiments/build_atlas.py``).

    ``run``: how it was made, for an atlas of a mesh; ``from_catalog``: the catalog it
    was summed from otherwise.  ``labels``: the label set as typed (build_atlas only).
    """

    scaffold: str
    label_set: tuple[int, ...] | None
    designs: int
    assignments: int
    types: tuple[AtlasType, ...]
    run: AtlasRun | None = None
    from_catalog: str | None = None
    labels: str | None = None

    @property
    def complete(self) -> bool:
        """Every design of the space was identified (an atlas of a catalog: always)."""
        return self.run is None or self.run.complete

    @classmethod
    def from_json(cls, data: object, where: str = "atlas") -> AtlasResult:
        """Read :meth:`to_json`."""
        d = as_object(data, where)
        scaffold = read_str(d, "scaffold", where)
        where = f"{where} of {scaffold}"
        types = tuple(
            AtlasType.from_json(t, f"{where}, types[{i}]") for i, t in enumerate(read_list(d, "types", where))
        )
        run = None
        if "identified_now" in d:
            run = AtlasRun(
                read_int(d, "identified_now", where),
                read_int(d, "reused", where),
                read_int(d, "from_cache", where),
                read_bool(d, "complete", where),
                read_int(d, "skipped", where),
                read_float(d, "wall_time", where),
            )
        return cls(
            scaffold,
            None if d.get("label_set") is None else read_ints(d, "label_set", where),
            read_int(d, "designs", where),
            read_int(d, "assignments", where),
            types,
            run,
            read_opt_str(d, "from_catalog", where) if "from_catalog" in d else None,
            read_opt_str(d, "labels", where) if "labels" in d else None,
        )

    def to_json(self) -> JsonObject:
        """Return ``{scaffold, label_set, designs, assignments, [identified_now ... skipped], types, ...}``."""
        out: JsonObject = {
            "scaffold": self.scaffold,
            "label_set": None if self.label_set is None else list(self.label_set),
            "designs": self.designs,
            "assignments": self.assignments,
        }
        r = self.run
        if r is not None:
            out.update(identified_now=r.identified_now, reused=r.reused, from_cache=r.from_cache)
            out.update(complete=r.complete, skipped=r.skipped)
        out["types"] = [t.to_json() for t in self.types]
        if r is not None:
            out["wall_time"] = r.wall_time
        if self.from_catalog is not None:
            out["from_catalog"] = self.from_catalog
        if self.labels is not None:
            out["labels"] = self.labels
        return out


INDEX_COLUMNS: tuple[tuple[str, str], ...] = (
    ("type", "string"),
    ("common_name", "string"),
    ("components", "int32"),
    ("crossing_number", "int32"),
    ("crossings", "int32"),
    ("table", "string"),
    ("scaffold", "string"),
    ("labels", "string"),
    ("designs", "int64"),
    ("assignments", "int64"),
    ("first_sum_abs", "int64"),
    ("chirality_table", "int64"),
    ("chirality_mirror", "int64"),
    ("chirality_undetermined", "int64"),
    ("examples", "string"),
    ("complete", "bool_"),
)
"""The columns of an atlas index, in file order, with their Arrow types (``examples``: a JSON list)."""

_NULLABLE = frozenset({"common_name", "components", "crossing_number", "crossings", "table", "first_sum_abs"})
_KINDS: tuple[tuple[str, type, bool], ...] = tuple(
    (name, {"string": str, "int32": int, "int64": int, "bool_": bool}[kind], name in _NULLABLE)
    for name, kind in INDEX_COLUMNS
)


@dataclass(frozen=True)
class IndexRow:
    """One row of an atlas index: one type in one space (scaffold, label set); columns in :data:`INDEX_COLUMNS`.

    ``examples_json`` is the ``examples`` column as stored; :attr:`examples` reads it (with
    :meth:`Example.from_json`, on first use: a lookup reads the examples of the rows of one
    type, not the ~10^4 of the whole index).
    """

    type: str
    common_name: str | None
    components: int | None
    crossing_number: int | None
    crossings: int | None
    table: str | None
    scaffold: str
    labels: str
    designs: int
    assignments: int
    first_sum_abs: int | None
    chirality_table: int
    chirality_mirror: int
    chirality_undetermined: int
    examples_json: str
    complete: bool

    @classmethod
    def from_row(cls, row: Mapping[str, object], where: str = "atlas index row") -> IndexRow:
        """Read one Parquet row, checking every column (``examples``: its text now, its JSON on first use)."""
        fast = [row.get(name) for name, _, _ in _KINDS]
        if all(type(v) is kind or (v is None and nullable) for v, (_, kind, nullable) in zip(fast, _KINDS)):
            return cls(*fast)  # type: ignore[arg-type]  # each column checked just above, at a fraction of the cost
        return cls(
            read_str(row, "type", where),
            read_opt_str(row, "common_name", where),
            read_opt_int(row, "components", where),
            read_opt_int(row, "crossing_number", where),
            read_opt_int(row, "crossings", where),
            read_opt_str(row, "table", where),
            read_str(row, "scaffold", where),
            read_str(row, "labels", where),
            read_int(row, "designs", where),
            read_int(row, "assignments", where),
            read_opt_int(row, "first_sum_abs", where),
            read_int(row, "chirality_table", where),
            read_int(row, "chirality_mirror", where),
            read_int(row, "chirality_undetermined", where),
            read_str(row, "examples", where),
            read_bool(row, "complete", where),
        )

    def to_row(self) -> dict[str, object]:
        """Return the row as written to Parquet: the columns of :data:`INDEX_COLUMNS`, ``examples`` as JSON text."""
        values = {name: getattr(self, name) for name, _ in INDEX_COLUMNS if name != "examples"}
        values["examples"] = self.examples_json
        return {name: values[name] for name, _ in INDEX_COLUMNS}

    @cached_property
    def examples(self) -> tuple[Example, ...]:
        """The simplest designs of the type in this space (the ``examples`` column read and checked)."""
        where = f"atlas index row {self.type!r} ({self.scaffold} {self.labels})"
        try:
            examples = json.loads(self.examples_json)
        except json.JSONDecodeError as exc:
            raise CatalogError(f"{where}: field 'examples' is not JSON ({exc})") from None
        return _examples({"examples": examples}, "examples", where)

    @staticmethod
    def examples_text(examples: tuple[Example, ...]) -> str:
        """Return the ``examples`` column of ``examples``: a JSON list."""
        return json.dumps([e.to_json() for e in examples])

    def count(self, chirality: Chirality) -> int:
        """Designs of the type in this space, of one chirality (``"any"``: all)."""
        return {"any": self.designs, "table": self.chirality_table, "mirror": self.chirality_mirror}[chirality]
