"""Catalogs of symmetric designs (``lkspace enumerate --invariant``): one Parquet file.

The rows have the designs schema (:mod:`lkspace.catalog.schema`); ``orbit_size`` counts
the fixed assignments a row stands for (its orbit under the normalizer, see
:mod:`lkspace.design.invariant`), so the column adds up to ``fixed_assignments``.  The
``lkspace`` metadata carries the usual keys plus ``invariant``: the subgroup's name,
order, vertex permutations, the normalizer's order, the edge orbits and the number of
fixed assignments.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from dataclasses import replace
from typing import TYPE_CHECKING, Any

import numpy as np

from ..design.invariant import InvariantSpace, make_invariant_space
from ..design.invariant_walk import MAX_FIXED, invariant_blocks
from ..design.space import DesignSpace
from ..errors import CatalogError, LkspaceError
from ..model.scaffold import Scaffold
from ..model.specs import LabelSetSpec, parse_label_set
from ..symmetry.group import SymmetryMode
from .batches import gather_blocks
from .lock import catalog_lock
from .metadata import CatalogMetadata, Filters, Unrecorded, json_object
from .options import Selection
from .records import PartFooter
from .schema import ROW_GROUP, expected_schema
from .settings import CANONICAL_RULE, catalog_metadata
from .transaction import catalog_target
from .writer import write_batches

if TYPE_CHECKING:
    import pandas as pd
    import pyarrow as pa


def invariant_space(
    scaffold: Scaffold,
    subgroup: str,
    label_set: LabelSetSpec = "-2..2",
    symmetry: SymmetryMode = "rotations",
    no_zero: bool = False,
) -> InvariantSpace:
    """Return the :class:`~lkspace.design.invariant.InvariantSpace` of user-level arguments (a label SET as text)."""
    labels = parse_label_set(label_set) if isinstance(label_set, str) else np.asarray(label_set, np.int64)
    return make_invariant_space(scaffold, labels, symmetry, subgroup, no_zero)


def invariant_batches(
    space: InvariantSpace, components: int | None = None, max_designs: int | None = None
) -> Iterator[pa.RecordBatch]:
    """Record batches (designs schema) of the symmetric designs of ``space``, about ``ROW_GROUP`` rows each."""
    yield from gather_blocks(invariant_blocks(space, components), space.scaffold, max_designs, ROW_GROUP)


def symmetric_designs(
    scaffold: Scaffold,
    subgroup: str,
    label_set: LabelSetSpec = "-2..2",
    symmetry: SymmetryMode = "rotations",
    *,
    components: int | None = None,
    no_zero: bool = False,
    max_designs: int | None = None,
) -> Iterator[pd.DataFrame]:
    """Yield the designs fixed by ``subgroup``, up to its normalizer, as catalog rows in batches.

    Parameters
    ----------
    scaffold : Scaffold
        ``lkspace.symmetric_designs`` also takes a path or a built-in name (:func:`lkspace.load`).
    subgroup : str
        A subgroup name (``"C3"``, ``"C4:face=0"``, ``"stabilizer:vertex=2"``, ``"rotations"``, ...;
        :mod:`lkspace.symmetry.subgroups`).
    label_set, symmetry, components, no_zero, max_designs
        As for :func:`lkspace.designs`.

    Examples
    --------
    >>> import lkspace
    >>> df = next(lkspace.symmetric_designs("cube", "C3:vertex=0", "-1..1"))
    >>> len(df), int(df.orbit_size.sum())
    (54, 81)
    """
    space = invariant_space(scaffold, subgroup, label_set, symmetry, no_zero)
    for batch in invariant_batches(space, components, max_designs):
        yield batch.to_pandas()


def invariant_metadata(space: InvariantSpace, components: int | None, max_designs: int | None) -> CatalogMetadata:
    """Return the ``lkspace`` metadata of a symmetric catalog: the usual keys and ``invariant``."""
    plain = DesignSpace(space.scaffold, space.label_set, space.mode, space.no_zero)
    meta = catalog_metadata(plain, Selection(components=components, max_designs=max_designs))
    return replace(
        meta,
        acting_order=int(len(space.action[1])),
        canonical_rule=CANONICAL_RULE + "; under the normalizer of the invariant subgroup",
        invariant=json_object(space.summary(), "the subgroup's summary"),
    )


def count_invariant(space: InvariantSpace, components: int | None = None) -> dict[str, Any]:
    """Totals of a symmetric space: by listing when it is small enough, else ``designs`` by Burnside.

    ``by_components`` is ``None`` when the fixed assignments are past
    :data:`~lkspace.design.invariant_walk.MAX_FIXED` (counted, not listed).
    """
    invariant = json_object(space.summary(), "the subgroup's summary")
    base: dict[str, Any] = {
        "assignments": space.assignments,
        "fixed_assignments": space.n_fixed,
        "invariant": invariant,
    }
    if space.n_fixed > MAX_FIXED:
        note = f"{space.n_fixed:,} fixed assignments: too many to list (limit {MAX_FIXED:,}); counted by Burnside"
        if components is not None:
            return {**base, "designs": None, "by_components": None, "note": note + ", which cannot filter components"}
        return {**base, "designs": space.count_designs(), "by_components": None, "note": note}
    rows, covered = 0, 0
    by: dict[str, int] = {}
    for block in invariant_blocks(space, components):
        rows += len(block.labels)
        covered += int(block.orbit_sizes.sum())
        comps, counts = np.unique(block.traces.components[block.row_class], return_counts=True)
        for c, n in zip(comps.tolist(), counts.tolist(), strict=True):
            by[str(c)] = by.get(str(c), 0) + n
    return {
        **base,
        "designs": rows,
        "assignments_covered": covered,
        "by_components": dict(sorted(by.items(), key=lambda kv: int(kv[0]))),
    }


def write_invariant_catalog(
    space: InvariantSpace,
    path: str | os.PathLike[str],
    components: int | None = None,
    max_designs: int | None = None,
) -> dict[str, Any]:
    """Write the symmetric designs of ``space`` to one Parquet file at ``path`` (atomically, under the lock).

    Returns the totals: ``designs``, ``assignments``, ``fixed_assignments``,
    ``assignments_covered``, ``by_components``, ``output``, ``group_order``,
    ``acting_order``, ``symmetry``, ``label_set``, ``invariant``.
    """
    target = catalog_target(path)
    if os.path.isdir(target.path):
        raise CatalogError(f"{target.shown}: is a folder; a symmetric catalog is one .parquet file", usage=True)
    meta = invariant_metadata(space, components, max_designs)
    with catalog_lock(target.lock, target.shown):
        batches = invariant_batches(space, components, max_designs)
        summary = write_batches(target.path, expected_schema(meta), PartFooter(meta), batches)
    by_components, covered = summary.counts()
    return {
        "designs": summary.rows,
        "assignments": space.assignments,
        "fixed_assignments": space.n_fixed,
        "assignments_covered": covered,
        "by_components": dict(sorted(by_components.items(), key=lambda kv: int(kv[0]))),
        "output": os.fspath(path),
        "group_order": meta.group_order,
        "acting_order": meta.acting_order,
        "symmetry": space.mode,
        "label_set": space.label_set.tolist(),
        "invariant": meta.invariant,
    }


def check_invariant_settings(path: str, footer: PartFooter, scaffold: Scaffold) -> None:
    """Raise unless a symmetric catalog's settings are the ones :func:`invariant_metadata` gives for its subgroup.

    Computed again from the scaffold, label set, symmetry, subgroup and filters recorded: a
    count, the subgroup's summary or the rule edited (and sealed again) had verified, and so
    had a shard, which a symmetric catalog (one file) never has.
    """
    settings = footer.settings
    invariant = settings.invariant or {}
    filters = settings.filters if isinstance(settings.filters, Filters) else Filters()
    symmetry = "none" if isinstance(settings.symmetry, Unrecorded) else settings.symmetry
    try:
        labels = np.array(settings.label_set, np.int64)
        subgroup = invariant.get("subgroup")
        if not isinstance(subgroup, str):
            raise CatalogError(f"subgroup {subgroup!r} is not a name")
        space = make_invariant_space(scaffold, labels, symmetry, subgroup, filters.no_zero)
        again = invariant_metadata(space, filters.components, filters.max_designs)
    except LkspaceError as exc:
        raise CatalogError(
            f"{path}: damaged: its 'lkspace' metadata names no symmetric space lkspace builds: {exc}"
        ) from None
    if settings.to_json() != again.to_json() or footer.shard is not None:
        raise CatalogError(
            f"{path}: damaged: its recorded settings (subgroup, counts, filters, shard) are not the ones its scaffold, "
            "label set and subgroup give"
        )
