"""Reverse lookup: the simplest designs of a knot or link type, from an atlas index (``lkspace lookup``).

An **atlas index** is one Parquet file with one row per (type, scaffold, label set),
built from :func:`~lkspace.linktypes.atlas.atlas` results by :func:`index_rows` and
:func:`write_index` (``experiments/build_atlas.py``); lkspace ships one
(:data:`SHIPPED`).  Columns (docs/design-to-target.md, "Looking up a type"):

=====================  ==========================================================
``type``               the atlas type (:func:`~lkspace.linktypes.atlas.type_key`)
``common_name``        its common name, or null
``components``         components
``crossing_number``    the crossing number the name states (null: split, unknown)
``crossings``          crossings of the smallest simplified diagram seen
``table``              the table that named it
``scaffold``, ``labels``  the space: a built-in name and a label set (``-2..2``)
``designs``, ``assignments``  designs of the type up to rotation; label vectors
``first_sum_abs``      the smallest sum |t| of a design of the type
``chirality_table``, ``chirality_mirror``, ``chirality_undetermined``  designs per chirality
``examples``           JSON list of the simplest designs of each chirality:
                       ``{labels, sum_abs, nonzero, crossings, mirror}``
``complete``           every design of the space was identified
=====================  ==========================================================

The file's metadata (key ``lkspace-atlas-index``) holds ``format``, ``lkspace_version``,
``commit``, ``date``, ``spaces``: ``{scaffold, labels, designs, assignments, types,
complete, identified, wall_time}`` for every space built, and ``left_out``: ``{scaffold, labels, reason}``.  Reading needs pyarrow only.
A row is an :class:`~lkspace.linktypes.records.IndexRow`, an answer a
:class:`~lkspace.linktypes.records.LookupAnswer`: their ``from_row``/``to_row`` and
``to_json`` are the only readers and writers of these formats.
"""

from __future__ import annotations

import json
import os

from ..errors import CatalogError, LkspaceError
from ..scaffolds.constructed import table, table_design
from .answers import LookupAnswer, LookupDesign
from .common_names import common_name, resolve_type
from .fields import JsonObject
from .ideal_shapes import ideal_shape
from .records import INDEX_COLUMNS, AtlasResult, Example, IndexRow
from .spelling import Chirality

SHIPPED = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "data", "atlas.parquet")
"""The atlas index shipped with lkspace."""

META = b"lkspace-atlas-index"
FORMAT = 1
LIMIT = 10
"""Designs a lookup returns by default."""


def index_rows(data: AtlasResult, labels: str) -> list[IndexRow]:
    """Return the index rows of one :func:`~lkspace.linktypes.atlas.atlas` result (``labels``: its label set as typed)."""
    from .atlas import crossing_number, is_named

    rows = []
    for t in data.types:
        named = is_named(t.name)
        rows.append(
            IndexRow(
                type=t.name,
                common_name=common_name(t.name),
                components=t.components,
                crossing_number=crossing_number(t.name) if named else None,
                crossings=t.crossings,
                table=t.table,
                scaffold=data.scaffold,
                labels=labels,
                designs=t.designs,
                assignments=t.assignments,
                first_sum_abs=t.simplest_sum_abs,
                chirality_table=t.chirality.table,
                chirality_mirror=t.chirality.mirror,
                chirality_undetermined=t.chirality.undetermined,
                examples_json=IndexRow.examples_text(t.examples),
                complete=data.complete,
            )
        )
    return rows


def write_index(path: str, rows: list[IndexRow], meta: JsonObject) -> None:
    """Write an atlas index (temporary name, then renamed)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    from ..io.atomic import atomic_path

    written = [r.to_row() for r in rows]
    columns = {key: pa.array([r[key] for r in written], getattr(pa, kind)()) for key, kind in INDEX_COLUMNS}
    table = pa.table(columns).replace_schema_metadata({META: json.dumps({"format": FORMAT, **meta})})
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with atomic_path(path, suffix=".parquet.tmp") as tmp:
        pq.write_table(table, tmp, compression="zstd")


def read_index(path: str | None = None) -> tuple[list[IndexRow], JsonObject]:
    """Return the rows and the metadata of an atlas index (default: the shipped one)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    path = path or SHIPPED
    try:
        with pq.ParquetFile(path) as file:  # not read_table: that imports pandas
            table = file.read()
    except FileNotFoundError:
        raise CatalogError(f"atlas {path}: no such file", parameter="atlas") from None
    except (OSError, pa.ArrowException) as exc:
        raise CatalogError(f"atlas {path}: not a Parquet atlas index ({exc})", parameter="atlas") from None
    raw = (table.schema.metadata or {}).get(META)
    if raw is None:
        raise CatalogError(
            f"atlas {path}: not an atlas index (no {META.decode()} metadata); build one with experiments/build_atlas.py",
            parameter="atlas",
        )
    try:
        meta = json.loads(raw)
    except (ValueError, RecursionError):  # ValueError: not UTF-8 or not JSON
        meta = None
    if not isinstance(meta, dict):
        raise CatalogError(f"atlas {path}: its {META.decode()} metadata is no JSON object", parameter="atlas")
    rows = [IndexRow.from_row(row, f"atlas {path}, row {i}") for i, row in enumerate(table.to_pylist())]
    return rows, meta


def lookup(name: str, atlas: str | None = None, *, limit: int = LIMIT, scaffold: str | None = None) -> LookupAnswer:
    """Return the simplest designs of the type ``name`` in an atlas index (default: the shipped one).

    ``name``: a table name (``5_2``, ``m3_1``: mirror images only), an atlas type
    (``split: 0_1 + 0_1``) or a common name (``"Borromean rings"``).  ``scaffold``: only
    that space's designs.  A design in two label sets of one scaffold is listed once.  A
    connected sum is looked up without the mirror marks of its factors.

    Returns a :class:`~lkspace.linktypes.records.LookupAnswer` (``to_json()``: ``{query,
    name, chirality, common_name, atlas, searched, found_in, designs_total, simplest_kept,
    designs, ideal_shape}``): ``designs_total`` counts the designs of the type (of the chirality asked)
    summed over the spaces searched, ``simplest_kept`` the simplest of them the atlas keeps
    (:mod:`~lkspace.linktypes.examples`), from which ``designs`` is drawn; ``designs`` (at
    most ``limit``, simplest first: sum |t|, non-zero labels, crossings, then scaffold and
    labels) holds :class:`~lkspace.linktypes.records.LookupDesign` ``{type, scaffold, labels,
    label_set, sum_abs, nonzero, crossings, mirror, chiral_name, designs_of_type, command}``;
    ``ideal_shape`` (a knot up to 10 crossings, else ``None``) is the design and relaxation
    that come closest to the ideal ropelength (:mod:`~lkspace.linktypes.ideal_shapes`).
    Raises :class:`TypeNotFound` (exit 1) when the atlas holds no such design.
    """
    wanted, chirality = resolve_type(name)
    rows, meta = read_index(atlas)
    spaces = [f"{s['scaffold']} {s['labels']}" for s in _spaces(meta)]
    if scaffold is not None:
        spaces = [s for s in spaces if s.split(" ")[0] == scaffold]
    hits = [r for r in rows if _same_type(r.type, wanted) and scaffold in (None, r.scaffold)]
    if "#" in wanted:  # a sum as the atlas spells it: factors in table order, no mirror marks
        wanted = hits[0].type if hits else "#".join(p[1:] if p.startswith("m") else p for p in wanted.split("#"))
    found: dict[tuple[str, tuple[int, ...]], LookupDesign] = {}
    for row in hits:
        for ex in row.examples:
            if chirality != "any" and ex.mirror is not (chirality == "mirror"):
                continue
            key = (row.scaffold, ex.labels)
            if key not in found:
                found[key] = _design(row, ex)
    designs = sorted(found.values(), key=_simplest)
    if not hits and scaffold is None:  # no design of the type at all (not: none of the chirality asked)
        designs = constructed_designs(wanted, chirality)
    if not designs:
        raise TypeNotFound(_absent(wanted, chirality, hits, spaces, atlas, scaffold))
    return LookupAnswer(
        query=name,
        name=wanted,
        chirality=chirality,
        common_name=common_name(wanted, None if chirality == "any" else chirality == "mirror"),
        atlas=os.path.abspath(atlas or SHIPPED),
        searched=tuple(spaces),
        found_in=tuple(dict.fromkeys(f"{r.scaffold} {r.labels}" for r in hits if r.count(chirality))),
        designs_total=sum(r.count(chirality) for r in hits),
        simplest_kept=len(designs),
        designs=tuple(designs[:limit]),
        ideal_shape=ideal_shape(wanted),
    )


class TypeNotFound(LkspaceError):
    """No design of the type is in the atlas (exit 1); the message names the spaces searched."""


def _spaces(meta: JsonObject) -> list[dict[str, str]]:
    """Return the spaces an index was built from (``{scaffold, labels}``), as its metadata lists them."""
    listed = meta.get("spaces")
    out = []
    for s in listed if isinstance(listed, list) else []:
        if isinstance(s, dict) and isinstance(s.get("scaffold"), str) and isinstance(s.get("labels"), str):
            out.append({"scaffold": str(s["scaffold"]), "labels": str(s["labels"])})
    return out


def _simplest(design: LookupDesign) -> tuple[int, int, int, str, tuple[int, ...]]:
    """Sort key: sum |t|, non-zero labels, crossings (unknown last), scaffold, labels."""
    crossings = design.crossings if design.crossings is not None else 1 << 30
    return (design.sum_abs, design.nonzero, crossings, design.scaffold, design.labels)


def _same_type(row_type: str, wanted: str) -> bool:
    """Whether an atlas type is the one asked for (a sum matches its factors in any order, mirror marks aside)."""
    if "#" not in wanted:
        return row_type == wanted
    factors = sorted(p[1:] if p.startswith("m") else p for p in wanted.split("#"))
    return sorted(row_type.split("#")) == factors


def constructed_designs(name: str, chirality: Chirality) -> list[LookupDesign]:
    """Return the constructed design of a table type (``knot:NAME``, ``link:NAME``), each chirality asked for.

    Empty when ``name`` is not in the shipped table of diagrams (:mod:`lkspace.scaffolds.constructed`).
    """
    entry = table().get(name)
    if entry is None:
        return []
    kind = "knot" if entry.components == 1 else "link"
    sides = [False, True] if chirality == "any" else [chirality == "mirror"]
    if entry.amphichiral:
        sides = sides[:1]
    out = []
    for mirror in sides:
        builtin = f"{kind}:{'m' if mirror else ''}{name}"
        labels = tuple(int(t) for t in table_design(builtin).labels)  # type: ignore[union-attr]
        known = None if entry.amphichiral else mirror
        out.append(
            LookupDesign(
                type=name,
                common_name=common_name(name, known),
                scaffold=builtin,
                labels=labels,
                label_set="constructed",
                sum_abs=sum(abs(t) for t in labels),
                nonzero=sum(t != 0 for t in labels),
                crossings=entry.crossings,
                mirror=known,
                chiral_name=("m" if known else "") + name,
                designs_of_type=1,
                command=f"lkspace identify {builtin}",
                constructed=True,
            )
        )
    return out


def _design(row: IndexRow, ex: Example) -> LookupDesign:
    mirror = ex.mirror
    return LookupDesign(
        type=row.type,
        common_name=common_name(row.type, mirror),
        scaffold=row.scaffold,
        labels=ex.labels,
        label_set=row.labels,
        sum_abs=ex.sum_abs,
        nonzero=ex.nonzero,
        crossings=ex.crossings,
        mirror=mirror,
        chiral_name=("m" if mirror else "") + row.type if mirror is not None else row.type,
        designs_of_type=row.designs,
        command=f"lkspace identify {row.scaffold} --twist {','.join(map(str, ex.labels))}",
    )


def _absent(
    wanted: str,
    chirality: Chirality,
    hits: list[IndexRow],
    spaces: list[str],
    atlas: str | None,
    scaffold: str | None,
) -> str:
    """Return the line saying that no design was found: where it looked, and how to look further."""
    asked = f"m{wanted}" if chirality == "mirror" else wanted
    if chirality == "table":
        asked += " (the table's chirality)"
    told = ""
    if hits:
        n = sum(r.designs for r in hits)
        told = f" (it holds {n:,} designs of {wanted}, none identified as this chirality: ask for {wanted})"
    where = "the atlas " + (atlas or "shipped with lkspace")
    shown = ", ".join(spaces[:12]) + (f" and {len(spaces) - 12} more" if len(spaces) > 12 else "")
    return (
        f"{asked}: no design in {where}{told}; searched {len(spaces)} space{'' if len(spaces) == 1 else 's'}: "
        f"{shown or f'none (no space of scaffold {scaffold!r})'}; "
        "build a bigger atlas with experiments/build_atlas.py and pass it as `atlas`, or search one space "
        f"with lkspace solve MESH --type {asked.split(' ')[0]}"
    )
