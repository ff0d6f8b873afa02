"""The catalog's wire formats for files and folders: the part footer and the manifest.

Each is a frozen record with one validating ``from_json`` and one ``to_json``, used by
every reader and writer of that format (the settings they share are
:class:`~lkspace.catalog.metadata.CatalogMetadata`):

- :class:`PartFooter`: the ``lkspace`` key of a Parquet file: the settings, the file's
  :class:`Shard` and, in the footer, its totals (:class:`PartSummary`) and ``digest``;
- :class:`Manifest`: ``_lkspace.json`` of a folder: the run's :class:`Signature`, its run
  id and the finished parts.

``to_json`` writes the keys in the order lkspace has always written them; ``from_json``
refuses anything else with a one-line :class:`~lkspace.errors.CatalogError` naming the
file (``where``) and what is wrong.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field

from ..errors import CatalogError
from .metadata import (
    LATER_KEYS,
    CatalogMetadata,
    Json,
    JsonObject,
    Unrecorded,
    checked_header,
    count_field,
    json_object,
    metadata_digest,
    put,
    recorded,
    same_settings,
    shown,
    text_field,
)


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
            raise CatalogError(f"{what} run {shown(run)} is not a string (damaged)")
        return cls(
            count_field(shard, "index", what, 0),
            count_field(shard, "count", what, 1),
            text_field(shard, "plan", what),
            run,
        )


@dataclass(frozen=True)
class PartSummary:
    """Totals of one written catalog file (a part, or a one-file catalog).

    Attributes
    ----------
    by_components : dict of str -> int, or UNRECORDED
        Rows by number of components (keys are decimal strings, as in JSON).
    assignments_covered : int or UNRECORDED
        Assignments the rows stand for (-1: past 64 bits).
    rows : int
        Rows written.
    file : str or None
        The part's file name in its folder (``None``: a footer's totals).
    sha256 : str or None
        Hex SHA-256 of the file's bytes (``None``: a footer's totals).
    """

    by_components: dict[str, int] | Unrecorded
    assignments_covered: int | Unrecorded
    rows: int
    file: str | None = None
    sha256: str | None = None

    @property
    def counted(self) -> bool:
        """Whether the totals by components and of assignments are recorded (lkspace writes them)."""
        return not isinstance(self.by_components, Unrecorded) and not isinstance(self.assignments_covered, Unrecorded)

    def counts(self) -> tuple[dict[str, int], int]:
        """Return ``(by_components, assignments_covered)``; a part without them is not kept (:attr:`counted`)."""
        if isinstance(self.by_components, Unrecorded) or isinstance(self.assignments_covered, Unrecorded):
            raise CatalogError(f"{self.file}: its totals by components are not recorded (damaged)")
        return self.by_components, self.assignments_covered

    def to_json(self) -> JsonObject:
        """JSON form (the manifest's entry of a part; a footer's totals without ``file``)."""
        by = self.by_components if isinstance(self.by_components, Unrecorded) else dict[str, Json](self.by_components)
        out = put({}, by_components=by, assignments_covered=self.assignments_covered, rows=self.rows)
        if self.file is not None:
            out.update(file=self.file, sha256=self.sha256)
        return out

    @classmethod
    def from_json(cls, data: Json, where: str) -> PartSummary:
        """Read a manifest entry or a footer's totals (``where`` names it)."""
        entry = json_object(data, where)
        rows = entry.get("rows")
        if isinstance(rows, bool) or not isinstance(rows, int) or rows < 0:
            raise CatalogError(f"{where}: damaged: its metadata says {rows!r} rows")
        file, sha = entry.get("file"), entry.get("sha256")
        if (file is None) != (sha is None) or not isinstance(file, str | None) or not isinstance(sha, str | None):
            raise CatalogError(f"{where}: file {shown(file)} and sha256 {shown(sha)} are malformed (damaged)")
        covered = recorded(entry, "assignments_covered", count_field, where)
        return cls(recorded(entry, "by_components", _counts, where), covered, rows, file, sha)


def _counts(entry: JsonObject, key: str, where: str) -> dict[str, int]:
    by = json_object(entry[key], f"{where}: {key}")
    counts = {k: v for k, v in by.items() if isinstance(v, int) and not isinstance(v, bool)}
    if len(counts) != len(by) or not all(k.isdigit() for k in by):
        raise CatalogError(f"{where}: {key} {shown(by)} is not counts by components (damaged)")
    return counts


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
    by_key : bool
        Whether they were named by key only (``"named_by": "key"``; :class:`~lkspace.catalog.options.Selection`).
    sealed : bool
        Whether the metadata read carried its ``digest`` (lkspace writes one with the totals;
        without it an edit cannot be told: removed, or an older lkspace wrote the file).
    """

    settings: CatalogMetadata
    shard: Shard | None = None
    totals: PartSummary | None = None
    identified: bool = False
    by_key: bool = False
    sealed: bool = field(default=True, compare=False)

    def to_json(self) -> JsonObject:
        """JSON form: settings, ``shard``, totals, ``digest`` (with totals), ``identified`` (when true)."""
        out = self.settings.to_json()
        if self.shard is not None:
            out["shard"] = self.shard.to_json()
        if self.by_key:
            out["named_by"] = "key"
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
        """Read the ``lkspace`` metadata of the file ``where``; a footer's ``digest`` is checked.

        A footer with a digest must record every setting: lkspace sealed footers only after it
        recorded the :data:`~lkspace.catalog.metadata.LATER_KEYS` (an older catalog lacks both).
        """
        meta = checked_header(data, where)
        digest = meta.get("digest")
        if digest is not None and digest != metadata_digest(meta):
            raise CatalogError(
                f"{where}: damaged: its 'lkspace' metadata does not match the digest it was written with"
            )
        missing = [k for k in LATER_KEYS if k not in meta]
        if digest is not None and missing:  # every lkspace that seals its footers records them
            raise CatalogError(f"{where}: damaged: its 'lkspace' metadata has a digest but no {missing[0]}")
        shard = meta.get("shard")
        return cls(
            CatalogMetadata.from_json(meta, where),
            None if shard is None else Shard.from_json(shard, where),
            PartSummary.from_json(meta, where) if "rows" in meta else None,
            meta.get("identified") is True,
            meta.get("named_by") == "key",
            digest is not None,
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
    by_key : bool
        Whether it names them by key only (``"named_by": "key"``).
    """

    settings: CatalogMetadata
    shards: int
    plan: str | None = None
    identify: bool | None = None
    by_key: bool = False

    def to_json(self) -> JsonObject:
        """JSON form: the settings' keys, then ``shards``, ``plan``, ``identify`` and ``named_by`` (by key only)."""
        out = self.settings.to_json()
        out["shards"] = self.shards
        if self.plan is not None:
            out["plan"] = self.plan
        if self.identify is not None:
            out["identify"] = self.identify
        if self.by_key:
            out["named_by"] = "key"
        return out

    def resumes(self, old: Signature) -> bool:
        """Whether a build of the signature ``old`` can be finished by a run of this one (named alike)."""
        return same_settings(old.to_json(), self.to_json()) and old.by_key == self.by_key


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
        meta = checked_header(data, where)
        settings = CatalogMetadata.from_json(meta, where)
        entries, count = meta.get("parts"), meta.get("shards")
        if not isinstance(entries, dict) or isinstance(count, bool) or not isinstance(count, int) or count < 1:
            raise CatalogError(f"{where}: no part list (damaged manifest)")
        if not all(k.isdigit() and k == str(int(k)) and int(k) < count for k in entries):
            raise CatalogError(f"{where}: the parts are not numbered 0..{count - 1} (damaged manifest)")
        run, plan, identify = meta.get("run"), meta.get("plan"), meta.get("identify")
        if not isinstance(run, str) or not isinstance(plan, str | None) or not isinstance(identify, bool | None):
            raise CatalogError(f"{where}: no run id, plan or identify setting (damaged manifest)")
        if (plan is None) != (identify is None):  # both absent only for a catalog written to a URL
            raise CatalogError(f"{where}: no run id, plan or identify setting (damaged manifest)")
        parts = {int(index): _entry(entry, index, where) for index, entry in entries.items()}
        signature = Signature(settings, count, plan, identify, meta.get("named_by") == "key")
        return cls(signature, run, parts, meta.get("complete") is True)


def _entry(data: Json, index: str, where: str) -> PartSummary:
    """Read the manifest entry of part ``index``: totals, a plain ``.parquet`` file name and its SHA-256."""
    malformed = f"{where}: the entry of part {index} is malformed (damaged manifest)"
    try:
        part = PartSummary.from_json(data, where)
    except CatalogError:
        raise CatalogError(malformed) from None
    name, sha = part.file, part.sha256
    if name is None or name != os.path.basename(name) or not name.endswith(".parquet"):
        raise CatalogError(malformed)
    if sha is None or len(sha) != 64 or not all(c in "0123456789abcdef" for c in sha):
        raise CatalogError(malformed)
    return part
