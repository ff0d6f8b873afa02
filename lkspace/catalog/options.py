"""The options of a catalog run, as records: which rows (:class:`Selection`) and how it runs (:class:`Execution`).

:func:`~lkspace.write_catalog` takes one of each; both default to the plain run (every
design, one process)::

    write_catalog("cube", "cube.parquet", "-1..1",
                  selection=Selection(components=1, identify=True),
                  execution=Execution(jobs=2, shards=4, resume=True))

:func:`~lkspace.designs` takes a :class:`Selection` too (``identify`` aside: it writes no files).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..design.space import WalkMode


@dataclass(frozen=True)
class Selection:
    """Which rows a catalog holds.

    Attributes
    ----------
    mode : {"designs", "residues", "spanning-trees"}
        One row per design, per residue-class orbit (topology), or per dual spanning tree.
    components : int or None
        Keep rows with this many components (``None``: all).
    max_designs : int or None
        Stop after this many rows (``None``: the whole walk).
    sample : int or None
        ``"spanning-trees"`` mode: sample this many uniform spanning trees instead of listing all.
    seed : int
        Random seed of ``sample``.
    identify : bool
        Add knot/link columns to the rows (a written catalog only: :func:`~lkspace.write_catalog`).
    by_key : bool
        With ``identify``: name by key only, never in full
        (:attr:`~lkspace.knots.batch.NamerOptions.by_key`), for spaces too big to name.
    """

    mode: WalkMode = "designs"
    components: int | None = None
    max_designs: int | None = None
    sample: int | None = None
    seed: int = 0
    identify: bool = False
    by_key: bool = False

    def __post_init__(self) -> None:
        """Refuse a mode lkspace does not walk, counts below 1 and a seed below 0.

        They had given 0 rows, every row (``max_designs=-3``), the designs walk (``mode="bogus"``)
        or an internal error (``seed=-1``).
        """
        from ..design.space import WALK_MODES
        from ..errors import UsageError

        if self.mode not in WALK_MODES:
            raise UsageError(f"mode {self.mode!r}: use one of {', '.join(WALK_MODES)}", parameter="mode")
        for name in ("components", "max_designs", "sample", "seed"):
            value = getattr(self, name)
            least = 0 if name == "seed" else 1
            if value is None and name != "seed":
                continue
            if isinstance(value, bool) or not isinstance(value, int) or value < least:
                raise UsageError(f"{name}: must be an integer of at least {least}, got {value!r}", parameter=name)


@dataclass(frozen=True)
class Execution:
    """How a catalog run executes: processes, parts, where they run, and whether it resumes.

    Attributes
    ----------
    jobs : int
        Worker processes (1..:data:`~lkspace.catalog.plan.MAX_JOBS`); they write whole parts.
    shards : int or None
        Parts of the catalog (``None``: one per :data:`~lkspace.catalog.plan.PART_ROWS` designs).
    scheduler : str or None
        Where parts run (:mod:`lkspace.runtime.schedulers`): ``"local"``, ``"dask"`` or a Dask scheduler
        address; ``None``: ``$DASK_SCHEDULER_ADDRESS`` or local.
    resume : bool
        Keep the verified parts of an interrupted run and write the rest.
    allow_large : bool
        Go ahead with a run estimated past :data:`~lkspace.catalog.plan.ROW_LIMIT` rows or
        :data:`~lkspace.catalog.plan.BYTE_LIMIT` bytes (refused otherwise, before any work).
    """

    jobs: int = 1
    shards: int | None = None
    scheduler: str | None = None
    resume: bool = False
    allow_large: bool = False
