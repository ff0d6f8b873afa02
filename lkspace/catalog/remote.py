"""Catalogs written to an fsspec URL (``s3://bucket/cat.parquet``, ``gs://...``, ``memory://...``).

Object stores have no atomic rename and no lock, so a URL catalog is written in an
order that makes completeness visible instead:

1. a folder catalog's old manifest ``_lkspace.json`` is deleted first (from then on the
   folder reads as incomplete);
2. every part is written by a worker to a local temporary file and uploaded whole under
   its final name (an object appears only when its upload completes);
3. the manifest, listing each part with its rows and SHA-256, is written **last**: its
   presence marks the catalog complete.

``resume=True`` keeps the parts already in the folder whose footer metadata matches the
run (settings, plan, part number) and that read to the end, and writes the rest.  A
one-file catalog (up to a million rows) is uploaded in one piece.  Readers: pandas,
pyarrow and ``dask.dataframe.read_parquet`` open the URL directly (names starting with
``_`` are skipped).  Two runs writing one URL at once are not detected (no lock): don't.
``memory://`` lives in one process's memory, so it takes ``jobs=1`` and the local
scheduler (tests, notebooks).
"""

from __future__ import annotations

import json
import os
from dataclasses import replace
from typing import Any

import pyarrow as pa
import pyarrow.parquet as pq

from ..errors import CatalogError, ExportError, UsageError, require
from ..runtime.schedulers import is_dask
from .jobs import PartsJob, run_parts, write_part_remote
from .metadata import CatalogMetadata, Json, decode, lkspace_mark
from .options import Execution
from .records import Manifest, PartFooter, PartSummary, Signature
from .schema import METADATA_KEY
from .transaction import MANIFEST, PART_NAME, new_run, part_name


def remote_url(path: str | os.PathLike[str]) -> str | None:
    """``path`` when it is an fsspec URL other than a local file (``file://`` is local), else ``None``."""
    text = os.fspath(path)
    if "://" not in text or text.startswith("file://"):
        return None
    return text.rstrip("/")


def _fs(url: str) -> tuple[Any, str]:
    """Return ``(file system, path)`` of ``url``; an unknown protocol is a usage error."""
    fsspec = require("fsspec", "dask", f"writing to {url}")
    protocol = url.split("://", 1)[0]
    try:
        fsspec.get_filesystem_class(protocol)
    except ValueError:
        raise UsageError(
            f"{url}: unknown protocol {protocol!r}; give a local path or an fsspec URL (s3://, gs://, memory://, ...)"
        ) from None
    except ImportError as exc:
        raise CatalogError(f"{url}: {protocol}:// needs a package that is not installed ({exc})") from None
    fs, root = fsspec.core.url_to_fs(url)
    return fs, root


def check_remote(url: str, argument: str = "path") -> None:
    """Check the catalog URL ``url`` before any work: a known protocol, and nothing there lkspace did not write.

    Messages call the URL ``argument`` as the caller does (the command line: ``-o``).
    """
    fs, root = _fs(url)
    if not fs.exists(root):
        return
    if fs.isdir(root):
        names = sorted(os.path.basename(str(p).rstrip("/")) for p in fs.ls(root, detail=False))
        strange = [n for n in names if n != MANIFEST and not PART_NAME.fullmatch(n)]
        if not names or strange:
            what = f"holds {strange[0]!r}, which is not part of an lkspace catalog" if strange else "is empty"
            raise ExportError(f"{url}: {what}; lkspace replaces only catalogs it wrote: choose another {argument}")
        return
    try:
        with fs.open(root, "rb") as fh:
            raw = (pq.read_metadata(fh).metadata or {}).get(METADATA_KEY)
        meta: Json = json.loads(raw) if raw is not None else None
    except (OSError, ValueError, RecursionError, pa.ArrowException):
        meta = None
    if not lkspace_mark(meta):
        raise ExportError(
            f"{url}: is not an lkspace catalog; lkspace replaces only catalogs it wrote: choose another {argument}"
        )


def _kept_parts(fs: Any, root: str, settings: CatalogMetadata, plan: str) -> tuple[str, dict[int, PartSummary]]:
    """Return ``(run id, parts)``: the parts in the folder ``root`` of the one earlier run of these settings.

    A part is kept when its footer metadata is of this run's settings and ``plan`` and it
    reads to the end; of several earlier runs, the one with the most such parts.
    """
    import hashlib
    import io

    by_run: dict[str, dict[int, PartSummary]] = {}
    for path in sorted(fs.glob(f"{root}/part-*.parquet")):
        try:
            with fs.open(path, "rb") as fh:
                data = fh.read()
            footer = PartFooter.from_json(decode(pq.read_metadata(io.BytesIO(data)).metadata[METADATA_KEY], path), path)
            pq.read_table(io.BytesIO(data))
        except (OSError, ValueError, KeyError, TypeError):  # CatalogError is a ValueError
            continue
        shard, totals = footer.shard, footer.totals
        if shard is None or shard.run is None or shard.plan != plan or totals is None or not totals.counted:
            continue
        if not footer.has_settings(settings, shard):
            continue
        entry = replace(totals, file=os.path.basename(path), sha256=hashlib.sha256(data).hexdigest())
        by_run.setdefault(shard.run, {}).setdefault(shard.index, entry)
    if not by_run:
        return new_run(), {}
    run = max(by_run, key=lambda r: len(by_run[r]))
    return run, by_run[run]


def write_remote(job: PartsJob, url: str, execution: Execution) -> tuple[list[PartSummary], int]:
    """Write the parts of ``job`` to ``url`` as ``execution`` says; return their summaries and how many were kept.

    ``execution.scheduler`` is resolved (:func:`lkspace.runtime.schedulers.resolve_scheduler`).
    """
    fs, root = _fs(url)
    jobs, scheduler = execution.jobs, str(execution.scheduler)
    if fs.protocol in ("memory", ("memory",)) and (jobs > 1 or is_dask(scheduler)):
        raise UsageError(f"{url}: memory:// is private to this process; use jobs=1 and the local scheduler")
    job, n = replace(job, remote=url), job.plan.parts
    if n == 1 and url.endswith(".parquet"):
        if fs.isdir(root):
            raise CatalogError(f"{url}: is a folder; give a new name for a one-file catalog")
        return [write_part_remote(job, 0)[1]], 0
    resume = execution.resume and fs.isdir(root)
    run_id, kept = _kept_parts(fs, root, job.settings, job.plan.fingerprint) if resume else (new_run(), {})
    if fs.exists(f"{root}/{MANIFEST}"):
        fs.rm(f"{root}/{MANIFEST}")  # from here on the folder reads as incomplete
    if not kept and fs.isdir(root):
        for old in fs.glob(f"{root}/part-*.parquet"):
            fs.rm(old)
    fs.makedirs(root, exist_ok=True)
    files = tuple(str(kept[i].file) if i in kept else part_name(i, run_id) for i in range(n))
    job = replace(job, files=files, run=run_id)
    parts = dict(kept)
    todo = [i for i in range(n) if i not in kept]
    for i, summary in run_parts(job, todo, jobs, lambda rows: None, scheduler):
        parts[i] = summary
    keep_files = {str(p.file) for p in parts.values()}
    for old in fs.glob(f"{root}/part-*.parquet"):
        if os.path.basename(old) not in keep_files:
            fs.rm(old)
    manifest = Manifest(Signature(job.settings, n), run_id, parts, complete=True)
    with fs.open(f"{root}/{MANIFEST}", "w") as fh:  # last: the manifest marks the catalog complete
        fh.write(manifest.encode())
    return [parts[i] for i in range(n)], len(kept)
