"""A catalog run as a transaction: built beside its target, put in place when complete.

For a target ``DIR/NAME`` (a ``.parquet`` file or a folder of parts) a run uses, in
``DIR``:

- ``.NAME.lkspace-lock``: the writer's lock (:mod:`lkspace.catalog.lock`);
- ``.NAME.lkspace-build``: the catalog being built (a file, or a folder of parts with
  the manifest ``_lkspace.json``, which records each finished part's rows and SHA-256);
- ``.NAME.lkspace-old``: where the old catalog goes for a moment when it cannot be
  swapped with the new one in one step (not on Linux).

When the build is complete it replaces the target (:func:`lkspace.io.atomic.replace_path`):
readers see the old catalog or the new one.  An interrupted run leaves the build folder
with its finished parts; resuming (``resume=True``) checks them against their checksums
and redoes the rest.  Every other temporary name of the target starts with ``.NAME.lkspace-`` or
``..NAME.lkspace-build.`` and is removed by the next run.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import stat
from collections.abc import Callable
from dataclasses import dataclass

from ..errors import CatalogError, ExportError
from ..io.atomic import remove_path, write_text
from ..io.paths import not_a_link, not_an_input, only_extension, output_folder
from .metadata import Json, lkspace_mark
from .records import Manifest, PartSummary, Signature

MANIFEST = "_lkspace.json"
"""The manifest of a sharded catalog (pandas and pyarrow skip names starting with ``_``)."""

EXTENSIONS = (".parquet", "")
"""Names a catalog may have: ``x.parquet`` (a file or a folder), or no extension (a folder of parts)."""


class CatalogInterrupted(KeyboardInterrupt):
    """A run stopped by Ctrl-C (SIGINT) or SIGTERM after cleaning up; ``exit_code`` is 128 + the signal.

    ``left`` says what the run left (``"interrupted; 4 of 11 parts are finished in ..."``);
    ``resumable`` whether running it again with ``resume=True`` keeps those parts (the
    message then says so).
    """

    def __init__(self, left: str, exit_code: int = 130, resumable: bool = False) -> None:
        super().__init__(f"{left}: run it again with resume=True to finish" if resumable else left)
        self.left = left
        self.exit_code = exit_code
        self.resumable = resumable


@dataclass(frozen=True)
class Destination:
    """Where a catalog goes: ``path`` (its folders' symlinks resolved), and the names of its run's files beside it."""

    path: str
    shown: str

    @property
    def folder(self) -> str:
        """The folder holding the catalog."""
        return os.path.dirname(self.path)

    def _beside(self, what: str) -> str:
        return os.path.join(self.folder, f".{os.path.basename(self.path)}.lkspace-{what}")

    @property
    def build(self) -> str:
        """The catalog being built (a file or a folder)."""
        return self._beside("build")

    @property
    def lock(self) -> str:
        """The writer's lock file."""
        return self._beside("lock")

    @property
    def aside(self) -> str:
        """Where the old catalog waits while it is swapped out (not on Linux)."""
        return self._beside("old")


def catalog_target(
    output: str | os.PathLike[str], inputs: tuple[str | None, ...] = (), argument: str = "path"
) -> Destination:
    """Check the output ``output`` of a catalog before any work: return its :class:`Destination`.

    Messages call the output ``argument`` as the caller does (the command line: ``-o``).

    A symbolic link is refused (:func:`~lkspace.io.paths.not_a_link`).  Only a catalog
    lkspace wrote is replaced (:func:`foreign_reason`).  Refused, each with one line: an
    empty name, a name that is only ``.parquet``, an extension other than ``.parquet``,
    a device, FIFO or socket, anything that is not an lkspace catalog, one of ``inputs``,
    a missing or read-only folder.
    """
    text = os.fspath(output)
    if not text.strip():
        raise ExportError(f"{argument}: the catalog name is empty", parameter="path")
    bare = text.rstrip("/" + os.sep) or text
    only_extension(bare, (".parquet",))
    ext = os.path.splitext(os.path.basename(bare))[1].lower()
    if ext not in EXTENSIONS:
        raise ExportError(
            f"{text}: a catalog is written as Parquet; give a name ending in .parquet (not {ext!r}); "
            "pandas converts it to CSV or JSON afterwards"
        )
    not_a_link(bare)
    not_an_input(bare, inputs)
    path = os.path.realpath(bare)
    if os.path.lexists(path):
        mode = os.stat(path).st_mode
        if not stat.S_ISDIR(mode) and not stat.S_ISREG(mode):
            raise ExportError(f"{text}: is a device, FIFO or socket, not a file lkspace may replace")
        reason = foreign_reason(path)
        if reason is not None:
            raise ExportError(f"{text}: {reason}; lkspace replaces only catalogs it wrote: choose another {argument}")
    output_folder(os.path.dirname(path), text)
    return Destination(path, text)


PART_NAME = re.compile(r"part-\d{5}-[0-9a-f]+\.parquet")
"""Names of the parts of a catalog folder (:func:`part_name`)."""


def foreign_reason(path: str) -> str | None:
    """Return why the existing file or folder ``path`` is not a catalog lkspace wrote, or ``None`` if it is.

    A folder is one when it holds a manifest ``_lkspace.json`` (a JSON object with a
    ``format_version`` and ``parts``) and nothing but part files and lkspace's own
    temporaries; a file when it is Parquet with ``lkspace`` metadata (a JSON object with a
    ``format_version``).  A damaged catalog that no longer reads is not recognised.
    """
    if os.path.isdir(path):
        entries = os.listdir(path)
        if not entries:
            return "is an empty folder, not an lkspace catalog"
        manifest = _manifest_json(path)
        if not lkspace_mark(manifest) or not isinstance(manifest, dict) or not isinstance(manifest.get("parts"), dict):
            return "is a folder that holds no lkspace catalog (no lkspace manifest _lkspace.json)"
        for entry in sorted(entries):
            if entry != MANIFEST and not PART_NAME.fullmatch(entry) and not entry.startswith(".part-"):
                return f"is a folder holding {entry!r}, which is not part of an lkspace catalog"
        return None
    import pyarrow as pa
    import pyarrow.parquet as pq

    try:
        raw = (pq.read_metadata(path).metadata or {}).get(b"lkspace")  # schema.METADATA_KEY: schema imports pyarrow
        meta: Json = json.loads(raw) if raw is not None else None
    except (OSError, ValueError, RecursionError, pa.ArrowException):
        return "is a file that is not an lkspace catalog (not a readable Parquet file)"
    if not lkspace_mark(meta):
        return "is a Parquet file that is not an lkspace catalog (no 'lkspace' metadata)"
    return None


def remove_temporaries(target: Destination, keep_build: bool) -> None:
    """Remove this target's leftover temporary files (and the build unless ``keep_build``)."""
    name = os.path.basename(target.path)
    prefixes = (f".{name}.lkspace-", f"..{name}.lkspace-build.")
    keep = {os.path.basename(target.lock)} | ({os.path.basename(target.build)} if keep_build else set())
    for entry in os.listdir(target.folder):
        if entry.startswith(prefixes) and entry not in keep:
            remove_path(os.path.join(target.folder, entry))
    if keep_build and os.path.isdir(target.build):
        for entry in os.listdir(target.build):
            if entry.endswith(".tmp"):
                remove_path(os.path.join(target.build, entry))


def check_regular(path: str, what: str = "part") -> None:
    """Raise a one-line :class:`CatalogError` unless ``path`` is a regular file (a FIFO would block a read for ever).

    ``FileNotFoundError`` propagates (a catalog replaced while read), except for a link to nothing.
    """
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        if os.path.islink(path):  # for good, not a catalog replaced while read
            raise CatalogError(f"{path}: a symbolic link to {os.readlink(path)!r}, which does not exist") from None
        raise
    except OSError as exc:  # a loop of links, say
        raise CatalogError(f"{path}: cannot read: {exc.strerror}") from None
    if not stat.S_ISREG(mode):
        kind = "a folder" if stat.S_ISDIR(mode) else "a FIFO" if stat.S_ISFIFO(mode) else "a socket or device"
        raise CatalogError(
            f"{path}: not a regular file ({kind}) where the catalog's {what} belongs; "
            "replace it with the file it stands for"
        )


def file_sha256(path: str) -> str:
    """Hex SHA-256 of the bytes of ``path`` (a regular file: :func:`check_regular`)."""
    check_regular(path)
    with open(path, "rb") as fh:
        return hashlib.file_digest(fh, "sha256").hexdigest()


def part_name(index: int, run: str) -> str:
    """File name of part ``index`` of run ``run`` (names differ between runs, so readers never mix two)."""
    return f"part-{index:05d}-{run}.parquet"


def _manifest_json(folder: str) -> Json:
    """Return the JSON of the manifest of ``folder`` (``None`` if missing, not a regular file or not JSON)."""
    where = os.path.join(folder, MANIFEST)
    try:
        if not stat.S_ISREG(os.stat(where).st_mode):
            return None
        with open(where, encoding="utf-8") as fh:
            data: Json = json.load(fh)
    except (OSError, ValueError, RecursionError):  # RecursionError: nested past the stack
        return None
    return data


def load_manifest(folder: str) -> Manifest | None:
    """Return the manifest of a catalog or build folder, or ``None`` if missing or not a manifest lkspace reads."""
    data = _manifest_json(folder)
    try:
        return None if data is None else Manifest.from_json(data, os.path.join(folder, MANIFEST))
    except CatalogError:
        return None


def save_manifest(folder: str, manifest: Manifest) -> None:
    """Write the manifest atomically."""
    write_text(os.path.join(folder, MANIFEST), manifest.encode())


PartCheck = Callable[[str, int, Manifest], object]
"""``check(file, index, manifest)`` raises :class:`CatalogError` unless ``file`` is part ``index`` of ``manifest``'s
catalog by its own footer (:func:`lkspace.catalog.verify.part_footer`)."""


def verified_parts(folder: str, manifest: Manifest, part_footer: PartCheck) -> dict[int, PartSummary]:
    """Return the finished parts recorded in ``manifest`` (with their totals) that are still what it records.

    A part's file in ``folder`` must have the SHA-256 the manifest lists, and ``part_footer``
    must find its own footer naming the manifest's run, plan, settings and part number with
    the totals the manifest lists: a part of another run or other settings whose checksum
    was written into the manifest, or an edited total, is not kept (it is written again).
    """
    good = {}
    for index, entry in manifest.parts.items():
        file = os.path.join(folder, str(entry.file))
        if not (entry.counted and os.path.isfile(file) and file_sha256(file) == entry.sha256):
            continue
        try:
            part_footer(file, index, manifest)
        except CatalogError:
            continue
        good[index] = entry
    return good


def prune_build(folder: str, parts: dict[int, PartSummary]) -> None:
    """Remove from the build ``folder`` every file that is not the manifest or a part in ``parts``."""
    keep = {MANIFEST} | {str(entry.file) for entry in parts.values()}
    for entry in os.listdir(folder):
        if entry not in keep:
            remove_path(os.path.join(folder, entry))


def new_run() -> str:
    """Return a new run id: the catalog's identity, in its part names and in each part's footer."""
    import secrets

    return secrets.token_hex(4)


def seed_build(
    target: Destination, build: str, signature: Signature, part_footer: PartCheck
) -> tuple[str, dict[int, PartSummary]]:
    """Start a build from the finished catalog at the target, if it is of the same run settings.

    Returns ``(run id, parts)``: the build takes over the old catalog's run id (its parts'
    footers name it) and its parts whose checksums verify, linked (or copied) into
    ``build`` (checked with ``part_footer``, :func:`verified_parts`); a new run id and no
    parts when there is no such catalog.
    """
    old = load_manifest(target.path) if os.path.isdir(target.path) else None
    if old is None or not signature.resumes(old.signature):
        return new_run(), {}
    import shutil

    seeded = {}
    for index, entry in verified_parts(target.path, old, part_footer).items():
        name = str(entry.file)
        if name != part_name(index, old.run):
            continue
        src, dst = os.path.join(target.path, name), os.path.join(build, name)
        try:
            os.link(src, dst)
        except OSError:
            shutil.copy2(src, dst)
        seeded[index] = entry
    return old.run, seeded
