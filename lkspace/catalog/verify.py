"""Opening a catalog for reading: checking that it is the catalog it says it is.

Every reader of lkspace (:func:`~lkspace.catalog.reader.read_catalog`, ``export`` and
``identify --row``, the studio's catalog browser, ``atlas CATALOG``) opens a catalog
with :func:`open_catalog`, which checks, reading only the manifest and the Parquet
footers:

- a **file**: its footer reads (a truncated file's does not); its ``lkspace`` metadata is
  a JSON object of a known ``format_version``; its ``rows`` are the rows the file holds;
  its metadata matches the ``digest`` recorded with it; it is a whole catalog (not one
  part of a folder); its columns are a catalog's (names and types, ``key`` as wide as
  the scaffold has edges);
- a **folder**: its manifest ``_lkspace.json`` is such a JSON object, complete, listing
  parts ``0 .. n-1`` with their rows and SHA-256; the Parquet files in the folder are
  exactly the listed ones (a missing part, or an extra one that pandas would read as
  well, is refused); each part's footer names this catalog's run, its own part number
  and the part count, the manifest's settings and the manifest's rows (a swapped,
  renamed or foreign part is refused).

:meth:`CatalogParts.verify` then checks a part's bytes against the SHA-256 the manifest
recorded (a bit flip anywhere): ``read_catalog``, the browser and :func:`verify_catalog`
check every part, ``--row`` the part it reads.  Data pages also carry CRC-32 checksums
that pyarrow verifies as lkspace reads them (the only check of a one-file catalog's
rows).  Each refusal is a :class:`~lkspace.errors.CatalogError` of one line naming the
file and what is wrong.
"""

from __future__ import annotations

import os
import warnings
from dataclasses import dataclass
from typing import Literal

import pyarrow as pa
import pyarrow.parquet as pq

from ..errors import CatalogError, LkspaceWarning
from .metadata import LATER_KEYS, CatalogMetadata, Filters, JsonObject, decode
from .records import Manifest, PartFooter, PartSummary
from .schema import IDENTIFY_COLUMNS, METADATA_KEY, expected_schema
from .settings import catalog_scaffold, check_settings, check_totals
from .transaction import MANIFEST, check_regular, file_sha256


@dataclass(frozen=True, eq=False)
class CatalogParts:
    """A catalog whose structure was checked: its files in order and what each holds.

    Attributes
    ----------
    path : str
        The catalog file or folder.
    files : tuple of str
        The catalog file, or the parts of a folder in order.
    rows : tuple of int
        Rows of each file (footer and manifest agree).
    footer : PartFooter
        The ``lkspace`` metadata of the first file (with that file's totals).
    checksums : tuple of str, optional
        The manifest's SHA-256 of each part; ``None`` for a one-file catalog.
    run : str, optional
        The run id of a folder's parts; ``None`` for a one-file catalog.
    totals : tuple of PartSummary
        What each file says it holds: rows, rows by components, assignments covered (a
        folder's manifest and the part footers agree).
    unsealed : str, optional
        The first file whose metadata has no ``digest`` (:attr:`PartFooter.sealed`); ``None``: none.
    unidentified : str, optional
        The first part without knot/link columns when the manifest says its run identified them all,
        or named otherwise (by key only, or in full) than the manifest says (an edited manifest, or a
        folder still being identified); ``None``: none.
    """

    path: str
    files: tuple[str, ...]
    rows: tuple[int, ...]
    footer: PartFooter
    checksums: tuple[str, ...] | None
    totals: tuple[PartSummary, ...]
    run: str | None = None
    unsealed: str | None = None
    unidentified: str | None = None

    @property
    def n_rows(self) -> int:
        """Rows of the whole catalog."""
        return sum(self.rows)

    def locate(self, row: int) -> tuple[int, int]:
        """Return ``(part, row within the part)`` of catalog row ``row`` (``IndexError`` past the end)."""
        first = 0
        for part, n in enumerate(self.rows):
            if row < first + n:
                return part, row - first
            first += n
        raise IndexError(row)

    def verify(self, part: int) -> None:
        """Check the bytes of ``part`` against the manifest's SHA-256 (nothing to check for one file)."""
        if self.checksums is not None and file_sha256(self.files[part]) != self.checksums[part]:
            raise CatalogError(
                f"{self.files[part]}: damaged: its SHA-256 is not the one the manifest recorded "
                "(changed bytes, or a file put in its place)"
            )

    def verify_all(self) -> None:
        """Check every part's SHA-256."""
        for part in range(len(self.files)):
            self.verify(part)


def file_metadata(file: str) -> tuple[PartFooter, int]:
    """Return the ``lkspace`` footer metadata of the Parquet ``file`` and its rows, checked as one file.

    ``FileNotFoundError`` propagates (a catalog replaced while read); anything else wrong
    is a :class:`~lkspace.errors.CatalogError`.
    """
    check_regular(file)
    try:
        info = pq.read_metadata(file)
        raw = (info.metadata or {}).get(METADATA_KEY)
        schema = info.schema.to_arrow_schema()
    except FileNotFoundError:
        raise
    except (OSError, ValueError, pa.ArrowException) as exc:  # ValueError: names that are not UTF-8
        reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise CatalogError(f"{file}: damaged or not Parquet (truncated?): its footer does not read: {reason}") from None
    if raw is None:
        raise CatalogError(f"{file}: no 'lkspace' metadata; not an lkspace catalog")
    footer = PartFooter.from_json(decode(raw, file), file)
    rows = footer.totals.rows if footer.totals is not None else None
    if rows != info.num_rows:
        raise CatalogError(f"{file}: damaged: its metadata says {rows!r} rows, the file holds {info.num_rows:,}")
    _check_columns(file, schema.remove_metadata(), footer.settings)
    return footer, info.num_rows


def _check_columns(file: str, schema: pa.Schema, settings: CatalogMetadata) -> None:
    """Raise unless ``schema`` is the one a catalog of ``settings`` has (``--identify`` columns after it)."""
    expected = expected_schema(settings)
    fields = list(schema)
    for i, field in enumerate(fields):
        want = expected.field(i).type if i < len(expected) else IDENTIFY_COLUMNS.get(field.name)
        if (i < len(expected) and field.name != expected.field(i).name) or field.type != want:
            raise CatalogError(
                f"{file}: damaged or not an lkspace catalog: column {i} is {field.name!r} ({field.type}), "
                f"not a catalog's {expected.field(i).name if i < len(expected) else 'identify column'}"
            )
    if len(fields) < len(expected):
        raise CatalogError(f"{file}: damaged or not an lkspace catalog: no column {expected.field(len(fields)).name!r}")


def open_catalog(path: str | os.PathLike[str]) -> CatalogParts:
    """Open the catalog file or folder at ``path`` and check its structure (module docstring).

    A file whose metadata has no ``digest`` is read with a warning (its metadata cannot be
    checked); :func:`verify_catalog` refuses it.

    Raises
    ------
    CatalogError
        One line naming the file and what is wrong with it.
    """
    parts = _structure(os.fspath(path))
    if parts.unsealed is not None:
        warnings.warn(LkspaceWarning(unsealed(parts.unsealed) + "; read as it stands"), stacklevel=2)
    return parts


def unsealed(file: str) -> str:
    """Say that the metadata of ``file`` has no digest, so an edit of it cannot be told."""
    return (
        f"{file}: its 'lkspace' metadata has no digest (removed, or written by an lkspace from before "
        "2026-12-02), so a change to it cannot be detected"
    )


def _structure(path: str) -> CatalogParts:
    """Open the catalog at ``path`` as :func:`open_catalog` does, without the warning."""
    if os.path.isdir(path):
        return _open_folder(path)
    if not os.path.exists(path):
        raise CatalogError(f"{path}: no such catalog")
    footer, rows = file_metadata(path)
    shard = footer.shard
    if shard is not None and shard.count != 1:
        raise CatalogError(
            f"{path}: part {shard.index} of a catalog of {shard.count} parts, not a whole catalog; "
            "open the folder it belongs to"
        )
    if shard is not None and shard.index != 0:
        raise CatalogError(f"{path}: damaged: its metadata calls it part {shard.index} of a one-part catalog")
    totals = (footer.totals,) if footer.totals is not None else ()
    return CatalogParts(path, (path,), (rows,), footer, None, totals, None, None if footer.sealed else path)


def _manifest(folder: str) -> Manifest:
    """Read the manifest of the catalog ``folder``: well formed (:meth:`Manifest.from_json`) and complete."""
    where = os.path.join(folder, MANIFEST)
    try:
        check_regular(where, "manifest")
        with open(where, "rb") as fh:
            raw = fh.read()
    except FileNotFoundError:
        raise CatalogError(
            f"{folder}: no manifest {MANIFEST}: not a finished lkspace catalog "
            "(an interrupted run is finished by running it again with `resume=True`)"
        ) from None
    except OSError as exc:
        raise CatalogError(f"{where}: cannot read: {exc.strerror}") from None
    manifest = Manifest.from_json(decode(raw, where), where)
    count = manifest.signature.shards
    if not manifest.complete or len(manifest.parts) != count:
        raise CatalogError(f"{folder}: an unfinished catalog ({len(manifest.parts)} of {count} parts)")
    return manifest


def _same_catalog(part: CatalogMetadata, manifest: CatalogMetadata) -> bool:
    """Whether a part and its manifest record the same catalog: every setting, the counts among them too.

    ``assignments``, ``group_order``, ``acting_order`` and ``canonical_rule`` included (an
    edited manifest count read as intact, issue 35).  A setting recorded since
    (:data:`~lkspace.catalog.metadata.LATER_KEYS`) is compared only where both record it:
    a resumed build keeps the parts of an earlier version beside new ones.
    """
    ours, theirs = part.to_json(), manifest.to_json()
    for key in LATER_KEYS:
        if key not in ours:
            theirs.pop(key, None)
    return ours == theirs


def _open_folder(folder: str) -> CatalogParts:
    manifest = _manifest(folder)
    count, run = manifest.signature.shards, manifest.run
    entries = [manifest.parts[i] for i in range(count)]
    listed = [str(e.file) for e in entries]
    present = {p for p in os.listdir(folder) if p.endswith(".parquet") and not p.startswith((".", "_"))}
    for i, name in enumerate(listed):
        if name not in present:
            raise CatalogError(f"{os.path.join(folder, name)}: missing: the manifest lists it as part {i} of {count}")
    extra = sorted(present - set(listed))
    if extra:
        raise CatalogError(
            f"{os.path.join(folder, extra[0])}: not a part of this catalog (its manifest does not list it, "
            "but pandas and Dask would read it): remove it"
        )
    footers = [part_footer(os.path.join(folder, name), i, manifest) for i, name in enumerate(listed)]
    files = tuple(os.path.join(folder, name) for name in listed)
    rows = tuple(e.rows for e in entries)
    loose = next((f for f, footer in zip(files, footers, strict=True) if not footer.sealed), None)
    sign = manifest.signature
    plain = next(
        (f for f, ft in zip(files, footers, strict=True) if not ft.identified or ft.by_key != sign.by_key), None
    )
    plain = plain if sign.identify else None
    checksums = tuple(str(e.sha256) for e in entries)
    return CatalogParts(folder, files, rows, footers[0], checksums, tuple(entries), run, loose, plain)


def part_footer(file: str, i: int, manifest: Manifest) -> PartFooter:
    """Return the footer of ``file``, checked to be part ``i`` of the catalog of ``manifest``.

    Its run, plan, settings and part number are the manifest's, and its totals (rows, rows
    by components, assignments covered) are the ones the manifest lists for part ``i``.
    """
    footer, rows = file_metadata(file)
    count, run, shard = manifest.signature.shards, manifest.run, footer.shard
    other = run if shard is None or shard.run is None else shard.run
    if other != run:
        raise CatalogError(f"{file}: a part of another catalog (run {other}, not {run}): replaced")
    plan = None if shard is None else shard.plan
    if plan != manifest.signature.plan or not _same_catalog(footer.settings, manifest.signature.settings):
        raise CatalogError(f"{file}: a part of another catalog (scaffold, label set or settings differ)")
    if shard is None or shard.index != i or shard.count != count:
        where = "no part" if shard is None else f"part {shard.index} of {shard.count}"
        raise CatalogError(
            f"{file}: holds {where}, but the manifest lists it as part {i} of {count}: parts swapped or renamed"
        )
    listed = manifest.parts[i]
    if rows != listed.rows:
        raise CatalogError(f"{file}: holds {rows:,} rows, the manifest says {listed.rows:,}: replaced or damaged")
    totals = footer.totals
    if totals is not None and (totals.by_components, totals.assignments_covered) != (
        listed.by_components,
        listed.assignments_covered,
    ):
        raise CatalogError(
            f"{file}: the manifest's totals of part {i} (rows by components, assignments covered) are not the "
            "ones the part records: the manifest was edited or damaged"
        )
    return footer


Checks = Literal[
    "manifest, part footers, SHA-256 of every part",
    "footer, CRC-32 of every data page",
    "footer, CRC-32 of every data page, every row recomputed (DNA designs)",
]
"""What :func:`verify_catalog` checked: a folder's part checksums, or a file's page checksums (and a DNA catalog's rows)."""


@dataclass(frozen=True)
class CatalogCheck:
    """What :func:`verify_catalog` found: an intact catalog's size and identity.

    Attributes
    ----------
    path : str
        The catalog (a file or a folder).
    rows, parts : int
        Rows of the whole catalog, and its files (1 for a one-file catalog).
    format_version : int
    scaffold : str
        The scaffold's name.
    run : str or None
        The run id of a folder's parts (``None`` for a one-file catalog).
    checks : str
        What was checked (:data:`Checks`).
    """

    path: str
    rows: int
    parts: int
    format_version: int
    scaffold: str
    run: str | None
    checks: Checks

    def to_dict(self) -> JsonObject:
        """JSON form (``lkspace verify --json``)."""
        return {
            "path": self.path,
            "rows": self.rows,
            "parts": self.parts,
            "format_version": self.format_version,
            "scaffold": self.scaffold,
            "run": self.run,
            "checks": self.checks,
        }


def verify_catalog(path: str | os.PathLike[str]) -> CatalogCheck:
    """Check a catalog completely before reading it with pandas, pyarrow or Dask.

    The structure as :func:`open_catalog` checks it, then every part's SHA-256 (a folder)
    or every data page's CRC-32 (a file written with page checksums); a DNA catalog's rows
    are recomputed from its settings and must be exactly its buildable designs
    (:func:`~lkspace.catalog.dna_rows.check_dna_rows`).  Returns a
    :class:`CatalogCheck`; raises :class:`~lkspace.errors.CatalogError` (one line) otherwise.

    Examples
    --------
    >>> import lkspace, tempfile, os
    >>> out = os.path.join(tempfile.mkdtemp(), "t.parquet")
    >>> _ = lkspace.write_catalog("tetrahedron", out, "-2,2", execution=lkspace.Execution(shards=2))
    >>> lkspace.verify_catalog(out).parts
    2
    """
    parts = _structure(os.fspath(path))
    if parts.unsealed is not None:
        raise CatalogError(unsealed(parts.unsealed) + ": not verified (write the catalog again)")
    if parts.unidentified is not None:
        raise CatalogError(
            f"{parts.unidentified}: not identified as the manifest says its run identified every part"
            " (not at all, or by key where it says in full, or the other way)"
        )
    checks: Checks
    if parts.checksums is not None:
        parts.verify_all()
        checks = "manifest, part footers, SHA-256 of every part"
    else:
        read_pages(parts.files[0])
        checks = "footer, CRC-32 of every data page"
    settings = parts.footer.settings
    scaffold = catalog_scaffold(parts.footer, parts.path)
    if settings.dna is not None:  # its rows follow from its settings: recomputed
        from .dna_rows import check_dna_rows

        check_dna_rows(parts)
        checks = "footer, CRC-32 of every data page, every row recomputed (DNA designs)"
    elif settings.invariant is None:  # a symmetric catalog's counts are its subgroup's (lkspace.catalog.symmetric)
        check_settings(parts.files[0], settings, scaffold, parts.totals, parts.footer.shard)
    else:
        from .symmetric import check_invariant_settings

        check_invariant_settings(parts.files[0], parts.footer, scaffold)
    no_zero = isinstance(settings.filters, Filters) and settings.filters.no_zero
    kept_labels = tuple(t for t in settings.label_set if t or not no_zero)
    for file, totals in zip(parts.files, parts.totals, strict=True):
        check_totals(file, totals, kept_labels)
    return CatalogCheck(
        path=parts.path,
        rows=parts.n_rows,
        parts=len(parts.files),
        format_version=settings.format_version,
        scaffold=settings.scaffold.name,
        run=parts.run,
        checks=checks,
    )


def read_pages(file: str) -> None:
    """Read every data page of ``file``, verifying the page checksums it carries."""
    check_regular(file)
    try:
        parquet = pq.ParquetFile(file, page_checksum_verification=True)
        for group in range(parquet.metadata.num_row_groups):
            parquet.read_row_group(group)
    except FileNotFoundError:
        raise
    except (OSError, pa.ArrowException) as exc:
        raise damaged(file, exc) from None


def damaged(file: str, exc: BaseException) -> CatalogError:
    """Return the one-line error for data of ``file`` that pyarrow could not read (``exc``)."""
    reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    return CatalogError(f"{file}: damaged: {reason}")
