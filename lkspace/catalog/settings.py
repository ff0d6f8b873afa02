"""What a catalog records, computed again: its settings from its design space, its scaffold, its totals from its rows.

:func:`catalog_metadata` is what the writers record; the ``check_*`` functions and
:func:`catalog_scaffold` are what :func:`~lkspace.catalog.verify.verify_catalog` (and, for the
scaffold, every reader of a row) check a catalog against.
"""

from __future__ import annotations

from typing import cast

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

from ..design.space import DesignSpace, make_space
from ..errors import CatalogError, LkspaceError
from ..io.scaffold_json import scaffold_from_dict, scaffold_to_dict
from ..io.sources import load
from ..model.scaffold import Scaffold
from ..symmetry.tolerance import resolve_tolerance
from .metadata import (
    FORMAT_VERSION,
    UNRECORDED,
    CatalogMetadata,
    Filters,
    JsonObject,
    ScaffoldInfo,
    Unrecorded,
    shown,
)
from .options import Selection
from .plan import plan_fingerprint
from .records import PartFooter, PartSummary, Shard
from .writer import tally

CANONICAL_RULE = (
    "orbit member smallest in (t mod K per edge, then t per edge), lexicographic in edge order; see docs/catalog.md"
)


def catalog_metadata(space: DesignSpace, selection: Selection) -> CatalogMetadata:
    """Return the ``lkspace`` metadata common to every part of a catalog (its signature for resuming)."""
    sc = space.scaffold
    geometry = cast(JsonObject, {k: v for k, v in scaffold_to_dict(sc).items() if k not in ("labels", "nulls")})
    return CatalogMetadata(
        format_version=FORMAT_VERSION,
        scaffold=ScaffoldInfo(sc.name, sc.content_hash(), sc.n_edges, sc.n_faces, sc.periodic, geometry),
        label_set=tuple(space.label_set.tolist()),
        symmetry=space.mode,
        symmetry_tolerance=None if space.mode == "none" else resolve_tolerance(sc, space.tolerance),
        group_order=space.group_order,
        acting_order=space.n_actions,
        assignments=space.assignments,
        mode=selection.mode,
        filters=Filters(selection.components, space.no_zero, selection.max_designs),
        sample=selection.sample,
        seed=selection.seed if selection.sample is not None else None,
        canonical_rule=CANONICAL_RULE,
    )


def check_settings(
    path: str, settings: CatalogMetadata, scaffold: Scaffold, totals: tuple[PartSummary, ...], shard: Shard | None
) -> None:
    """Raise unless ``settings`` are the ones :func:`catalog_metadata` gives for the space they name.

    The counts (``assignments``, ``group_order``, ``acting_order``), the tolerance and the
    canonical rule are computed again from the scaffold, label set, symmetry and selection
    recorded; a setting missing or changed (and sealed again) is refused, and so are
    ``totals`` (of every file) that the recorded filters could not have given and a
    ``shard`` whose plan is not the one these settings are cut into (or no shard at all).
    The settings are a sealed footer's: every setting is there
    (:meth:`~lkspace.catalog.records.PartFooter.from_json`).
    """
    filters = settings.filters if isinstance(settings.filters, Filters) else Filters()
    symmetry = "none" if isinstance(settings.symmetry, Unrecorded) else settings.symmetry
    tolerance = settings.symmetry_tolerance if isinstance(settings.symmetry_tolerance, float) else None
    sample = None if isinstance(settings.sample, Unrecorded) else settings.sample
    seed = settings.seed if isinstance(settings.seed, int) else 0
    try:
        selection = Selection(settings.mode, filters.components, filters.max_designs, sample, seed)
        space = make_space(scaffold, np.array(settings.label_set, np.int64), symmetry, filters.no_zero, tolerance)
        again = catalog_metadata(space, selection)
        plan = None if shard is None else plan_fingerprint(space, selection, shard.count)
    except LkspaceError as exc:
        raise CatalogError(
            f"{path}: damaged: its 'lkspace' metadata names no design space lkspace builds: {exc}"
        ) from None
    if settings.to_json() != again.to_json() or not _filtered(settings, filters, totals):
        raise CatalogError(
            f"{path}: damaged: its recorded settings (label set, symmetry, counts, filters) are not the ones "
            "its scaffold and label set give"
        )
    if shard is None:
        raise CatalogError(f"{path}: damaged: its 'lkspace' metadata has no shard (part number, part count, plan)")
    if shard.plan != plan:
        raise CatalogError(
            f"{path}: damaged: its recorded plan {shown(shard.plan)} is not the one its settings are cut "
            f"into in {shard.count:,} part{'s' if shard.count > 1 else ''}"
        )


def _filtered(settings: CatalogMetadata, filters: Filters, totals: tuple[PartSummary, ...]) -> bool:
    """Whether ``totals`` fit the filters: only the kept component count, at most ``max_designs`` rows, every assignment of a whole walk."""
    by = [int(k) for t in totals if isinstance(t.by_components, dict) for k, n in t.by_components.items() if n]
    covered = [t.assignments_covered for t in totals]
    if filters.components is not None:
        return set(by) <= {filters.components}
    if filters.max_designs is not None:
        return sum(t.rows for t in totals) <= filters.max_designs
    whole = (
        settings.mode != "spanning-trees"
        and not filters.no_zero
        and all(isinstance(c, int) and c >= 0 for c in covered)
    )
    return not whole or sum(c for c in covered if isinstance(c, int)) == settings.assignments


def catalog_scaffold(footer: PartFooter, path: str) -> Scaffold:
    """Return the scaffold of a catalog: stored in its ``footer``, else loaded by name.

    Its content hash, name (of a stored scaffold) and counts must be the ones the metadata records.
    """
    info = footer.settings.scaffold
    try:
        scaffold = scaffold_from_dict(info.data, info.name) if info.data else load(info.name)
    except LkspaceError as exc:
        raise CatalogError(f"{path}: the scaffold in its 'lkspace' metadata: {exc}") from None
    name = info.name if info.data else UNRECORDED  # loaded by it: a path names the file, not the scaffold
    recorded = (info.content_hash, name, info.edges, info.faces, info.periodic)
    actual = (scaffold.content_hash(), scaffold.name, scaffold.n_edges, scaffold.n_faces, scaffold.periodic)
    if any(r != a for r, a in zip(recorded, actual, strict=True) if not isinstance(r, Unrecorded)):
        raise CatalogError(f"{path}: the scaffold {scaffold.name!r} differs from the one the catalog was written for")
    return scaffold


def check_totals(file: str, totals: PartSummary, label_set: tuple[int, ...]) -> None:
    """Raise unless the rows of ``file`` add up to ``totals`` (rows by components, assignments covered).

    Every label of its rows must be in ``label_set`` (the labels kept: without 0 for ``no_zero``).
    """
    by: dict[str, int] = {}
    covered = 0
    try:
        parquet = pq.ParquetFile(file)
        keyed = "key" in parquet.schema_arrow.names  # a designs catalog: the labels again, packed
        for batch in parquet.iter_batches(columns=["labels", "components", "orbit_size", *(["key"] if keyed else [])]):
            covered = tally(batch, by, covered)
            labels = batch.column("labels").flatten().to_numpy()
            if not np.isin(labels, label_set).all():
                raise CatalogError(f"{file}: damaged: it holds labels outside the ones it keeps, {list(label_set)}")
            if keyed and not _same_labels(labels, batch.column("key")):
                raise CatalogError(f"{file}: damaged: a row's labels are not the ones its key holds")
    except CatalogError:
        raise
    except (OSError, pa.ArrowException, ValueError) as exc:
        reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise CatalogError(f"{file}: damaged: {reason}") from None
    recorded = (totals.by_components, totals.assignments_covered)
    if recorded != (by, covered):
        raise CatalogError(
            f"{file}: damaged: its recorded totals (rows by components, assignments covered) "
            "are missing or not the ones its rows add up to"
        )


def _same_labels(labels: np.ndarray, keys: pa.Array) -> bool:
    """Whether the flattened ``labels`` of a batch are its ``key`` column's bytes (one int8 per edge, row after row)."""
    packed = np.frombuffer(keys.buffers()[1], np.int8)[keys.offset * keys.type.byte_width :][: len(labels)]
    return keys.null_count == 0 and len(packed) == len(labels) and np.array_equal(packed, labels)
