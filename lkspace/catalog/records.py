"""The catalog's wire formats: its ``lkspace`` metadata, the part footer and the manifest.

Each is a frozen record with one validating ``from_json`` and one ``to_json``, used by
every reader and writer of that format:

- :class:`CatalogMetadata`: the settings every file of a catalog shares (scaffold, label
  set, symmetry, mode, filters, ...), with its :class:`ScaffoldInfo` and :class:`Filters`;
- :class:`PartFooter`: the ``lkspace`` key of a Parquet file: the settings, the file's
  :class:`Shard` and, in the footer, its totals (:class:`PartSummary`) and ``digest``;
- :class:`Manifest`: ``_lkspace.json`` of a folder: the run's :class:`Signature`, its run
  id and the finished parts.

``to_json`` writes the keys in the order lkspace has always written them, so catalogs and
builds of earlier versions read and resume, and a record read and written back is the
same text.  ``from_json`` refuses anything else with a one-line
:class:`~lkspace.errors.CatalogError` naming the file (``where``) and what is wrong; a
setting recorded only since format version 1 was fixed (:data:`LATER_KEYS`) may be
absent (:data:`UNRECORDED`).
"""

from __future__ import annotations

import hashlib
import json
import os
from dataclasses import dataclass, field
from enum import Enum
from typing import Final, TypeAlias

from ..design.space import WALK_MODES, WalkMode
from ..errors import CatalogError
from ..symmetry.group import MODES, SymmetryMode

Json: TypeAlias = None | bool | int | float | str | list["Json"] | dict[str, "Json"]
"""A JSON value as :func:`json.loads` returns it."""

JsonObject: TypeAlias = dict[str, Json]

FORMAT_VERSION = 1
"""The catalog format version lkspace writes."""

FORMAT_VERSIONS = (1,)
"""Catalog format versions this lkspace reads."""

LATER_KEYS = ("symmetry_tolerance",)
"""Settings recorded since format version 1 was fixed: a catalog without one was written before it existed."""


class Unrecorded(Enum):
    """The value of a :data:`LATER_KEYS` setting that a catalog written before it existed lacks."""

    UNRECORDED = "unrecorded"


UNRECORDED: Final = Unrecorded.UNRECORDED


def decode(raw: bytes | str, where: str) -> Json:
    """Parse the JSON text ``raw`` of ``where`` (``lkspace`` metadata or a manifest)."""
    try:
        data: Json = json.loads(raw)
    except (UnicodeDecodeError, ValueError):
        raise CatalogError(
            f"{where}: the 'lkspace' metadata is not valid JSON (damaged, or not written by lkspace)"
        ) from None
    return data


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


def _shown(value: object) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def json_object(value: object, what: str) -> JsonObject:
    """Return ``value`` if it is a JSON object (a dict with string keys); raise naming it as ``what`` otherwise."""
    if not isinstance(value, dict) or not all(isinstance(k, str) for k in value):
        raise CatalogError(f"{what} is not a JSON object")
    return value


def _int(data: JsonObject, key: str, where: str, minimum: int | None = None) -> int:
    value = data.get(key)
    if isinstance(value, bool) or not isinstance(value, int) or (minimum is not None and value < minimum):
        raise CatalogError(f"{where}: {key} {_shown(value)} is not a count (damaged)")
    return value


def _optional_int(data: JsonObject, key: str, where: str) -> int | None:
    return None if data.get(key) is None else _int(data, key, where)


def _str(data: JsonObject, key: str, where: str) -> str:
    value = data.get(key)
    if not isinstance(value, str):
        raise CatalogError(f"{where}: {key} {_shown(value)} is not a string (damaged)")
    return value


def _bool(data: JsonObject, key: str, where: str) -> bool:
    value = data.get(key)
    if not isinstance(value, bool):
        raise CatalogError(f"{where}: {key} {_shown(value)} is not true or false (damaged)")
    return value


def _header(data: Json, where: str) -> JsonObject:
    """Return ``data`` if it is a JSON object of a known format version with a scaffold and a label set."""
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
    content_hash: str
    edges: int
    faces: int
    periodic: bool
    data: JsonObject | None = None

    def to_json(self) -> JsonObject:
        """JSON form (``data`` left out when not recorded)."""
        out: JsonObject = {
            "name": self.name,
            "content_hash": self.content_hash,
            "edges": self.edges,
            "faces": self.faces,
            "periodic": self.periodic,
        }
        if self.data is not None:
            out["data"] = self.data
        return out

    @classmethod
    def from_json(cls, data: Json, where: str) -> ScaffoldInfo:
        """Read the ``scaffold`` entry of ``where``'s metadata."""
        info = json_object(data, f"{where}: the scaffold in its 'lkspace' metadata")
        edges = info.get("edges")
        if isinstance(edges, bool) or not isinstance(edges, int) or edges < 1:
            raise CatalogError(f"{where}: the 'lkspace' metadata has no usable scaffold edges or mode (damaged)")
        what = f"{where}: the scaffold in its 'lkspace' metadata:"
        geometry = info.get("data")
        return cls(
            _str(info, "name", what),
            _str(info, "content_hash", what),
            edges,
            _int(info, "faces", what, 1),
            _bool(info, "periodic", what),
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
        return cls(
            _optional_int(filters, "components", what),
            _bool(filters, "no_zero", what),
            _optional_int(filters, "max_designs", what),
        )


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
    """

    format_version: int
    scaffold: ScaffoldInfo
    label_set: tuple[int, ...]
    symmetry: SymmetryMode
    symmetry_tolerance: float | None | Unrecorded
    group_order: int
    acting_order: int
    assignments: int
    mode: WalkMode
    filters: Filters
    sample: int | None
    seed: int | None
    canonical_rule: str
    invariant: JsonObject | None = None

    def to_json(self) -> JsonObject:
        """JSON form (``symmetry_tolerance`` and ``invariant`` left out when absent)."""
        out: JsonObject = {
            "format_version": self.format_version,
            "scaffold": self.scaffold.to_json(),
            "label_set": list(self.label_set),
            "symmetry": self.symmetry,
        }
        if not isinstance(self.symmetry_tolerance, Unrecorded):
            out["symmetry_tolerance"] = self.symmetry_tolerance
        out.update(
            group_order=self.group_order,
            acting_order=self.acting_order,
            assignments=self.assignments,
            mode=self.mode,
            filters=self.filters.to_json(),
            sample=self.sample,
            seed=self.seed,
            canonical_rule=self.canonical_rule,
        )
        if self.invariant is not None:
            out["invariant"] = self.invariant
        return out

    @classmethod
    def from_json(cls, data: Json, where: str) -> CatalogMetadata:
        """Read the settings of ``where``'s ``lkspace`` metadata (or manifest)."""
        meta = _header(data, where)
        labels = meta["label_set"]
        if not isinstance(labels, list) or not all(isinstance(t, int) and not isinstance(t, bool) for t in labels):
            raise CatalogError(f"{where}: label_set {_shown(labels)} is not a list of integers (damaged)")
        symmetry, mode = meta.get("symmetry"), meta.get("mode")
        if symmetry not in MODES:
            raise CatalogError(f"{where}: symmetry {_shown(symmetry)} is not one of {', '.join(MODES)} (damaged)")
        if mode not in WALK_MODES:
            raise CatalogError(f"{where}: the 'lkspace' metadata has no usable scaffold edges or mode (damaged)")
        invariant = meta.get("invariant")
        return cls(
            _int(meta, "format_version", where),
            ScaffoldInfo.from_json(meta["scaffold"], where),
            tuple(t for t in labels if isinstance(t, int)),
            symmetry,
            _tolerance(meta, where),
            _int(meta, "group_order", where, 1),
            _int(meta, "acting_order", where, 1),
            _int(meta, "assignments", where, 0),
            mode,
            Filters.from_json(meta.get("filters"), where),
            _optional_int(meta, "sample", where),
            _optional_int(meta, "seed", where),
            _str(meta, "canonical_rule", where),
            None if invariant is None else json_object(invariant, f"{where}: invariant"),
        )


def _tolerance(meta: JsonObject, where: str) -> float | None | Unrecorded:
    if "symmetry_tolerance" not in meta:
        return UNRECORDED
    value = meta["symmetry_tolerance"]
    if value is not None and (isinstance(value, bool) or not isinstance(value, int | float)):
        raise CatalogError(f"{where}: symmetry_tolerance {_shown(value)} is not a number (damaged)")
    return value


@dataclass(frozen=True)
class Shard:
    """The ``shard`` entry of a file: which part of how many, of which plan and run.

    ``run`` is ``None`` for a one-file catalog.
    """

    index: int
    count: int
    plan: str
    run: str | None = None

    def to_json(self) -> JsonObject:
        """JSON form (``run`` left out for a one-file catalog)."""
        out: JsonObject = {"index": self.index, "count": self.count, "plan": self.plan}
        if self.run is not None:
            out["run"] = self.run
        return out

    @classmethod
    def from_json(cls, data: Json, where: str) -> Shard:
        """Read the ``shard`` entry of ``where``'s metadata."""
        what = f"{where}: the shard in its 'lkspace' metadata:"
        shard = json_object(data, what[:-1])
        run = shard.get("run")
        if run is not None and not isinstance(run, str):
            raise CatalogError(f"{what} run {_shown(run)} is not a string (damaged)")
        return cls(_int(shard, "index", what, 0), _int(shard, "count", what, 1), _str(shard, "plan", what), run)


@dataclass(frozen=True)
class PartSummary:
    """Totals of one written catalog file (a part, or a one-file catalog).

    Attributes
    ----------
    by_components : dict of str -> int
        Rows by number of components (keys are decimal strings, as in JSON).
    assignments_covered : int
        Assignments the rows stand for (-1: past 64 bits).
    rows : int
        Rows written.
    file : str or None
        The part's file name in its folder (``None``: a footer's totals).
    sha256 : str or None
        Hex SHA-256 of the file's bytes (``None``: a footer's totals).
    """

    by_components: dict[str, int]
    assignments_covered: int
    rows: int
    file: str | None = None
    sha256: str | None = None

    def to_json(self) -> JsonObject:
        """JSON form (the manifest's entry of a part; a footer's totals without ``file``)."""
        by: JsonObject = dict(self.by_components)
        out: JsonObject = {"by_components": by, "assignments_covered": self.assignments_covered, "rows": self.rows}
        if self.file is not None:
            out.update(file=self.file, sha256=self.sha256)
        return out

    @classmethod
    def from_json(cls, data: Json, where: str) -> PartSummary:
        """Read a manifest entry or a footer's totals (``where`` names it)."""
        entry = json_object(data, where)
        by = json_object(entry.get("by_components"), f"{where}: by_components")
        counts = {k: v for k, v in by.items() if isinstance(v, int) and not isinstance(v, bool)}
        if len(counts) != len(by) or not all(k.isdigit() for k in by):
            raise CatalogError(f"{where}: by_components {_shown(by)} is not counts by components (damaged)")
        rows = entry.get("rows")
        if isinstance(rows, bool) or not isinstance(rows, int) or rows < 0:
            raise CatalogError(f"{where}: damaged: its metadata says {rows!r} rows")
        file, sha = entry.get("file"), entry.get("sha256")
        if (file is None) != (sha is None) or not isinstance(file, str | None) or not isinstance(sha, str | None):
            raise CatalogError(f"{where}: file {_shown(file)} and sha256 {_shown(sha)} are malformed (damaged)")
        return cls(counts, _int(entry, "assignments_covered", where, -1), rows, file, sha)


@dataclass(frozen=True)
class PartFooter:
    """The ``lkspace`` metadata of one catalog file, as its Arrow schema and its Parquet footer hold it.

    The schema holds the settings and the shard; the footer adds the file's totals, a
    ``digest`` of the rest (:func:`metadata_digest`, checked when read, written by
    :meth:`to_json`) and, after an identification pass, ``"identified": true``.

    Attributes
    ----------
    settings : CatalogMetadata
    shard : Shard or None
        ``None``: a symmetric catalog (one file, no shard).
    totals : PartSummary or None
        ``None`` in the schema's copy, written before the rows.
    identified : bool
        Whether the knot/link columns are there (:mod:`lkspace.catalog.identified`).
    """

    settings: CatalogMetadata
    shard: Shard | None = None
    totals: PartSummary | None = None
    identified: bool = False

    def to_json(self) -> JsonObject:
        """JSON form: settings, ``shard``, totals, ``digest`` (with totals), ``identified`` (when true)."""
        out = self.settings.to_json()
        if self.shard is not None:
            out["shard"] = self.shard.to_json()
        if self.totals is not None:
            out.update(self.totals.to_json())
            out["digest"] = metadata_digest({**out, **({"identified": True} if self.identified else {})})
        if self.identified:
            out["identified"] = True
        return out

    def encode(self) -> bytes:
        """Return the bytes stored under the Parquet key ``lkspace``."""
        return json.dumps(self.to_json()).encode()

    def has_settings(self, settings: CatalogMetadata, shard: Shard | None) -> bool:
        """Whether this file was written with ``settings`` as part ``shard`` (:func:`same_settings`)."""
        return self.shard == shard and same_settings(self.settings.to_json(), settings.to_json())

    @classmethod
    def from_json(cls, data: Json, where: str) -> PartFooter:
        """Read the ``lkspace`` metadata of the file ``where``; a footer's ``digest`` is checked."""
        meta = _header(data, where)
        digest = meta.get("digest")
        if digest is not None and digest != metadata_digest(meta):
            raise CatalogError(
                f"{where}: damaged: its 'lkspace' metadata does not match the digest it was written with"
            )
        shard = meta.get("shard")
        return cls(
            CatalogMetadata.from_json(meta, where),
            None if shard is None else Shard.from_json(shard, where),
            PartSummary.from_json(meta, where) if "rows" in meta else None,
            meta.get("identified") is True,
        )


@dataclass(frozen=True)
class Signature:
    """The settings of a run, at the head of its manifest: a run resumes only a build of the same signature.

    Attributes
    ----------
    settings : CatalogMetadata
    shards : int
        Parts of the catalog.
    plan : str or None
        The plan's fingerprint (:attr:`~lkspace.catalog.plan.Plan.fingerprint`; ``None``: a URL catalog).
    identify : bool or None
        Whether the run adds knot/link columns (``None``: a URL catalog).
    """

    settings: CatalogMetadata
    shards: int
    plan: str | None = None
    identify: bool | None = None

    def to_json(self) -> JsonObject:
        """JSON form: the settings' keys, then ``shards``, ``plan`` and ``identify``."""
        out = self.settings.to_json()
        out["shards"] = self.shards
        if self.plan is not None:
            out["plan"] = self.plan
        if self.identify is not None:
            out["identify"] = self.identify
        return out

    def resumes(self, old: Signature) -> bool:
        """Whether a build of the signature ``old`` can be finished by a run of this one."""
        return same_settings(old.to_json(), self.to_json())


@dataclass(frozen=True)
class Manifest:
    """The manifest ``_lkspace.json`` of a catalog folder (or of a build in progress).

    Attributes
    ----------
    signature : Signature
        The run's settings.
    run : str
        The run id, in every part's name and footer.
    parts : dict of int -> PartSummary
        The finished parts (with ``file`` and ``sha256``) by part index, in the order they finished.
    complete : bool
        Whether every part is there (written last).
    """

    signature: Signature
    run: str
    parts: dict[int, PartSummary] = field(default_factory=dict)
    complete: bool = False

    def to_json(self) -> JsonObject:
        """JSON form: the signature's keys, then ``run``, ``parts`` and (when complete) ``complete``."""
        out = self.signature.to_json()
        parts: JsonObject = {str(i): p.to_json() for i, p in self.parts.items()}
        out.update(run=self.run, parts=parts)
        if self.complete:
            out["complete"] = True
        return out

    def encode(self) -> str:
        """Return the text of ``_lkspace.json``."""
        return json.dumps(self.to_json(), indent=1)

    @classmethod
    def from_json(cls, data: Json, where: str) -> Manifest:
        """Read the manifest ``where``: the settings, a run id and well-formed parts numbered below ``shards``."""
        meta = _header(data, where)
        settings = CatalogMetadata.from_json(meta, where)
        entries, count = meta.get("parts"), meta.get("shards")
        if not isinstance(entries, dict) or isinstance(count, bool) or not isinstance(count, int) or count < 1:
            raise CatalogError(f"{where}: no part list (damaged manifest)")
        if not all(k.isdigit() and k == str(int(k)) and int(k) < count for k in entries):
            raise CatalogError(f"{where}: the parts are not numbered 0..{count - 1} (damaged manifest)")
        run, plan, identify = meta.get("run"), meta.get("plan"), meta.get("identify")
        if not isinstance(run, str) or not isinstance(plan, str | None) or not isinstance(identify, bool | None):
            raise CatalogError(f"{where}: no run id, plan or identify setting (damaged manifest)")
        parts = {int(index): _entry(entry, index, where) for index, entry in entries.items()}
        return cls(Signature(settings, count, plan, identify), run, parts, meta.get("complete") is True)


def _entry(data: Json, index: str, where: str) -> PartSummary:
    """Read the manifest entry of part ``index``: totals, a plain ``.parquet`` file name and its SHA-256."""
    malformed = f"{where}: the entry of part {index} is malformed (damaged manifest)"
    try:
        part = PartSummary.from_json(data, where)
    except CatalogError:
        raise CatalogError(malformed) from None
    name = part.file
    if name is None or name != os.path.basename(name) or not name.endswith(".parquet"):
        raise CatalogError(malformed)
    return part
