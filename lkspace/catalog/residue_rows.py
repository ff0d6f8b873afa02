"""``--mode residues`` rows, one per residue-class orbit, built in batches of classes.

Each row is what :func:`lkspace.design.walk.residue_row` gives for one class (the same
facts), computed for many classes at once: traces, holding together of the representative
labels and Burnside counts in compiled calls, the other columns vectorized.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

import numpy as np
import pyarrow as pa

from ..design.batch import (
    BATCH_PORTS,
    counts_fit_int64,
    design_counts,
    holds_batch,
    representative_table,
    trace_batch,
)
from ..design.space import DesignSpace
from .columns import strand_columns
from .schema import ROW_GROUP, residue_schema

INT64_MAX = 2**63 - 1


def _exact_sizes(space: DesignSpace, indices: np.ndarray, classes: np.ndarray) -> list[int]:
    """Return the assignments per row (class size x classes in the orbit), exact Python ints."""
    n_opts = space.residue_table.n_opts
    e = np.arange(indices.shape[1])
    sizes = n_opts[e[None, :], indices]
    return [int(np.prod([int(x) for x in row], dtype=object)) * int(n) for row, n in zip(sizes, classes, strict=True)]


def residue_batch(space: DesignSpace, class_ids: np.ndarray, components: int | None) -> pa.RecordBatch:
    """One record batch of residue rows for the representative classes ``class_ids`` (in order)."""
    co = space.classes
    periodic = space.scaffold.periodic
    schema = residue_schema(periodic)
    traces = trace_batch(space, co.residues[class_ids])
    if components is not None:
        keep = traces.components == components
        class_ids, traces = class_ids[keep], traces.select(keep)
    n = len(class_ids)
    e = np.arange(space.scaffold.n_edges)
    indices = co.indices[class_ids]
    residues = co.residues[class_ids].astype(np.int8)
    labels = np.ascontiguousarray(representative_table(space)[e[None, :], indices])
    rows = np.arange(n)
    classes = space.n_actions // (co.stab_ptr[class_ids + 1] - co.stab_ptr[class_ids])
    designs = design_counts(space, class_ids)
    if counts_fit_int64(space):
        orbit = np.prod(space.residue_table.n_opts[e[None, :], indices], axis=1) * classes
        designs = np.asarray(designs, np.int64)
    else:
        big = [s if s <= INT64_MAX else -1 for s in _exact_sizes(space, indices, classes)]
        orbit = np.array(big, np.int64)
        designs = np.array([d if d <= INT64_MAX else -1 for d in designs], np.int64)
    n_e = len(e)

    def lists(a: np.ndarray) -> pa.Array:
        return pa.ListArray.from_arrays(pa.array(np.arange(n + 1, dtype=np.int32) * n_e), pa.array(a.reshape(-1)))

    cols = {
        "residues": lists(residues),
        "labels": lists(labels),
        "components": pa.array(traces.components.astype(np.int16)),
        "orbit_size": pa.array(orbit),
        "designs": pa.array(designs),
        "classes": pa.array(classes.astype(np.int64)),
        "holds_together": pa.array(holds_batch(space, traces, labels, rows)),
        "n_zero": pa.array(np.sum(labels == 0, axis=1).astype(np.int16)),
        "n_odd": pa.array(np.sum(residues % 2 != 0, axis=1).astype(np.int16)),
        "residue_class": pa.array(co.codes[class_ids].astype(np.int64)),
        **strand_columns(traces, rows, periodic),
    }
    return pa.RecordBatch.from_arrays([cols[f.name] for f in schema], schema=schema)


def residue_batches(
    space: DesignSpace,
    class_ids: Iterable[int] | None = None,
    components: int | None = None,
    max_designs: int | None = None,
    batch_rows: int | None = None,
) -> Iterator[pa.RecordBatch]:
    """Record batches of ``--mode residues`` rows: one per residue-class orbit, in class order."""
    co = space.classes
    ids = np.arange(len(co.codes)) if class_ids is None else np.fromiter(class_ids, np.int64)
    step = max(1, min(batch_rows or ROW_GROUP, BATCH_PORTS // (2 * space.scaffold.n_corners)))
    n_total = 0
    for s in range(0, len(ids), step):
        batch = residue_batch(space, ids[s : s + step], components)
        if max_designs is not None and n_total + batch.num_rows >= max_designs:
            yield batch.slice(0, max_designs - n_total)
            return
        n_total += batch.num_rows
        if batch.num_rows:
            yield batch
