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
from typing import Any

from ..errors import ExportError
from ..io.atomic import atomic_path, write_text
from ..model.scaffold import Scaffold

PICTURE_SIZE = 480


def picture_name(type_name: str) -> str:
    """Return a file name for a type's picture: ``3_1.png``, ``split_0_1_3_1.png``."""
    return re.sub(r"[^A-Za-z0-9_#-]+", "_", type_name).strip("_").replace("#", "+") + ".png"


def write_gallery(folder: str, data: dict[str, Any], scaffold: Scaffold | None, pictures: int = 12) -> list[str]:
    """Write ``atlas.parquet``, ``README.md`` and up to ``pictures`` PNGs into ``folder``; return the file names."""
    os.makedirs(folder, exist_ok=True)
    written = []
    if scaffold is not None and pictures > 0:
        written += _pictures(folder, data, scaffold, pictures)
    _parquet(os.path.join(folder, "atlas.parquet"), data)
    write_text(os.path.join(folder, "README.md"), markdown(data))
    return ["atlas.parquet", "README.md", *written]


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


def _pictures(folder: str, data: dict[str, Any], scaffold: Scaffold, limit: int) -> list[str]:
    out: list[str] = []
    for entry in data["types"]:
        if len(out) >= limit:
            break
        if entry["name"].startswith(("unknown", "split")):
            continue
        name = picture_name(entry["name"])
        picture(scaffold, entry["simplest"], os.path.join(folder, name), f"{entry['name']}: {entry['simplest']}")
        entry["picture"] = name
        out.append(name)
    return out


def _parquet(path: str, data: dict[str, Any]) -> None:
    import pyarrow as pa
    import pyarrow.parquet as pq

    types = data["types"]
    table = pa.table(
        {
            "name": pa.array([t["name"] for t in types], pa.string()),
            "components": pa.array([t["components"] for t in types], pa.int32()),
            "table": pa.array([t.get("table") for t in types], pa.string()),
            "crossings": pa.array([t.get("crossings") for t in types], pa.int32()),
            "designs": pa.array([t["designs"] for t in types], pa.int64()),
            "assignments": pa.array([t["assignments"] for t in types], pa.int64()),
            "simplest": pa.array([t["simplest"] for t in types], pa.list_(pa.int64())),
            "simplest_sum_abs": pa.array([t.get("simplest_sum_abs") for t in types], pa.int64()),
            "chirality": pa.array([json.dumps(t.get("chirality")) for t in types], pa.string()),
            "picture": pa.array([t.get("picture") for t in types], pa.string()),
        }
    )
    meta = {k: v for k, v in data.items() if k != "types"}
    table = table.replace_schema_metadata({"lkspace-atlas": json.dumps(meta)})
    with atomic_path(path, suffix=".parquet.tmp") as tmp:
        pq.write_table(table, tmp)


def markdown(data: dict[str, Any]) -> str:
    """Return the atlas as a Markdown page: a heading, the space, one table row per type."""
    lines = [
        f"# Atlas of {data['scaffold']}, labels {data.get('label_set')}",
        "",
        f"{data['designs']:,} designs (up to rotation) of {data['assignments']:,} assignments; "
        f"{len(data['types'])} types.  *simplest*: smallest sum |t|, then fewest non-zero labels.",
        "",
        *(
            [f"**Partial**: the time budget ran out; {data['skipped']:,} more designs were not identified.", ""]
            if not data.get("complete", True)
            else []
        ),
        "| type | components | table | smallest diagram (crossings) | designs | assignments | chirality (table/mirror/?) | simplest |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for t in data["types"]:
        c = t.get("chirality") or {}
        chir = f"{c.get('table', 0)}/{c.get('mirror', 0)}/{c.get('undetermined', 0)}"
        name = f"[{t['name']}]({t['picture']})" if t.get("picture") else t["name"]
        simplest = ",".join(map(str, t["simplest"]))
        lines.append(
            f"| {name} | {t['components']} | {t.get('table') or ''} | {t.get('crossings') if t.get('crossings') is not None else ''} "
            f"| {t['designs']:,} | {t['assignments']:,} | {chir} | `{simplest}` |"
        )
    return "\n".join(lines) + "\n"
