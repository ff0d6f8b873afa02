"""The atlas and lookup payloads that cross a boundary, one frozen record each.

=====================  =========================================  ===============================
record                 travels as                                 read by / written by
=====================  =========================================  ===============================
:class:`DesignRecord`  a design's line in an atlas's resumable    ``atlas.py`` (``read_cache``,
                       ``cache.jsonl``: its type and chirality    ``atlas``)
:class:`Example`       an entry of ``examples`` (JSON)            the three below
:class:`AtlasType`     an entry of ``types`` of ``atlas --json``  ``atlas.py`` / ``lookup.py``,
                       and of ``atlas.json`` (build_atlas)        ``gallery.py``, experiments
:class:`IndexRow`      one row of an atlas index (Parquet;        ``lookup.py`` (``write_index``,
                       ``lkspace/data/atlas.parquet``)            ``read_index``), experiments
:class:`LookupDesign`  an entry of ``designs`` of ``lookup``      ``lookup.py``, the CLI, studio
:class:`LookupAnswer`  ``lookup --json`` and ``/api/lookup``      ``lookup.py``, the CLI, studio
=====================  =========================================  ===============================

Each has exactly one reader (``from_json``, ``from_row`` for Parquet) that checks every
field and raises :class:`~lkspace.errors.CatalogError` naming the field and what arrived,
and one writer (``to_json``, ``to_row``) that gives the fields in the order the JSON has
always had.  Nothing here imports numpy or pyarrow: ``lkspace lookup`` stays light.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TypeAlias, cast

from ..errors import CatalogError
from .spelling import CHIRALITIES, Chirality

Json: TypeAlias = "None | bool | int | float | str | list[Json] | dict[str, Json]"
"""A JSON value as :func:`json.loads` returns it."""
JsonObject: TypeAlias = dict[str, Json]


def _get(data: Mapping[str, object], key: str, where: str) -> object:
    if key not in data:
        raise CatalogError(f"{where}: no field {key!r}")
    return data[key]


def _wrong(where: str, key: str, value: object, want: str) -> CatalogError:
    return CatalogError(f"{where}: field {key!r} is {value!r}, expected {want}")


def _int(data: Mapping[str, object], key: str, where: str) -> int:
    value = _get(data, key, where)
    if isinstance(value, int) and not isinstance(value, bool):
        return value
    raise _wrong(where, key, value, "an integer")


def _opt_int(data: Mapping[str, object], key: str, where: str) -> int | None:
    return None if _get(data, key, where) is None else _int(data, key, where)


def _str(data: Mapping[str, object], key: str, where: str) -> str:
    value = _get(data, key, where)
    if isinstance(value, str):
        return value
    raise _wrong(where, key, value, "a string")


def _opt_str(data: Mapping[str, object], key: str, where: str) -> str | None:
    return None if _get(data, key, where) is None else _str(data, key, where)


def _bool(data: Mapping[str, object], key: str, where: str) -> bool:
    value = _get(data, key, where)
    if isinstance(value, bool):
        return value
    raise _wrong(where, key, value, "true or false")


def _opt_bool(data: Mapping[str, object], key: str, where: str) -> bool | None:
    return None if _get(data, key, where) is None else _bool(data, key, where)


def _list(data: Mapping[str, object], key: str, where: str) -> list[object]:
    value = _get(data, key, where)
    if isinstance(value, list | tuple):
        return list(value)
    raise _wrong(where, key, value, "a list")


def _ints(data: Mapping[str, object], key: str, where: str) -> tuple[int, ...]:
    values = _list(data, key, where)
    if not set(map(type, values)) <= {int}:  # exactly int: no bool (C speed: an atlas holds ~10^4 label lists)
        raise _wrong(where, key, values, "a list of integers")
    return tuple(cast(list[int], values))


def _strs(data: Mapping[str, object], key: str, where: str) -> tuple[str, ...]:
    values = _list(data, key, where)
    if not set(map(type, values)) <= {str}:
        raise _wrong(where, key, values, "a list of strings")
    return tuple(cast(list[str], values))


def _object(value: object, where: str) -> Mapping[str, object]:
    if isinstance(value, Mapping) and set(map(type, value)) <= {str}:
        return cast(Mapping[str, object], value)
    raise CatalogError(f"{where}: {value!r} is no JSON object")


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
        d = _object(data, where)
        return cls(
            _str(d, "type", where),
            _opt_int(d, "components", where),
            _opt_str(d, "table", where),
            _opt_bool(d, "mirror", where),
            _opt_int(d, "crossings", where),
            _opt_str(d, "status", where),
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
        d = _object(data, where)  # anything else: field by field, naming the first that is wrong
        return cls(
            _ints(d, "labels", where),
            _int(d, "sum_abs", where),
            _int(d, "nonzero", where),
            _opt_int(d, "crossings", where),
            _opt_bool(d, "mirror", where),
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


def _chirality(text: str, where: str) -> Chirality:
    for side in CHIRALITIES:
        if text == side:
            return side
    raise _wrong(where, "chirality", text, " or ".join(CHIRALITIES))


def _examples(data: Mapping[str, object], key: str, where: str) -> tuple[Example, ...]:
    return tuple(Example.from_json(e, f"{where}, {key}[{i}]") for i, e in enumerate(_list(data, key, where)))


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
        d = _object(data, where)
        name = _str(d, "name", where)
        where = f"{where} {name!r}"
        chir = _object(d.get("chirality"), f"{where}, chirality")
        return cls(
            name,
            _opt_int(d, "components", where),
            _opt_str(d, "table", where),
            _opt_int(d, "crossings", where),
            _int(d, "designs", where),
            _int(d, "assignments", where),
            _ints(d, "simplest", where),
            _int(d, "simplest_sum_abs", where),
            _int(d, "simplest_nonzero", where),
            ChiralityCounts(*(_int(chir, side, f"{where}, chirality") for side in ("table", "mirror", "undetermined"))),
            _examples(d, "examples", where),
            _opt_str(d, "picture", where) if "picture" in d else None,
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
    ("complete", "bool"),
)
"""The columns of an atlas index, in file order, with their Arrow types (``examples``: a JSON list)."""


@dataclass(frozen=True)
class IndexRow:
    """One row of an atlas index: one type in one space (scaffold, label set); columns in :data:`INDEX_COLUMNS`."""

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
    examples: tuple[Example, ...]
    complete: bool

    @classmethod
    def from_row(cls, row: Mapping[str, object], where: str = "atlas index row") -> IndexRow:
        """Read one Parquet row (``examples`` a JSON string), checking every column."""
        raw = _str(row, "examples", where)
        try:
            examples = json.loads(raw)
        except json.JSONDecodeError as exc:
            raise CatalogError(f"{where}: field 'examples' is not JSON ({exc})") from None
        return cls(
            _str(row, "type", where),
            _opt_str(row, "common_name", where),
            _opt_int(row, "components", where),
            _opt_int(row, "crossing_number", where),
            _opt_int(row, "crossings", where),
            _opt_str(row, "table", where),
            _str(row, "scaffold", where),
            _str(row, "labels", where),
            _int(row, "designs", where),
            _int(row, "assignments", where),
            _opt_int(row, "first_sum_abs", where),
            _int(row, "chirality_table", where),
            _int(row, "chirality_mirror", where),
            _int(row, "chirality_undetermined", where),
            _examples({"examples": examples}, "examples", where),
            _bool(row, "complete", where),
        )

    def to_row(self) -> dict[str, object]:
        """Return the row as written to Parquet: the columns of :data:`INDEX_COLUMNS`, ``examples`` as JSON text."""
        values = {name: getattr(self, name) for name, _ in INDEX_COLUMNS}
        values["examples"] = json.dumps([e.to_json() for e in self.examples])
        return values

    def count(self, chirality: Chirality) -> int:
        """Designs of the type in this space, of one chirality (``"any"``: all)."""
        return {"any": self.designs, "table": self.chirality_table, "mirror": self.chirality_mirror}[chirality]


@dataclass(frozen=True)
class LookupDesign:
    """One design a lookup answers: where it lives, how simple it is, and the command that identifies it again."""

    type: str
    common_name: str | None
    scaffold: str
    labels: tuple[int, ...]
    label_set: str
    sum_abs: int
    nonzero: int
    crossings: int | None
    mirror: bool | None
    chiral_name: str
    designs_of_type: int
    command: str

    @classmethod
    def from_json(cls, data: object, where: str = "lookup design") -> LookupDesign:
        """Read one entry of ``designs`` (:meth:`to_json`)."""
        d = _object(data, where)
        return cls(
            _str(d, "type", where),
            _opt_str(d, "common_name", where),
            _str(d, "scaffold", where),
            _ints(d, "labels", where),
            _str(d, "label_set", where),
            _int(d, "sum_abs", where),
            _int(d, "nonzero", where),
            _opt_int(d, "crossings", where),
            _opt_bool(d, "mirror", where),
            _str(d, "chiral_name", where),
            _int(d, "designs_of_type", where),
            _str(d, "command", where),
        )

    def to_json(self) -> JsonObject:
        """Return ``{type, common_name, scaffold, labels, label_set, sum_abs, ..., command}``."""
        return {
            "type": self.type,
            "common_name": self.common_name,
            "scaffold": self.scaffold,
            "labels": list(self.labels),
            "label_set": self.label_set,
            "sum_abs": self.sum_abs,
            "nonzero": self.nonzero,
            "crossings": self.crossings,
            "mirror": self.mirror,
            "chiral_name": self.chiral_name,
            "designs_of_type": self.designs_of_type,
            "command": self.command,
        }


@dataclass(frozen=True)
class LookupAnswer:
    """The answer of ``lkspace lookup`` (fields in :func:`~lkspace.linktypes.lookup.lookup`)."""

    query: str
    name: str
    chirality: Chirality
    common_name: str | None
    atlas: str
    searched: tuple[str, ...]
    found_in: tuple[str, ...]
    designs_total: int
    simplest_kept: int
    designs: tuple[LookupDesign, ...]

    @property
    def asked(self) -> str:
        """The name with its mirror mark: ``m3_1`` for a mirror image asked for."""
        return f"m{self.name}" if self.chirality == "mirror" else self.name

    @classmethod
    def from_json(cls, data: object, where: str = "lookup answer") -> LookupAnswer:
        """Read ``lookup --json`` (:meth:`to_json`)."""
        d = _object(data, where)
        chirality = _chirality(_str(d, "chirality", where), where)
        return cls(
            _str(d, "query", where),
            _str(d, "name", where),
            chirality,
            _opt_str(d, "common_name", where),
            _str(d, "atlas", where),
            _strs(d, "searched", where),
            _strs(d, "found_in", where),
            _int(d, "designs_total", where),
            _int(d, "simplest_kept", where),
            tuple(
                LookupDesign.from_json(x, f"{where}, designs[{i}]") for i, x in enumerate(_list(d, "designs", where))
            ),
        )

    def to_json(self) -> JsonObject:
        """Return ``{query, name, chirality, common_name, atlas, searched, found_in, designs_total, ..., designs}``."""
        return {
            "query": self.query,
            "name": self.name,
            "chirality": self.chirality,
            "common_name": self.common_name,
            "atlas": self.atlas,
            "searched": list(self.searched),
            "found_in": list(self.found_in),
            "designs_total": self.designs_total,
            "simplest_kept": self.simplest_kept,
            "designs": [d.to_json() for d in self.designs],
        }
