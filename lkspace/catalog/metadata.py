"""The catalog's ``lkspace`` metadata as a record: the settings every file of a catalog shares.

:class:`CatalogMetadata` (with its :class:`ScaffoldInfo` and :class:`Filters`) has one
validating ``from_json`` and one ``to_json``; the file and folder records built on it are
in :mod:`lkspace.catalog.records`, and the field readers here serve both.  ``to_json``
writes the keys in the order lkspace has always written them, so catalogs and builds of
earlier versions read and resume, and a record read and written back is the same text.
``from_json`` refuses anything else with a one-line :class:`~lkspace.errors.CatalogError`
naming the file (``where``) and what is wrong; a setting recorded only since format
version 1 was fixed (:data:`LATER_KEYS`) may be absent (:data:`UNRECORDED`).
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Callable
from dataclasses import dataclass
from enum import Enum
from typing import Final, TypeVar

from ..design.space import WALK_MODES, WalkMode
from ..errors import CatalogError
from ..io.json_values import Json as Json
from ..io.json_values import JsonObject as JsonObject
from ..symmetry.group import MODES, SymmetryMode

FORMAT_VERSION = 1
"""The catalog format version lkspace writes."""

MAX_EDGES = 2**31 - 1
"""The most edges a catalog's ``key`` column (one byte per edge, an Arrow fixed-size binary) can hold."""

FORMAT_VERSIONS = (1,)
"""Catalog format versions this lkspace reads."""

LATER_KEYS = ("symmetry_tolerance",)
"""Settings recorded since format version 1 was fixed: a catalog without one was written before it existed.

Such a catalog has no ``digest`` either (footers were sealed after these were recorded,
2026-12-02): a sealed footer without one is damaged
(:meth:`~lkspace.catalog.records.PartFooter.from_json`).
"""


class Unrecorded(Enum):
    """The value of a setting the metadata lacks (a :data:`LATER_KEYS` setting of an older catalog, say).

    lkspace writes every setting; a reader needs only ``format_version``, the scaffold's
    ``name`` and ``edges``, ``label_set``, ``mode`` and (in a footer) ``rows``.  An absent
    key is read as :data:`UNRECORDED` and left out again by ``to_json``.
    """

    UNRECORDED = "unrecorded"

    def __str__(self) -> str:
        return self.value


UNRECORDED: Final = Unrecorded.UNRECORDED

T = TypeVar("T")


def recorded(data: JsonObject, key: str, read: Callable[[JsonObject, str, str], T], where: str) -> T | Unrecorded:
    """Return ``read(data, key, where)``, or :data:`UNRECORDED` when ``data`` has no ``key``."""
    return read(data, key, where) if key in data else UNRECORDED


def put(out: JsonObject, **values: Json | Unrecorded) -> JsonObject:
    """Add ``values`` to ``out`` in order, leaving out the :data:`UNRECORDED` ones; return ``out``."""
    out.update({k: v for k, v in values.items() if not isinstance(v, Unrecorded)})
    return out


def decode(raw: bytes | str, where: str) -> Json:
    """Parse the JSON text ``raw`` of ``where`` (``lkspace`` metadata or a manifest)."""
    try:
        data: Json = json.loads(raw)
    except (UnicodeDecodeError, ValueError, RecursionError):  # RecursionError: nested past the stack
        raise CatalogError(
            f"{where}: the 'lkspace' metadata is not valid JSON (damaged, or not written by lkspace)"
        ) from None
    return data


def lkspace_mark(data: Json) -> bool:
    """Whether ``data`` bears lkspace's mark: a JSON object with a ``format_version`` (metadata or a manifest).

    Not a check that it reads (``from_json`` is): a damaged catalog lkspace wrote is still
    one lkspace may replace, and nothing else is.
    """
    return isinstance(data, dict) and "format_version" in data


def metadata_digest(meta: JsonObject) -> str:
    """Return the SHA-256 of ``meta`` without its ``digest`` (canonical JSON): a file's footer records it.

    It makes a changed value in the metadata itself (a label set, a row count) detectable
    in a one-file catalog, which has no manifest.
    """
    body = {k: v for k, v in meta.items() if k != "digest"}
    return hashlib.sha256(json.dumps(body, sort_keys=True, separators=(",", ":")).encode()).hexdigest()


def same_settings(old: JsonObject, new: JsonObject) -> bool:
    """Whether the JSON ``old`` has every setting of ``new`` (a :data:`LATER_KEYS` setting it lacks passes)."""
    return all(old.get(k) == v for k, v in new.items() if k in old or k not in LATER_KEYS)


def shown(value: object) -> str:
    """Return ``repr(value)``, cut to 40 characters (for messages)."""
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def json_object(value: object, what: str) -> JsonObject:
    """Return ``value`` if it is a JSON object (a dict with string keys); raise naming it as ``what`` otherwise."""
    if not isinstance(value, dict) or not all(isinstance(k, str) for k in value):
        raise CatalogError(f"{what} is not a JSON object")
    return value


def count_field(data: JsonObject, key: str, where: str, minimum: int | None = None) -> int:
    """Return the integer ``data[key]`` (at least ``minimum``); raise naming it and ``where`` otherwise."""
    value = data.get(key)
    if isinstance(value, bool) or not isinstance(value, int) or (minimum is not None and value < minimum):
        raise CatalogError(f"{where}: {key} {shown(value)} is not a count (damaged)")
    return value


def optional_count(data: JsonObject, key: str, where: str) -> int | None:
    """Return the integer ``data[key]``, or ``None`` when it is null or absent."""
    return None if data.get(key) is None else count_field(data, key, where)


def text_field(data: JsonObject, key: str, where: str) -> str:
    """Return the string ``data[key]``; raise naming it and ``where`` otherwise."""
    value = data.get(key)
    if not isinstance(value, str):
        raise CatalogError(f"{where}: {key} {shown(value)} is not a string (damaged)")
    return value


def flag_field(data: JsonObject, key: str, where: str) -> bool:
    """Return the boolean ``data[key]``; raise naming it and ``where`` otherwise."""
    value = data.get(key)
    if not isinstance(value, bool):
        raise CatalogError(f"{where}: {key} {shown(value)} is not true or false (damaged)")
    return value


def checked_header(data: Json, where: str) -> JsonObject:
    """Return the metadata ``data`` of ``where`` if it is a JSON object of a known format version with a scaffold and a label set."""
    if not isinstance(data, dict):
        raise CatalogError(f"{where}: the 'lkspace' metadata is not a JSON object (damaged, or not written by lkspace)")
    version = data.get("format_version")
    if isinstance(version, bool) or version not in FORMAT_VERSIONS:
        known = ", ".join(map(str, FORMAT_VERSIONS))
        raise CatalogError(
            f"{where}: catalog format_version {version!r} is not one this lkspace reads ({known}); "
            "a newer lkspace wrote it, or it is damaged"
        )
    if not isinstance(data.get("scaffold"), dict) or not isinstance(data.get("label_set"), list):
        raise CatalogError(f"{where}: the 'lkspace' metadata has no scaffold or label_set (damaged)")
    return data


@dataclass(frozen=True)
class ScaffoldInfo:
    """The ``scaffold`` entry of the metadata: which scaffold, and (since it was recorded) its geometry.

    Attributes
    ----------
    name, content_hash : str
        The scaffold's name and :meth:`~lkspace.model.scaffold.Scaffold.content_hash`.
    edges, faces : int
    periodic : bool
    data : dict or None
        The scaffold file's JSON without labels (``None``: not recorded; loaded by name).
    """

    name: str
    content_hash: str | Unrecorded
    edges: int
    faces: int | Unrecorded
    periodic: bool | Unrecorded
    data: JsonObject | None = None

    def to_json(self) -> JsonObject:
        """JSON form (``data`` left out when not recorded)."""
        out = put({"name": self.name}, content_hash=self.content_hash)
        put(out, edges=self.edges, faces=self.faces, periodic=self.periodic)
        if self.data is not None:
            out["data"] = self.data
        return out

    @classmethod
    def from_json(cls, data: Json, where: str) -> ScaffoldInfo:
        """Read the ``scaffold`` entry of ``where``'s metadata."""
        info = json_object(data, f"{where}: the scaffold in its 'lkspace' metadata")
        edges = info.get("edges")
        if isinstance(edges, bool) or not isinstance(edges, int) or not 1 <= edges <= MAX_EDGES:
            raise CatalogError(f"{where}: the 'lkspace' metadata has no usable scaffold edges or mode (damaged)")
        what = f"{where}: the scaffold in its 'lkspace' metadata:"
        geometry = info.get("data")
        return cls(
            text_field(info, "name", what),
            recorded(info, "content_hash", text_field, what),
            edges,
            recorded(info, "faces", count_field, what),
            recorded(info, "periodic", flag_field, what),
            None if geometry is None else json_object(geometry, f"{what} data"),
        )


@dataclass(frozen=True)
class Filters:
    """The ``filters`` entry: rows kept by number of components, without zero labels, up to a count."""

    components: int | None = None
    no_zero: bool = False
    max_designs: int | None = None

    def to_json(self) -> JsonObject:
        """JSON form."""
        return {"components": self.components, "no_zero": self.no_zero, "max_designs": self.max_designs}

    @classmethod
    def from_json(cls, data: Json, where: str) -> Filters:
        """Read the ``filters`` entry of ``where``'s metadata."""
        what = f"{where}: the filters in its 'lkspace' metadata:"
        filters = json_object(data, what[:-1])
        if sorted(filters) != ["components", "max_designs", "no_zero"]:
            raise CatalogError(f"{what} keys {sorted(filters)} are not components, no_zero, max_designs (damaged)")
        return cls(
            optional_count(filters, "components", what),
            flag_field(filters, "no_zero", what),
            optional_count(filters, "max_designs", what),
        )


@dataclass(frozen=True)
class DnaSetting:
    """The ``dna`` entry: the catalog holds the DNA-buildable designs of the mesh at one scale (``docs/dna.md``).

    Attributes
    ----------
    nm_per_unit, window, bp_per_turn : float
        The scale, the window in half turns about each edge's natural twist, B-DNA's base
        pairs per turn.
    labels : tuple of (int, int)
        Per edge, the first and last label of its window (``first > last``: none).
    """

    nm_per_unit: float
    window: float
    bp_per_turn: float
    labels: tuple[tuple[int, int], ...]

    def to_json(self) -> JsonObject:
        """JSON form."""
        windows: list[Json] = [[lo, hi] for lo, hi in self.labels]
        return {
            "nm_per_unit": self.nm_per_unit,
            "window": self.window,
            "bp_per_turn": self.bp_per_turn,
            "labels": windows,
        }

    @classmethod
    def from_json(cls, data: Json, where: str) -> DnaSetting:
        """Read the ``dna`` entry of ``where``'s metadata."""
        what = f"{where}: the dna setting in its 'lkspace' metadata:"
        dna = json_object(data, what[:-1])
        numbers = [_number(dna, k, what) for k in ("nm_per_unit", "window", "bp_per_turn")]
        windows = dna.get("labels")
        pairs = windows if isinstance(windows, list) else [None]
        if not all(
            isinstance(p, list) and len(p) == 2 and all(isinstance(t, int) and not isinstance(t, bool) for t in p)
            for p in pairs
        ):
            raise CatalogError(f"{what} labels {shown(windows)} is not a list of [first, last] pairs (damaged)")
        labels = tuple(
            (p[0], p[1]) for p in pairs if isinstance(p, list) and isinstance(p[0], int) and isinstance(p[1], int)
        )
        return cls(numbers[0], numbers[1], numbers[2], labels)


@dataclass(frozen=True)
class CatalogMetadata:
    """The settings every file of a catalog shares, in the order they are written.

    Attributes
    ----------
    format_version : int
    scaffold : ScaffoldInfo
    label_set : tuple of int
    symmetry : {"rotations", "isometries", "none"}
    symmetry_tolerance : float, None or UNRECORDED
        The tolerance of the symmetry search (``None`` without symmetry).
    group_order, acting_order : int
        Order of the symmetry group, and signed edge permutations acting on the labels.
    assignments : int
        ``|label set| ** edges``.
    mode : {"designs", "residues", "spanning-trees"}
    filters : Filters
    sample, seed : int or None
        ``spanning-trees`` sampling (``seed`` is ``None`` without ``sample``).
    canonical_rule : str
        How each row's representative was chosen.
    invariant : dict or None
        A symmetric catalog's subgroup facts (:mod:`lkspace.catalog.symmetric`).
    dna : DnaSetting or None
        A DNA catalog's scale and windows (:mod:`lkspace.catalog.dna_catalog`).
    """

    format_version: int
    scaffold: ScaffoldInfo
    label_set: tuple[int, ...]
    symmetry: SymmetryMode | Unrecorded
    symmetry_tolerance: float | None | Unrecorded
    group_order: int | Unrecorded
    acting_order: int | Unrecorded
    assignments: int | Unrecorded
    mode: WalkMode
    filters: Filters | Unrecorded
    sample: int | None | Unrecorded
    seed: int | None | Unrecorded
    canonical_rule: str | Unrecorded
    invariant: JsonObject | None = None
    dna: DnaSetting | None = None

    def to_json(self) -> JsonObject:
        """JSON form (settings not recorded, and ``invariant`` and ``dna`` when absent, left out)."""
        out: JsonObject = {"format_version": self.format_version, "scaffold": self.scaffold.to_json()}
        put(out, label_set=list(self.label_set), symmetry=self.symmetry, symmetry_tolerance=self.symmetry_tolerance)
        put(out, group_order=self.group_order, acting_order=self.acting_order, assignments=self.assignments)
        filters = self.filters if isinstance(self.filters, Unrecorded) else self.filters.to_json()
        put(out, mode=self.mode, filters=filters, sample=self.sample, seed=self.seed)
        put(out, canonical_rule=self.canonical_rule)
        if self.invariant is not None:
            out["invariant"] = self.invariant
        if self.dna is not None:
            out["dna"] = self.dna.to_json()
        return out

    @classmethod
    def from_json(cls, data: Json, where: str) -> CatalogMetadata:
        """Read the settings of ``where``'s ``lkspace`` metadata (or manifest)."""
        meta = checked_header(data, where)
        labels = meta["label_set"]
        if not isinstance(labels, list) or not all(
            isinstance(t, int) and not isinstance(t, bool) and -128 <= t <= 127 for t in labels
        ):
            raise CatalogError(f"{where}: label_set {shown(labels)} is not a list of integers -128..127 (damaged)")
        mode = meta.get("mode")
        if mode not in WALK_MODES:
            raise CatalogError(f"{where}: the 'lkspace' metadata has no usable scaffold edges or mode (damaged)")
        invariant, dna = meta.get("invariant"), meta.get("dna")
        return cls(
            count_field(meta, "format_version", where),
            ScaffoldInfo.from_json(meta["scaffold"], where),
            tuple(t for t in labels if isinstance(t, int)),
            recorded(meta, "symmetry", _symmetry, where),
            recorded(meta, "symmetry_tolerance", _tolerance, where),
            recorded(meta, "group_order", count_field, where),
            recorded(meta, "acting_order", count_field, where),
            recorded(meta, "assignments", count_field, where),
            mode,
            recorded(meta, "filters", lambda d, k, w: Filters.from_json(d[k], w), where),
            recorded(meta, "sample", optional_count, where),
            recorded(meta, "seed", optional_count, where),
            recorded(meta, "canonical_rule", text_field, where),
            None if invariant is None else json_object(invariant, f"{where}: invariant"),
            None if dna is None else DnaSetting.from_json(dna, where),
        )


def _symmetry(meta: JsonObject, key: str, where: str) -> SymmetryMode:
    value = meta[key]
    if value not in MODES:
        raise CatalogError(f"{where}: symmetry {shown(value)} is not one of {', '.join(MODES)} (damaged)")
    return value


def _tolerance(meta: JsonObject, key: str, where: str) -> float | None:
    value = meta[key]
    if value is not None and (isinstance(value, bool) or not isinstance(value, int | float)):
        raise CatalogError(f"{where}: symmetry_tolerance {shown(value)} is not a number (damaged)")
    return value


def _number(data: JsonObject, key: str, what: str) -> float:
    value = data.get(key)
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise CatalogError(f"{what} {key} {shown(value)} is not a number (damaged)")
    return float(value)
