"""Designs -> Arrow record batches of the catalog schema (:mod:`lkspace.catalog.schema`).

The design walk (:mod:`lkspace.design`) yields blocks of label rows and per-class facts;
this module turns them into columns: the only place besides the reader and writer that
knows Arrow.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from typing import Any

import numpy as np
import pyarrow as pa

from ..design.space import DesignSpace
from ..design.spanning import spanning_tree_rows
from ..design.walk import Block, residue_row, walk_blocks
from ..kernels import kernel
from .schema import ROW_GROUP, design_schema, residue_schema

INT64_MAX = 2**63 - 1
"""Largest ``residue_class`` code stored; a larger one (a class of a big scaffold) is stored as null."""


def list_column(values: np.ndarray, counts: np.ndarray, type_: pa.ListType) -> pa.Array:
    """Return a list column of Arrow type ``type_``: row ``i`` holds the next ``counts[i]`` of ``values``."""
    offsets = np.zeros(len(counts) + 1, np.int32)
    np.cumsum(counts, out=offsets[1:])
    return pa.ListArray.from_arrays(pa.array(offsets), pa.array(values, type=type_.value_type))


def periods_column(blocks_periods: list[np.ndarray], repeats: list[int]) -> pa.Array:
    """Nested list column: per row, the class's ``(n_strands, dim)`` periods."""
    dims = [p.shape[1] for p in blocks_periods]
    dim = dims[0] if dims else 0
    flat = (
        np.concatenate([np.tile(p.reshape(-1), r) for p, r in zip(blocks_periods, repeats, strict=True)])
        if blocks_periods
        else np.zeros(0, np.int64)
    )
    n_strands = (
        np.concatenate([np.full(r, len(p), np.int64) for p, r in zip(blocks_periods, repeats, strict=True)])
        if blocks_periods
        else np.zeros(0, np.int64)
    )
    inner = pa.ListArray.from_arrays(
        pa.array(np.arange(len(flat) // max(dim, 1) + 1, dtype=np.int32) * dim), pa.array(flat, pa.int64())
    )
    offsets = np.zeros(len(n_strands) + 1, np.int32)
    np.cumsum(n_strands, out=offsets[1:])
    return pa.ListArray.from_arrays(pa.array(offsets), inner)


@kernel
def label_stats_kernel(
    labels: np.ndarray, n_zero: np.ndarray, n_odd: np.ndarray, abs_sum: np.ndarray, abs_max: np.ndarray
) -> None:
    """Fill the per-row counts of zero and odd labels and the sum and maximum of ``|t|`` (see :func:`label_stats`)."""
    for i in range(labels.shape[0]):
        z: Any = 0  # integers that become numpy integers as labels are added (numba unifies them)
        o: Any = 0
        s: Any = 0
        m: Any = 0
        for j in range(labels.shape[1]):
            t = np.int32(labels[i, j])
            a = t if t >= 0 else -t
            z += t == 0
            o += a % 2
            s += a
            m = max(m, a)
        n_zero[i], n_odd[i], abs_sum[i], abs_max[i] = z, o, s, m


def label_stats(labels: np.ndarray) -> dict[str, np.ndarray]:
    """Per-row summary columns of ``labels (m, n_edges) int8`` (one compiled pass)."""
    labels = np.ascontiguousarray(labels, dtype=np.int8)
    m = len(labels)
    out: dict[str, np.ndarray] = {
        "n_zero": np.empty(m, np.int16),
        "n_odd": np.empty(m, np.int16),
        "abs_sum": np.empty(m, np.int32),
        "abs_max": np.empty(m, np.int16),
    }
    label_stats_kernel(labels, out["n_zero"], out["n_odd"], out["abs_sum"], out["abs_max"])
    out["n_even"] = (labels.shape[1] - out["n_odd"]).astype(np.int16)
    return out


def blocks_to_batch(blocks: list[Block], n_edges: int, periodic: bool) -> pa.RecordBatch:
    """One record batch of the designs schema from :class:`~lkspace.design.walk.Block` s."""
    schema = design_schema(n_edges, periodic)
    sizes = np.array([len(b.labels) for b in blocks], np.int64)
    labels = np.concatenate([b.labels for b in blocks]) if blocks else np.zeros((0, n_edges), np.int8)
    labels = np.ascontiguousarray(labels, dtype=np.int8)
    m = len(labels)
    stats = label_stats(labels)
    strand_counts = np.repeat([len(b.info.strand_lengths) for b in blocks], sizes) if blocks else np.zeros(0, np.int64)
    strand_values = (
        np.concatenate([np.tile(b.info.strand_lengths, len(b.labels)) for b in blocks])
        if blocks
        else np.zeros(0, np.int64)
    )
    cols = {
        "labels": pa.ListArray.from_arrays(
            pa.array(np.arange(m + 1, dtype=np.int32) * n_edges), pa.array(labels.reshape(-1), pa.int8())
        ),
        "key": pa.FixedSizeBinaryArray.from_buffers(pa.binary(n_edges), m, [None, pa.py_buffer(labels.tobytes())]),
        "components": pa.array(np.repeat([b.info.components for b in blocks], sizes).astype(np.int16)),
        "orbit_size": pa.array(np.concatenate([b.orbit_sizes for b in blocks]) if blocks else np.zeros(0, np.int64)),
        "holds_together": pa.array(np.concatenate([b.holds_together for b in blocks]) if blocks else np.zeros(0, bool)),
        **{k: pa.array(v) for k, v in stats.items()},
        "residue_class": pa.array(np.repeat([b.class_code for b in blocks], sizes).astype(np.int64)),
        "strand_lengths": list_column(strand_values.astype(np.int32), strand_counts, pa.list_(pa.int32())),
    }
    if periodic:
        inf = [int(np.sum(np.any(b.info.periods != 0, axis=1))) for b in blocks]
        cols["n_infinite"] = pa.array(np.repeat(inf, sizes).astype(np.int16))
        cols["strand_periods"] = periods_column([b.info.periods for b in blocks], sizes.tolist())
    return pa.RecordBatch.from_arrays([cols[f.name] for f in schema], schema=schema)


def residue_rows_to_batch(rows: list[dict[str, Any]], periodic: bool) -> pa.RecordBatch:
    """Record batch of the residues schema from row dicts (few rows: one per class orbit)."""
    schema = residue_schema(periodic)
    data = {f.name: [r[f.name] for r in rows] for f in schema}
    data["residue_class"] = [c if c <= INT64_MAX else None for c in data["residue_class"]]
    return pa.RecordBatch.from_pydict(data, schema=schema)


def design_batches(
    space: DesignSpace,
    class_ids: Iterable[int] | None = None,
    components: int | None = None,
    max_designs: int | None = None,
    batch_rows: int | None = None,
) -> Iterator[pa.RecordBatch]:
    """Arrow record batches of designs (catalog schema), streamed class by class."""
    batch_rows = batch_rows or ROW_GROUP
    n_edges, periodic = space.scaffold.n_edges, space.scaffold.periodic
    pending, n_pending, n_total = [], 0, 0
    for block in walk_blocks(space, class_ids, components):
        if max_designs is not None and n_total + len(block.labels) > max_designs:
            keep = max_designs - n_total
            block = Block(
                block.class_code,
                block.residues,
                block.info,
                block.labels[:keep],
                block.orbit_sizes[:keep],
                block.holds_together[:keep],
            )
        pending.append(block)
        n_pending += len(block.labels)
        n_total += len(block.labels)
        if n_pending >= batch_rows:
            yield blocks_to_batch(pending, n_edges, periodic)
            pending, n_pending = [], 0
        if max_designs is not None and n_total >= max_designs:
            break
    if pending:
        yield blocks_to_batch(pending, n_edges, periodic)


def residue_batches(
    space: DesignSpace,
    class_ids: Iterable[int] | None = None,
    components: int | None = None,
    max_designs: int | None = None,
    batch_rows: int | None = None,
) -> Iterator[pa.RecordBatch]:
    """Record batches of ``--mode residues`` rows: one per residue-class orbit."""
    batch_rows = batch_rows or ROW_GROUP
    co = space.classes
    rows: list[dict] = []
    n_total = 0
    for c in range(len(co.codes)) if class_ids is None else class_ids:
        info = space.class_info(co.residues[c])
        if components is not None and info.components != components:
            continue
        rows.append(residue_row(space, co.indices[c], co.stabilizers[c], info))
        n_total += 1
        if len(rows) >= batch_rows:
            yield residue_rows_to_batch(rows, space.scaffold.periodic)
            rows = []
        if max_designs is not None and n_total >= max_designs:
            break
    if rows:
        yield residue_rows_to_batch(rows, space.scaffold.periodic)


def space_batches(
    space: DesignSpace,
    mode: str,
    class_ids: Iterable[int] | None = None,
    components: int | None = None,
    max_designs: int | None = None,
    sample: int | None = None,
    seed: int = 0,
) -> Iterator[pa.RecordBatch]:
    """Record batches of ``space`` for ``mode`` (``designs``, ``residues`` or ``spanning-trees``)."""
    if mode == "designs":
        return design_batches(space, class_ids, components, max_designs)
    if mode == "residues":
        return residue_batches(space, class_ids, components, max_designs)
    rows = spanning_tree_rows(space, sample=sample, seed=seed, max_designs=max_designs)
    return iter([residue_rows_to_batch(rows, space.scaffold.periodic)])
