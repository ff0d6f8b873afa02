"""Writing whole catalogs: contiguous shards, parallel jobs (fork), resume.

A run with one shard writes a single Parquet file; with several, a folder of parts
``part-00000.parquet``, ... plus a manifest ``_lkspace.json`` (pandas and pyarrow skip
names starting with ``_`` or ``.``).  Each part is written under a temporary name and
renamed when complete; its footer metadata records its rows and counts, so ``resume``
keeps finished parts (when their metadata matches the run) and redoes the others.
Shards are contiguous runs of representative residue classes with about equal numbers
of designs (exact Burnside counts per class).
"""

from __future__ import annotations

import json
import multiprocessing as mp
import os
from collections.abc import Callable, Iterable
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from dataclasses import asdict, dataclass
from typing import Any, TypeAlias

import numpy as np
import pyarrow as pa

from ..design.counting import class_weights
from ..design.space import DesignSpace, make_space
from ..errors import CatalogError
from ..io.atomic import write_text
from ..io.scaffold_json import scaffold_to_dict
from ..io.sources import ScaffoldSource
from ..model.specs import LabelSetSpec
from .batches import space_batches
from .reader import read_metadata
from .schema import FORMAT_VERSION, design_schema, residue_schema
from .writer import CatalogWriter

CANONICAL_RULE = (
    "orbit member smallest in (t mod K per edge, then t per edge), lexicographic in edge order; see docs/catalog.md"
)
_STATE: dict[str, Any] = {}

Progress: TypeAlias = Callable[[int | None], Callable[[int], object] | None]
"""``progress(total)`` -> ``None`` or ``advance(rows written so far)``; ``total`` is ``None`` when unknown."""


@dataclass(frozen=True, repr=False)
class CatalogWritten:
    """What :func:`write_catalog` wrote: totals of the run and where it went.

    Attributes
    ----------
    designs : int
        Rows written (designs, or residue-class orbits in the other modes).
    assignments, assignments_covered : int
        ``|label set| ** n_edges``, and the assignments the rows stand for.
    by_components : dict of int -> int
        Rows by number of components.
    output : str
        Absolute path of the catalog file or folder.
    shards, shards_resumed : int
        Parts written, and parts kept from an earlier run (``resume=True``).
    group_order, acting_order : int
        Order of the symmetry group, and number of distinct signed edge permutations.
    symmetry, mode : str
    label_set : list of int
    """

    designs: int
    assignments: int
    assignments_covered: int
    by_components: dict[int, int]
    output: str
    shards: int
    shards_resumed: int
    group_order: int
    acting_order: int
    symmetry: str
    label_set: list[int]
    mode: str
    format_version: int = FORMAT_VERSION

    def __repr__(self) -> str:
        return f"CatalogWritten({self.designs:,} rows to {self.output} in {self.shards} part(s))"

    def to_dict(self) -> dict[str, Any]:
        """JSON form: the ``lkspace enumerate --json`` fields (``by_components`` keyed by strings)."""
        out = asdict(self)
        out["by_components"] = {str(k): v for k, v in self.by_components.items()}
        return out


def catalog_metadata(
    space: DesignSpace,
    mode: str,
    components: int | None,
    max_designs: int | None,
    sample: int | None,
    seed: int,
) -> dict[str, Any]:
    """Return the ``lkspace`` metadata common to every part of a catalog (its signature for --resume)."""
    sc = space.scaffold
    return {
        "format_version": FORMAT_VERSION,
        "scaffold": {
            "name": sc.name,
            "content_hash": sc.content_hash(),
            "edges": sc.n_edges,
            "faces": sc.n_faces,
            "periodic": sc.periodic,
            "data": {k: v for k, v in scaffold_to_dict(sc).items() if k not in ("labels", "nulls")},  # geometry only
        },
        "label_set": space.label_set.tolist(),
        "symmetry": space.mode,
        "group_order": space.group_order,
        "acting_order": space.n_actions,
        "assignments": space.assignments,
        "mode": mode,
        "filters": {"components": components, "no_zero": space.no_zero, "max_designs": max_designs},
        "sample": sample,
        "seed": seed if sample is not None else None,
        "canonical_rule": CANONICAL_RULE,
    }


def _write_one(
    path: str,
    schema: pa.Schema,
    meta: dict[str, Any],
    batches: Iterable[pa.RecordBatch],
    on_rows: Callable[[int], object] | None = None,
) -> dict[str, Any]:
    """Write ``batches`` to ``path``; returns the part summary (also stored in its footer)."""
    writer = CatalogWriter(path, schema, meta)
    by: dict[str, int] = {}
    covered = 0
    try:
        for batch in batches:
            writer.write(batch)
            comps = batch.column("components").to_numpy()
            for c, n in zip(*np.unique(comps, return_counts=True), strict=True):
                by[str(int(c))] = by.get(str(int(c)), 0) + int(n)
            covered += int(batch.column("orbit_size").to_numpy().sum())
            if on_rows is not None:
                on_rows(batch.num_rows)
    except BaseException as exc:
        writer.abort(exc)
        raise
    summary = {"by_components": by, "assignments_covered": covered}
    writer.close(summary)
    return {**summary, "rows": writer.rows}


def _part_worker(i: int) -> dict[str, Any]:
    st = _STATE
    ids = st["ranges"][i]
    meta = {**st["meta"], "shard": {"index": i, "count": len(st["ranges"])}}
    counter = st["counter"]

    live = st.get("live")

    def on_rows(n: int) -> None:
        with counter.get_lock():
            counter.value += n
        if live is not None:  # same process (jobs == 1): update the bar as rows arrive
            live(counter.value + st["base"])

    return _write_one(
        st["parts"][i],
        st["schema"],
        meta,
        space_batches(st["space"], "designs", ids, st["components"]),
        on_rows,
    )


def split_classes(weights: np.ndarray, n_shards: int) -> list[list[int]]:
    """Split the representative classes into contiguous runs with about equal design counts."""
    w = np.asarray([int(x) for x in weights], np.float64)
    cum = np.cumsum(w)
    total = cum[-1] if len(cum) else 0.0
    cuts = np.searchsorted(cum, total * np.arange(1, n_shards) / n_shards, side="left")
    bounds = [0, *cuts.tolist(), len(w)]
    return [[c for c in range(bounds[i], bounds[i + 1]) if w[c] > 0] for i in range(n_shards)]


def write_catalog(
    space: DesignSpace | ScaffoldSource,
    path: str | os.PathLike[str],
    label_set: LabelSetSpec = "-2..2",
    symmetry: str = "rotations",
    *,
    no_zero: bool = False,
    mode: str = "designs",
    components: int | None = None,
    max_designs: int | None = None,
    sample: int | None = None,
    seed: int = 0,
    jobs: int = 1,
    shards: int | None = None,
    resume: bool = False,
    progress: Progress | None = None,
) -> CatalogWritten:
    """Walk a design space and write its catalog; return its totals (:class:`CatalogWritten`).

    ``space`` is a :class:`~lkspace.design.space.DesignSpace`, or a scaffold (a path or a
    built-in name) whose space is given by ``label_set``, ``symmetry`` and ``no_zero``.

    A single shard writes one Parquet file at ``path``; several shards write a folder
    ``path/`` with ``part-00000.parquet``, ... and a manifest ``_lkspace.json`` (ignored by
    pandas and pyarrow, which open the folder as one table).  Every part is written to a
    temporary name and renamed when complete, so ``resume=True`` skips the parts that exist
    (after checking their metadata matches this run) and redoes the rest.  ``jobs`` parts
    are written in parallel processes.  ``progress(total)`` may return a callable taking
    the rows written so far.
    """
    if not isinstance(space, DesignSpace):
        space = make_space(space, label_set, symmetry, no_zero)
    path = os.fspath(path)
    meta = catalog_metadata(space, mode, components, max_designs, sample, seed)
    periodic = space.scaffold.periodic
    schema = design_schema(space.scaffold.n_edges, periodic) if mode == "designs" else residue_schema(periodic)
    weights: np.ndarray | None = None
    expected: int | None = None
    if mode == "designs":
        weights = class_weights(space, components)
        expected = int(sum(weights))
        expected = min(expected, max_designs) if max_designs is not None else expected
    if shards is None:  # auto: one file, or ~2M-row parts for big parallel/resumable runs
        if expected is not None and max_designs is None:  # a whole design walk
            big = expected > 4_000_000
            shards = max(2 * jobs, -(-expected // 2_000_000)) if jobs > 1 or big else 1
        else:
            shards = 1
    if shards > 1 and (mode != "designs" or max_designs is not None):
        raise CatalogError("--shards/--jobs apply to full design walks (not with --max-designs or other modes)")
    advance = progress(expected) if progress is not None else None
    if shards == 1:
        if resume and os.path.isfile(path) and _matches(path, meta):
            single, skipped = read_metadata(path), 1
            if advance:
                advance(single["rows"])
        else:
            if os.path.isdir(path):
                raise CatalogError(f"{path}: is a folder; give a file name or use --shards")
            single = _write_one(
                path,
                schema,
                {**meta, "shard": {"index": 0, "count": 1}},
                space_batches(space, mode, None, components, max_designs, sample, seed),
                advance and _accumulate(advance),
            )
            skipped = 0
        return _totals(space, meta, [single], path, 1, skipped)
    manifest = os.path.join(path, "_lkspace.json")
    if os.path.exists(path) and not os.path.isdir(path):
        raise CatalogError(f"{path}: exists and is not a folder; a catalog of {shards} shards is a folder")
    if os.path.isdir(path) and os.listdir(path):
        if not os.path.exists(manifest):
            raise CatalogError(f"{path}: folder is not empty and holds no lkspace catalog; choose another -o")
        with open(manifest, encoding="utf-8") as fh:
            old = json.load(fh)
        if resume and old != {**meta, "shards": shards}:
            raise CatalogError(
                f"{path}: --resume with different settings than the catalog there "
                f"(scaffold, labels, symmetry, filters or shards differ)"
            )
        if not resume:
            for name in os.listdir(path):
                if name.startswith("part-") and name.endswith(".parquet"):
                    os.remove(os.path.join(path, name))
    os.makedirs(path, exist_ok=True)
    write_text(manifest, json.dumps({**meta, "shards": shards}, indent=1))
    parts = [os.path.join(path, f"part-{i:05d}.parquet") for i in range(shards)]
    assert weights is not None  # several shards: a whole design walk (checked above)
    ranges = split_classes(weights, shards)
    summaries: list[dict[str, Any] | None] = [None] * shards
    todo = []
    for i, part in enumerate(parts):
        if resume and os.path.isfile(part) and _matches(part, meta):
            summaries[i] = resumed = read_metadata(part)
            if advance:
                advance(resumed["rows"])
        else:
            todo.append(i)
    ctx = mp.get_context("fork")
    counter = ctx.Value("q", 0)
    _STATE.update(
        space=space, ranges=ranges, meta=meta, schema=schema, parts=parts, components=components, counter=counter
    )
    base = sum(s["rows"] for s in summaries if s)
    _STATE.update(base=base, live=advance if jobs <= 1 else None)
    try:
        if jobs <= 1:
            for i in todo:
                summaries[i] = _part_worker(i)
                if advance:
                    advance(counter.value + base)
        else:
            with ProcessPoolExecutor(max_workers=jobs, mp_context=ctx) as pool:
                futures = {pool.submit(_part_worker, i): i for i in todo}
                pending = set(futures)
                while pending:
                    finished, pending = wait(pending, timeout=0.25, return_when=FIRST_COMPLETED)
                    for f in finished:
                        summaries[futures[f]] = f.result()
                    if advance:
                        advance(counter.value + base)
    finally:
        _STATE.clear()
    written = [s for s in summaries if s is not None]
    assert len(written) == shards  # every part was written or resumed
    return _totals(space, meta, written, path, shards, shards - len(todo))


def _accumulate(advance: Callable[[int], object]) -> Callable[[int], None]:
    state = {"n": 0}

    def on_rows(n: int) -> None:
        state["n"] += n
        advance(state["n"])

    return on_rows


def _matches(part: str, meta: dict[str, Any]) -> bool:
    try:
        old = read_metadata(part)
    except CatalogError:
        return False
    return all(old.get(k) == v for k, v in meta.items())


def _totals(
    space: DesignSpace, meta: dict[str, Any], summaries: list[dict[str, Any]], path: str, shards: int, skipped: int
) -> CatalogWritten:
    by: dict[int, int] = {}
    for s in summaries:
        for k, v in s["by_components"].items():
            by[int(k)] = by.get(int(k), 0) + v
    return CatalogWritten(
        designs=sum(s["rows"] for s in summaries),
        assignments=space.assignments,
        assignments_covered=sum(s["assignments_covered"] for s in summaries),
        by_components=dict(sorted(by.items())),
        output=os.path.abspath(path),
        shards=shards,
        shards_resumed=skipped,
        group_order=space.group_order,
        acting_order=space.n_actions,
        symmetry=space.mode,
        label_set=space.label_set.tolist(),
        mode=meta["mode"],
    )
