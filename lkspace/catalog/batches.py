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

from ..compiled.kernels import kernel
from ..design.batch import concat_traces
from ..design.space import DesignSpace, WalkMode
from ..design.spanning import spanning_tree_rows
from ..design.walk import DesignBlock, walk_blocks
from ..model.scaffold import Scaffold
from .columns import numpy_column, residue_rows_to_batch, strand_columns
from .residue_rows import residue_batches
from .schema import ROW_GROUP, design_schema


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


def blocks_to_batch(blocks: list[DesignBlock], n_edges: int, periodic: bool) -> pa.RecordBatch:
    """One record batch of the designs schema from :class:`~lkspace.design.walk.DesignBlock` s."""
    schema = design_schema(n_edges, periodic)
    if not blocks:
        return pa.RecordBatch.from_pylist([], schema=schema)
    labels = np.ascontiguousarray(np.concatenate([b.labels for b in blocks]), dtype=np.int8)
    m = len(labels)
    stats = label_stats(labels)
    offsets = np.cumsum([0] + [len(b.class_codes) for b in blocks])
    row_class = np.concatenate([b.row_class + o for b, o in zip(blocks, offsets, strict=False)])
    traces = blocks[0].traces if len(blocks) == 1 else concat_traces([b.traces for b in blocks])
    codes = np.concatenate([b.class_codes for b in blocks]).astype(np.int64)
    cols = {
        "labels": pa.ListArray.from_arrays(
            numpy_column(np.arange(m + 1, dtype=np.int32) * n_edges), numpy_column(labels.reshape(-1))
        ),
        "key": pa.FixedSizeBinaryArray.from_buffers(pa.binary(n_edges), m, [None, pa.py_buffer(labels.tobytes())]),
        "components": numpy_column(traces.components[row_class].astype(np.int16)),
        "orbit_size": numpy_column(np.concatenate([b.orbit_sizes for b in blocks]).astype(np.int64)),
        "holds_together": numpy_column(np.concatenate([b.holds_together for b in blocks])),
        **{k: numpy_column(v) for k, v in stats.items()},
        "residue_class": numpy_column(codes[row_class]),
        **strand_columns(traces, row_class, periodic),
    }
    return pa.RecordBatch.from_arrays([cols[f.name] for f in schema], schema=schema)


def design_batches(
    space: DesignSpace,
    class_ids: Iterable[int] | None = None,
    components: int | None = None,
    max_designs: int | None = None,
    batch_rows: int | None = None,
) -> Iterator[pa.RecordBatch]:
    """Arrow record batches of designs (catalog schema), streamed class by class."""
    blocks = walk_blocks(space, class_ids, components)
    yield from gather_blocks(blocks, space.scaffold, max_designs, batch_rows or ROW_GROUP)


def gather_blocks(
    blocks: Iterable[DesignBlock], scaffold: Scaffold, max_designs: int | None, batch_rows: int
) -> Iterator[pa.RecordBatch]:
    """Record batches of about ``batch_rows`` rows from design ``blocks``, stopping after ``max_designs`` rows."""
    n_edges, periodic = scaffold.n_edges, scaffold.periodic
    pending, n_pending, n_total = [], 0, 0
    for block in blocks:
        if max_designs is not None and n_total + len(block.labels) > max_designs:
            block = block.head(max_designs - n_total)
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


def space_batches(
    space: DesignSpace,
    mode: WalkMode,
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
