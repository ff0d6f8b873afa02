"""Design rows in memory: :func:`designs`, the batch iterator over a design space."""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

from ..design.space import WALK_MODES, WalkMode, make_space
from ..errors import LabelError
from ..model.scaffold import Scaffold
from ..model.specs import LabelSetSpec
from ..symmetry.group import SymmetryMode
from .batches import design_batches, residue_batches, space_batches

if TYPE_CHECKING:
    import pandas as pd
    import pyarrow as pa


def designs(
    scaffold: Scaffold,
    label_set: LabelSetSpec = "-2..2",
    symmetry: SymmetryMode = "rotations",
    *,
    mode: WalkMode = "designs",
    components: int | None = None,
    no_zero: bool = False,
    max_designs: int | None = None,
    sample: int | None = None,
    seed: int = 0,
    batch_rows: int | None = None,
    as_arrow: bool = False,
    tolerance: float | None = None,
) -> Iterator[pd.DataFrame | pa.RecordBatch]:
    """Walk a design space and yield its catalog rows in batches (no files).

    Parameters
    ----------
    scaffold : Scaffold
        ``lkspace.designs`` also takes a path or a built-in name (:func:`lkspace.load`).
    label_set : str or sequence of int
        The label set ``SET`` (``"-2..2"``, ``"-2,2"``, or a list).
    symmetry : {"rotations", "isometries", "none"}
    mode : {"designs", "residues", "spanning-trees"}
        One row per design, per residue-class orbit, or per spanning-tree class.
    components, no_zero, max_designs
        Filters applied during the walk.
    sample, seed
        ``spanning-trees`` only: sample ``sample`` uniform spanning trees instead of all.
    batch_rows : int, optional
        Rows per batch (default 262,144).
    as_arrow : bool
        Yield ``pyarrow.RecordBatch`` instead of pandas DataFrames.
    tolerance : float, optional
        Symmetry search tolerance in mesh units (default: 1/100 of the shortest edge).

    Yields
    ------
    pandas.DataFrame or pyarrow.RecordBatch
        Columns as in ``docs/catalog.md``.

    Examples
    --------
    >>> import lkspace
    >>> df = next(lkspace.designs("tetrahedron", "-2,2"))
    >>> len(df), int(df.orbit_size.sum())
    (12, 64)
    """
    space = make_space(scaffold, label_set, symmetry, no_zero, tolerance)
    if mode not in WALK_MODES:
        raise LabelError(f"unknown mode {mode!r}; choose one of {', '.join(WALK_MODES)}")
    if mode == "designs":
        batches = design_batches(space, None, components, max_designs, batch_rows)
    elif mode == "residues":
        batches = residue_batches(space, None, components, max_designs, batch_rows)
    else:
        batches = space_batches(space, mode, sample=sample, seed=seed, max_designs=max_designs)
    for batch in batches:
        yield batch if as_arrow else batch.to_pandas()
