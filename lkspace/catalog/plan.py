"""The plan of a catalog run, made before any row is written: its size, its bounds, its parts.

The plan depends on the design space and the selection only, never on ``jobs``: the
representative residue classes are cut into contiguous runs of about
:data:`PART_ROWS` designs (exact Burnside counts per class), one part each.  So a run
interrupted with 4 jobs resumes with 1 and finds the same parts.
The estimate of rows and bytes is checked against :data:`ROW_LIMIT` and
:data:`BYTE_LIMIT` (past them the caller must allow a large run, ``Execution(allow_large=True)``)
and :data:`MAX_PARTS` (past it nothing is written at all): :class:`CatalogTooLarge`.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass

import numpy as np

from ..design.counting import class_weights
from ..design.space import DesignSpace
from ..errors import CatalogError, TooLargeError, UsageError
from ..model.counts import count_text
from .options import Execution, Selection

PART_ROWS = 1_000_000
"""Designs per part of a sharded catalog (about): a walk with more rows becomes a folder."""

MAX_JOBS = 256
"""Largest ``jobs``: worker processes beyond this only cost memory."""

ROW_LIMIT = 100_000_000
"""Rows a run may write unless it allows a large run (``allow_large=True``)."""

BYTE_LIMIT = 2_000_000_000
"""Estimated bytes a run may write unless it allows a large run (``allow_large=True``)."""

MAX_PARTS = 100_000
"""Parts a catalog may have even with ``allow_large=True`` (``MAX_PARTS * PART_ROWS`` rows): larger runs are refused."""

MAX_SHARDS = MAX_PARTS
"""Largest ``shards``."""


def estimated_bytes(rows: int, n_edges: int) -> int:
    """Rough size on disk of ``rows`` catalog rows of a scaffold with ``n_edges`` edges.

    Measured: 5.1 bytes per row for the cube (12 edges, zstd); the estimate scales with
    the edges, as the ``labels`` and ``key`` columns do.
    """
    return int(rows * (0.5 + 0.4 * n_edges))


@dataclass(frozen=True)
class Plan:
    """What a run will write.

    Attributes
    ----------
    rows : int
        Rows expected (exact for design walks, an upper bound otherwise).
    bytes : int
        Rough size on disk (:func:`estimated_bytes`).
    ranges : list of list of int, or None
        Representative class ids of each part, in order; ``None``: one part, the whole walk.
    """

    rows: int
    bytes: int
    ranges: list[list[int]] | None

    @property
    def parts(self) -> int:
        """Number of parts (1: a single Parquet file)."""
        return 1 if self.ranges is None else len(self.ranges)

    @property
    def fingerprint(self) -> str:
        """A short hash of the parts' class ranges: equal plans, equal fingerprints."""
        ranges = None if self.ranges is None else [[r[0], r[-1], len(r)] if r else [] for r in self.ranges]
        text = json.dumps(ranges)
        return hashlib.sha256(text.encode()).hexdigest()[:16]


def split_classes(weights: np.ndarray, n_shards: int) -> list[list[int]]:
    """Split the representative classes into contiguous runs with about equal design counts."""
    w = np.asarray([int(x) for x in weights], np.float64)
    cum = np.cumsum(w)
    total = cum[-1] if len(cum) else 0.0
    cuts = np.searchsorted(cum, total * np.arange(1, n_shards) / n_shards, side="left")
    bounds = [0, *cuts.tolist(), len(w)]
    return [[c for c in range(bounds[i], bounds[i + 1]) if w[c] > 0] for i in range(n_shards)]


class CatalogTooLarge(TooLargeError):
    """A catalog run past a size bound.

    Attributes
    ----------
    estimate : str
        What the run would write: ``"cube: about 576,941,778 rows (3.1 GB) to write, past ..."``.
    allowable : bool
        Whether ``allow_large=True`` lets it go ahead (``False``: past :data:`MAX_PARTS`, refused).
    """

    def __init__(self, estimate: str, allowable: bool) -> None:
        remedy = "count the designs, filter them or use a smaller label set"
        if allowable:
            remedy = f"pass Execution(allow_large=True) to go ahead (or {remedy})"
        super().__init__(f"{estimate}; {remedy}")
        self.estimate = estimate
        self.allowable = allowable


def check_jobs(jobs: int) -> None:
    """Raise :class:`UsageError` unless ``1 <= jobs <=`` :data:`MAX_JOBS`."""
    if not 1 <= jobs <= MAX_JOBS:
        raise UsageError(f"jobs {jobs}: use 1..{MAX_JOBS} worker processes", parameter="jobs")


def make_plan(space: DesignSpace, selection: Selection, execution: Execution) -> Plan:
    """Estimate the run and cut it into ``execution.shards`` parts; refuse it when it is past a bound.

    Raises
    ------
    CatalogTooLarge
        The estimate is past :data:`ROW_LIMIT` or :data:`BYTE_LIMIT` and
        ``execution.allow_large`` is false, or past :data:`MAX_PARTS` parts.
    """
    n_edges, shards, allow_large = space.scaffold.n_edges, execution.shards, execution.allow_large
    mode, max_designs = selection.mode, selection.max_designs
    if shards is not None and not 1 <= shards <= MAX_SHARDS:
        raise UsageError(f"shards {shards}: use 1..{MAX_SHARDS} parts", parameter="shards")
    weights: np.ndarray | None = None
    if mode == "designs":
        weights = class_weights(space, selection.components)
        rows = int(sum(weights))
    elif mode == "residues":
        rows = len(space.classes.codes)
    else:  # spanning trees: at most one row per tree listed or sampled
        from ..design.spanning import MAX_TREES

        rows = selection.sample if selection.sample is not None else MAX_TREES
    if max_designs is not None:
        rows = min(rows, max_designs)
    size = estimated_bytes(rows, n_edges)
    needed = -(-rows // PART_ROWS)
    about = f"{space.scaffold.name}: about {count_text(rows)} rows ({_gb(size)})"
    if needed > MAX_PARTS:
        raise CatalogTooLarge(f"{about} is past what lkspace writes ({MAX_PARTS * PART_ROWS:,} rows)", False)
    if not allow_large and (rows > ROW_LIMIT or size > BYTE_LIMIT):
        raise CatalogTooLarge(f"{about} to write, past {ROW_LIMIT:,} rows or {_gb(BYTE_LIMIT)}", True)
    whole_walk = mode == "designs" and max_designs is None
    if shards is None:
        shards = max(1, needed) if whole_walk else 1
    if shards > 1 and not whole_walk:
        raise CatalogError(
            "shards applies to full design walks (not with max_designs or other modes)", usage=True, parameter="shards"
        )
    if shards == 1 or weights is None:
        return Plan(rows, size, None)
    return Plan(rows, size, split_classes(weights, shards))


def plan_fingerprint(space: DesignSpace, selection: Selection, parts: int) -> str:
    """Return the fingerprint of the plan of a run of ``space`` and ``selection`` cut into ``parts`` parts.

    What the ``shard`` of every file of such a catalog records (:attr:`Plan.fingerprint`);
    :func:`~lkspace.catalog.verify.verify_catalog` computes it again.  One part is one
    range, whatever the space (no counts needed).

    Raises
    ------
    LkspaceError
        ``parts`` that no run of these settings is cut into.
    """
    if parts == 1:
        return Plan(0, 0, None).fingerprint
    return make_plan(space, selection, Execution(shards=parts, allow_large=True)).fingerprint


def _gb(n: int) -> str:
    return f"{n / 1e9:.1f} GB" if n >= 1e8 else f"{n / 1e6:.1f} MB"
