"""An atlas written to a folder: ``atlas.parquet``, ``README.md`` (a Markdown table) and PNG pictures.

Every file is written under a temporary name and renamed when complete
(:mod:`lkspace.io.atomic`).  Pictures (``lkspace.export`` to PNG, 480 x 480) show the
simplest design of the first ``pictures`` named types, in the table's order.
"""

from __future__ import annotations

import io
import json
import os
import re
from dataclasses import replace

from ..errors import ExportError
from ..io.atomic import atomic_path, write_text
from ..model.scaffold import Scaffold
from .atlas import is_named
from .records import AtlasResult

PICTURE_SIZE = 480


def picture_name(type_name: str) -> str:
    """Return a file name for a type's picture: ``3_1.png``, ``split_0_1_3_1.png``."""
    return re.sub(r"[^A-Za-z0-9_#-]+", "_", type_name).strip("_").replace("#", "+") + ".png"


def write_gallery(
    folder: str, data: AtlasResult, scaffold: Scaffold | None, pictures: int = 12
) -> tuple[list[str], AtlasResult]:
    """Write ``atlas.parquet``, ``README.md`` and up to ``pictures`` PNGs into ``folder``.

    Returns the file names and the atlas with each type's ``picture``.
    """
    os.makedirs(folder, exist_ok=True)
    written = []
    if scaffold is not None and pictures > 0:
        data = _pictures(folder, data, scaffold, pictures)
        written = [t.picture for t in data.types if t.picture is not None]
    _parquet(os.path.join(folder, "atlas.parquet"), data)
    write_text(os.path.join(folder, "README.md"), markdown(data))
    return ["atlas.parquet", "README.md", *written], data


def atlas_folder(folder: str, inputs: tuple[str | None, ...] = ()) -> None:
    """Check ``-o`` of an atlas before any work: a new or empty folder, or one holding an atlas lkspace wrote.

    A folder holding one of ``inputs`` is refused too (the atlas would write over it).
    """
    if os.path.exists(folder) and not os.path.isdir(folder):
        raise ExportError(f"-o {folder}: not a folder")
    real = os.path.realpath(folder)
    for source in inputs:
        if source is not None and os.path.exists(source):
            inside = os.path.realpath(source)
            if inside == real or inside.startswith(real.rstrip(os.sep) + os.sep):
                raise ExportError(f"-o {folder}: holds the input {source}, which the atlas could overwrite")
    if os.path.isdir(folder) and os.listdir(folder) and not _holds_atlas(folder):
        raise ExportError(
            f"-o {folder}: a folder that holds no lkspace atlas (atlas.parquet or cache.jsonl); "
            "lkspace writes only into new or empty folders or its own atlas: choose another -o"
        )


def _holds_atlas(folder: str) -> bool:
    """Whether ``folder`` holds an atlas written by lkspace (its ``atlas.parquet`` or its cache's header)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    try:
        if b"lkspace-atlas" in (pq.read_metadata(os.path.join(folder, "atlas.parquet")).metadata or {}):
            return True
    except (OSError, pa.ArrowException):
        pass
    try:
        with open(os.path.join(folder, "cache.jsonl"), encoding="utf-8") as fh:
            header = json.loads(fh.readline())
    except (OSError, ValueError):
        return False
    return isinstance(header, dict) and {"scaffold", "hash", "labels"} <= set(header)


def picture(scaffold: Scaffold, labels: list[int], path: str, title: str) -> None:
    """Draw one design as a small PNG (480 x 480, a 64-colour palette: tens of KB)."""
    from PIL import Image

    from ..formats.options import PictureOptions
    from ..formats.png import png_bytes
    from ..formats.render import Look
    from ..geometry.realization import realize

    look = Look(width=PICTURE_SIZE, height=PICTURE_SIZE)
    data = png_bytes(realize(scaffold, labels), PictureOptions(look=look, title=title))
    with Image.open(io.BytesIO(data)) as img:
        small = img.convert("RGB").quantize(colors=64)
    with atomic_path(path, suffix=".png") as tmp:
        small.save(tmp, format="PNG", optimize=True)


def _pictures(folder: str, data: AtlasResult, scaffold: Scaffold, limit: int) -> AtlasResult:
    """Draw the simplest design of the first ``limit`` named types; return the atlas with their ``picture``."""
    types = list(data.types)
    drawn = 0
    for i, entry in enumerate(types):
        if drawn >= limit:
            break
        if not is_named(entry.name):
            continue
        name = picture_name(entry.name)
        simplest = list(entry.simplest)
        picture(scaffold, simplest, os.path.join(folder, name), f"{entry.name}: {simplest}")
        types[i] = replace(entry, picture=name)
        drawn += 1
    return replace(data, types=tuple(types))


def _parquet(path: str, data: AtlasResult) -> None:
    import pyarrow as pa
    import pyarrow.parquet as pq

    types = data.types
    table = pa.table(
        {
            "name": pa.array([t.name for t in types], pa.string()),
            "components": pa.array([t.components for t in types], pa.int32()),
            "table": pa.array([t.table for t in types], pa.string()),
            "crossings": pa.array([t.crossings for t in types], pa.int32()),
            "designs": pa.array([t.designs for t in types], pa.int64()),
            "assignments": pa.array([t.assignments for t in types], pa.int64()),
            "simplest": pa.array([list(t.simplest) for t in types], pa.list_(pa.int64())),
            "simplest_sum_abs": pa.array([t.simplest_sum_abs for t in types], pa.int64()),
            "chirality": pa.array([json.dumps(t.chirality.to_json()) for t in types], pa.string()),
            "picture": pa.array([t.picture for t in types], pa.string()),
        }
    )
    meta = {k: v for k, v in data.to_json().items() if k != "types"}
    table = table.replace_schema_metadata({"lkspace-atlas": json.dumps(meta)})
    with atomic_path(path, suffix=".parquet.tmp") as tmp:
        pq.write_table(table, tmp)


def markdown(data: AtlasResult) -> str:
    """Return the atlas as a Markdown page: a heading, the space, one table row per type."""
    label_set = None if data.label_set is None else list(data.label_set)
    skipped = 0 if data.run is None else data.run.skipped
    lines = [
        f"# Atlas of {data.scaffold}, labels {label_set}",
        "",
        f"{data.designs:,} designs (up to rotation) of {data.assignments:,} assignments; "
        f"{len(data.types)} types.  *simplest*: smallest sum |t|, then fewest non-zero labels.",
        "",
        *(
            [f"**Partial**: the time budget ran out; {skipped:,} more designs were not identified.", ""]
            if not data.complete
            else []
        ),
        "| type | components | table | smallest diagram (crossings) | designs | assignments | chirality (table/mirror/?) | simplest |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for t in data.types:
        c = t.chirality
        chir = f"{c.table}/{c.mirror}/{c.undetermined}"
        name = f"[{t.name}]({t.picture})" if t.picture else t.name
        simplest = ",".join(map(str, t.simplest))
        lines.append(
            f"| {name} | {t.components} | {t.table or ''} | {t.crossings if t.crossings is not None else ''} "
            f"| {t.designs:,} | {t.assignments:,} | {chir} | `{simplest}` |"
        )
    return "\n".join(lines) + "\n"
