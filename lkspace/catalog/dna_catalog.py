"""DNA catalogs (``lkspace enumerate MESH --dna NM``): every buildable design of a mesh at one scale.

The rows are :mod:`lkspace.catalog.dna_rows`'s, one per buildable label assignment of the
windows.  **No symmetry reduction**: each edge's window depends on its length, so only the
symmetries keeping every window could merge rows; listing every buildable assignment
(symmetry ``none``, ``orbit_size`` 1) keeps the catalog a plain list that ``lkspace
verify`` recomputes.  The rows have the designs schema (:mod:`lkspace.catalog.schema`);
the ``lkspace`` metadata records ``label_set`` (the labels of all windows),
``assignments`` (the product of the window sizes: every assignment of the windows,
buildable or not) and ``dna`` (:class:`~lkspace.catalog.metadata.DnaSetting`).
"""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np

from ..errors import CatalogError
from ..io.json_values import JsonObject
from .dna_rows import DnaSpace, dna_batches, dna_blocks, dna_metadata
from .identified import Identified
from .lock import catalog_lock
from .records import PartFooter
from .schema import expected_schema
from .transaction import catalog_target
from .writer import write_batches


@dataclass(frozen=True)
class DnaTotals:
    """What a DNA catalog holds (counted, or ``written`` to that path): the head of ``enumerate --dna --json``."""

    designs: int
    assignments: int
    by_components: dict[str, int]
    label_set: tuple[int, ...]
    written: str | None = None

    def to_json(self) -> JsonObject:
        """Return ``{designs, assignments, by_components, group_order, written, symmetry, label_set}``."""
        return {
            "designs": self.designs,
            "assignments": self.assignments,
            "by_components": dict(self.by_components),
            "group_order": 1,
            "written": self.written,
            "symmetry": "none",
            "label_set": list(self.label_set),
        }


@dataclass(frozen=True)
class DnaReport:
    """What ``enumerate --dna`` reports: the totals, the DNA setting, and the names when identified.

    ``natural_twist``: each edge's natural twist at the scale (half turns, 3 decimals);
    ``patterns``: the buildable parity patterns; ``identified``: ``--identify``'s summary.
    """

    totals: DnaTotals
    setting: JsonObject
    natural_twist: tuple[float, ...]
    patterns: int
    seconds: float
    identified: Identified | None = None

    def to_json(self) -> JsonObject:
        """Return the totals' keys, ``identified`` (when named), ``dna``, ``mode`` and ``seconds``."""
        out: JsonObject = self.totals.to_json()
        if self.identified is not None:
            out["identified"] = self.identified.to_json()
        out["dna"] = {**self.setting, "natural_twist": list(self.natural_twist), "patterns": self.patterns}
        out["mode"] = "designs"
        out["seconds"] = self.seconds
        return out


def _by_components(counts: dict[str, int]) -> dict[str, int]:
    """Return ``counts`` in order of the number of components."""
    return dict(sorted(counts.items(), key=lambda kv: int(kv[0])))


def count_dna(space: DnaSpace, components: int | None = None, max_designs: int | None = None) -> DnaTotals:
    """Return the totals of a DNA catalog without writing it."""
    rows, by = 0, dict[str, int]()
    for block in dna_blocks(space, components):
        comps = block.traces.components[block.row_class]
        if max_designs is not None:
            comps = comps[: max(0, max_designs - rows)]
        rows += len(comps)
        for c, n in zip(*np.unique(comps, return_counts=True), strict=True):
            by[str(int(c))] = by.get(str(int(c)), 0) + int(n)
    return DnaTotals(rows, space.assignments, _by_components(by), tuple(space.space.label_set.tolist()))


def write_dna_catalog(
    space: DnaSpace, path: str | os.PathLike[str], components: int | None = None, max_designs: int | None = None
) -> DnaTotals:
    """Write the buildable designs of ``space`` to one Parquet file at ``path`` (atomically, under the lock); return its totals."""
    target = catalog_target(path)
    if os.path.isdir(target.path):
        raise CatalogError(f"{target.shown}: is a folder; a DNA catalog is one .parquet file", usage=True)
    meta = dna_metadata(space, components, max_designs)
    with catalog_lock(target.lock, target.shown):
        batches = dna_batches(space, components, max_designs)
        summary = write_batches(target.path, expected_schema(meta), PartFooter(meta), batches)
    by_components, _covered = summary.counts()
    label_set = tuple(space.space.label_set.tolist())
    return DnaTotals(summary.rows, space.assignments, _by_components(by_components), label_set, os.fspath(path))
