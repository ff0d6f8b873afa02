"""The catalog's Arrow schema, versioned (explained for users in ``docs/catalog.md``).

Layout (format version 1), one row per design:

=================  ==========================  ===============================================
column             Arrow type                  meaning
=================  ==========================  ===============================================
labels             list<int8>                  canonical labels in edge order (the orbit's
                                               representative, :mod:`lkspace.design.walk`)
key                fixed_size_binary[n_edges]  the same labels as packed int8 bytes: an exact
                                               canonical design key for joins / de-duplication
components         int16                       number of strands
orbit_size         int64                       assignments the design stands for
holds_together     bool                        winding at nonzero-label edges connects all
n_zero n_odd       int16                       labels equal to 0 / odd / even
n_even
abs_sum abs_max    int32 / int16               sum and maximum of ``|t|``
residue_class      int64                       mixed-radix code of ``t mod K`` (edge 0 most
                                               significant, digits index each edge's residues)
strand_lengths     list<int32>                 corners per strand, descending
n_infinite         int16                       (periodic only) strands with a nonzero period
strand_periods     list<list<int64>>           (periodic only) period per strand, same order
=================  ==========================  ===============================================

Why ``labels`` is ``list<int8>``: catalogs promise a column pandas reads as a list of
ints per row, and Parquet has no fixed-size list (pyarrow stores ``fixed_size_list`` as
a plain list, measured 1.5 M rows/s against 1.9 M for ``list<int8>``).  Lists are the
slow columns (~2-3 M rows/s against 15-80 M for the scalar columns), so the row layout
keeps them to ``labels`` and ``strand_lengths`` and adds the packed ``key`` (23 M rows/s)
for consumers that want fixed width.  Row groups of 262,144 rows, zstd.

``--mode residues`` / ``spanning-trees`` rows (one per residue-class orbit) instead carry
``residues`` (list<int8>), a representative ``labels`` row, ``components``,
``strand_lengths``, ``holds_together``, ``n_zero``, ``n_odd``, ``residue_class``,
``classes`` (classes in the orbit), ``orbit_size`` (assignments the row stands for) and
``designs`` (designs in it).

Metadata key ``lkspace`` (JSON, :class:`~lkspace.catalog.records.PartFooter`): format
version (:data:`~lkspace.catalog.records.FORMAT_VERSION`), scaffold name and content hash,
``label_set``, symmetry mode and group order, filters, mode, shard, and the rows/by-components
totals of the part; in the footer also ``digest``, the SHA-256 of the rest
(:func:`~lkspace.catalog.records.metadata_digest`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import pyarrow as pa

if TYPE_CHECKING:
    from .metadata import CatalogMetadata

ROW_GROUP = 262_144
METADATA_KEY = b"lkspace"

IDENTIFY_COLUMNS = {
    "knot_name": pa.string(),
    "crossings": pa.int32(),
    "mirror": pa.bool_(),
    "split": pa.bool_(),
    "jones": pa.string(),
    "linking_matrix": pa.string(),
    "identify_error": pa.string(),
    "identify_status": pa.string(),
}
"""Columns ``--identify`` adds after the others (:mod:`lkspace.catalog.identified`), with their types."""


def expected_schema(settings: CatalogMetadata) -> pa.Schema:
    """Return the schema a catalog file of ``settings`` (mode, scaffold) has, before any ``--identify`` columns."""
    periodic = settings.scaffold.periodic is True
    if settings.mode == "designs":
        return design_schema(settings.scaffold.edges, periodic)
    return residue_schema(periodic)


def design_schema(n_edges: int, periodic: bool) -> pa.Schema:
    """Arrow schema of a designs catalog."""
    fields = [
        ("labels", pa.list_(pa.int8())),
        ("key", pa.binary(n_edges)),
        ("components", pa.int16()),
        ("orbit_size", pa.int64()),
        ("holds_together", pa.bool_()),
        ("n_zero", pa.int16()),
        ("n_odd", pa.int16()),
        ("n_even", pa.int16()),
        ("abs_sum", pa.int32()),
        ("abs_max", pa.int16()),
        ("residue_class", pa.int64()),
        ("strand_lengths", pa.list_(pa.int32())),
    ]
    if periodic:
        fields += [("n_infinite", pa.int16()), ("strand_periods", pa.list_(pa.list_(pa.int64())))]
    return pa.schema(fields)


def residue_schema(periodic: bool) -> pa.Schema:
    """Arrow schema of a residues / spanning-trees catalog."""
    fields = [
        ("residues", pa.list_(pa.int8())),
        ("labels", pa.list_(pa.int8())),
        ("components", pa.int16()),
        ("orbit_size", pa.int64()),
        ("designs", pa.int64()),
        ("classes", pa.int64()),
        ("holds_together", pa.bool_()),
        ("n_zero", pa.int16()),
        ("n_odd", pa.int16()),
        ("residue_class", pa.int64()),
        ("strand_lengths", pa.list_(pa.int32())),
    ]
    if periodic:
        fields += [("n_infinite", pa.int16()), ("strand_periods", pa.list_(pa.list_(pa.int64())))]
    return pa.schema(fields)
