"""The answers of ``lkspace lookup`` and ``solve --type``, as frozen wire records.

One reader (``from_json``) and one writer (``to_json``) each, like the atlas records of
:mod:`~lkspace.linktypes.records` (which tabulates them all); fields in the order the
JSON has always had.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from .fields import (
    Json,
    JsonObject,
    as_object,
    get_field,
    read_bool,
    read_chirality,
    read_int,
    read_ints,
    read_list,
    read_opt_bool,
    read_opt_int,
    read_opt_str,
    read_str,
    read_strs,
)
from .ideal_shapes import IdealShape
from .spelling import Chirality


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
    constructed: bool = False

    @classmethod
    def from_json(cls, data: object, where: str = "lookup design") -> LookupDesign:
        """Read one entry of ``designs`` (:meth:`to_json`)."""
        d = as_object(data, where)
        return cls(
            read_str(d, "type", where),
            read_opt_str(d, "common_name", where),
            read_str(d, "scaffold", where),
            read_ints(d, "labels", where),
            read_str(d, "label_set", where),
            read_int(d, "sum_abs", where),
            read_int(d, "nonzero", where),
            read_opt_int(d, "crossings", where),
            read_opt_bool(d, "mirror", where),
            read_str(d, "chiral_name", where),
            read_int(d, "designs_of_type", where),
            read_str(d, "command", where),
            read_opt_bool(d, "constructed", where) or False,
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
            "constructed": self.constructed,
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
    ideal_shape: IdealShape | None = None

    @property
    def asked(self) -> str:
        """The name with its mirror mark: ``m3_1`` for a mirror image asked for."""
        return f"m{self.name}" if self.chirality == "mirror" else self.name

    @classmethod
    def from_json(cls, data: object, where: str = "lookup answer") -> LookupAnswer:
        """Read ``lookup --json`` (:meth:`to_json`)."""
        d = as_object(data, where)
        chirality = read_chirality(read_str(d, "chirality", where), where)
        return cls(
            read_str(d, "query", where),
            read_str(d, "name", where),
            chirality,
            read_opt_str(d, "common_name", where),
            read_str(d, "atlas", where),
            read_strs(d, "searched", where),
            read_strs(d, "found_in", where),
            read_int(d, "designs_total", where),
            read_int(d, "simplest_kept", where),
            tuple(
                LookupDesign.from_json(x, f"{where}, designs[{i}]")
                for i, x in enumerate(read_list(d, "designs", where))
            ),
            None if d.get("ideal_shape") is None else IdealShape.from_json(d["ideal_shape"], f"{where}, ideal_shape"),
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
            "ideal_shape": None if self.ideal_shape is None else self.ideal_shape.to_json(),
        }


def _matrix(data: Mapping[str, object], key: str, where: str) -> tuple[tuple[int, ...], ...] | None:
    if get_field(data, key, where) is None:
        return None
    rows = read_list(data, key, where)
    return tuple(read_ints({key: r}, key, where) for r in rows)


@dataclass(frozen=True)
class TargetSolution:
    """One design ``solve --type`` / ``--linking-matrix`` found, re-identified.

    ``identified``: identify named it (a type target), so ``name``, ``chiral_name``,
    ``mirror``, ``table`` and ``crossings`` are part of the answer; a linking-matrix
    target alone leaves them out.
    """

    labels: tuple[int, ...]
    components: int
    sum_abs: int
    max_abs: int
    nonzero: int
    orbit_size: int
    linking_matrix: tuple[tuple[int, ...], ...] | None
    reidentified: bool = True
    identified: bool = False
    name: str | None = None
    chiral_name: str | None = None
    mirror: bool | None = None
    table: str | None = None
    crossings: int | None = None

    @classmethod
    def from_json(cls, data: object, where: str = "solution") -> TargetSolution:
        """Read one entry of ``solutions`` (:meth:`to_json`)."""
        d = as_object(data, where)
        named = "name" in d
        return cls(
            read_ints(d, "labels", where),
            read_int(d, "components", where),
            read_int(d, "sum_abs", where),
            read_int(d, "max_abs", where),
            read_int(d, "nonzero", where),
            read_int(d, "orbit_size", where),
            _matrix(d, "linking_matrix", where),
            read_bool(d, "reidentified", where),
            named,
            read_opt_str(d, "name", where) if named else None,
            read_opt_str(d, "chiral_name", where) if named else None,
            read_opt_bool(d, "mirror", where) if named else None,
            read_opt_str(d, "table", where) if named else None,
            read_opt_int(d, "crossings", where) if named else None,
        )

    def to_json(self) -> JsonObject:
        """Return ``{labels, components, sum_abs, max_abs, nonzero, orbit_size, linking_matrix, reidentified, ...}``."""
        matrix: Json = None if self.linking_matrix is None else [list(r) for r in self.linking_matrix]
        out: JsonObject = {
            "labels": list(self.labels),
            "components": self.components,
            "sum_abs": self.sum_abs,
            "max_abs": self.max_abs,
            "nonzero": self.nonzero,
            "orbit_size": self.orbit_size,
            "linking_matrix": matrix,
            "reidentified": self.reidentified,
        }
        if self.identified:
            out.update(name=self.name, chiral_name=self.chiral_name, mirror=self.mirror, table=self.table)
            out["crossings"] = self.crossings
        return out
