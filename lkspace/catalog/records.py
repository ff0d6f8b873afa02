"""The records a catalog run keeps on disk: each part's totals and the manifest of a folder.

Both are JSON in the files (``_lkspace.json``, Parquet footers) and frozen dataclasses in
memory; :meth:`to_json` writes the keys in the order lkspace has always written them, so
a build interrupted by an earlier version resumes, and :meth:`from_json` returns ``None``
for a record it cannot read (a damaged manifest keeps no parts; nothing is guessed).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any


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
        The part's file name in its folder (``None`` for a one-file catalog).
    sha256 : str or None
        Hex SHA-256 of the file's bytes (``None`` for a one-file catalog).
    """

    by_components: dict[str, int]
    assignments_covered: int
    rows: int
    file: str | None = None
    sha256: str | None = None

    def to_json(self) -> dict[str, Any]:
        """JSON form (the manifest's entry of a part)."""
        out: dict[str, Any] = {
            "by_components": self.by_components,
            "assignments_covered": self.assignments_covered,
            "rows": self.rows,
        }
        if self.file is not None:
            out.update(file=self.file, sha256=self.sha256)
        return out

    @classmethod
    def from_json(cls, data: object) -> PartSummary | None:
        """Read a manifest entry or a file's footer metadata; ``None`` when it is not one."""
        if not isinstance(data, dict):
            return None
        by, covered, rows = data.get("by_components"), data.get("assignments_covered"), data.get("rows")
        file, sha = data.get("file"), data.get("sha256")
        if not isinstance(by, dict) or not isinstance(covered, int) or not isinstance(rows, int):
            return None
        if not all(isinstance(k, str) and isinstance(v, int) for k, v in by.items()):
            return None
        if not (file is None or isinstance(file, str)) or not (sha is None or isinstance(sha, str)):
            return None
        return cls(dict(by), covered, rows, file, sha)


@dataclass(frozen=True)
class Manifest:
    """The manifest ``_lkspace.json`` of a catalog folder (or of a build in progress).

    Attributes
    ----------
    signature : dict
        The run's settings: the catalog metadata, ``shards`` and, for local runs, the
        plan's fingerprint ``plan`` and ``identify``.  A run resumes only a build of the
        same signature.
    run : str
        The run id, in every part's name and footer.
    parts : dict of str -> PartSummary
        The finished parts, keyed by part index (a decimal string).
    complete : bool
        Whether every part is there (written last).
    """

    signature: dict[str, Any]
    run: str
    parts: dict[str, PartSummary] = field(default_factory=dict)
    complete: bool = False

    def to_json(self) -> dict[str, Any]:
        """JSON form: the signature's keys, then ``run``, ``parts`` and (when complete) ``complete``."""
        out = {**self.signature, "run": self.run, "parts": {k: p.to_json() for k, p in self.parts.items()}}
        if self.complete:
            out["complete"] = True
        return out

    @classmethod
    def from_json(cls, data: object) -> Manifest | None:
        """Read a manifest's JSON; ``None`` when it is not one (parts it cannot read are left out)."""
        if not isinstance(data, dict) or not isinstance(data.get("run"), str):
            return None
        entries = data.get("parts")
        parts = {}
        for index, entry in (entries if isinstance(entries, dict) else {}).items():
            part = PartSummary.from_json(entry)
            if part is not None and part.file is not None:
                parts[str(index)] = part
        signature = {k: v for k, v in data.items() if k not in ("run", "parts", "complete")}
        return cls(signature, data["run"], parts, data.get("complete") is True)
