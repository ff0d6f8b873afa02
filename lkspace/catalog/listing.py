"""Design rows in memory: :func:`designs`, the batch iterator over a design space."""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

from ..design.space import WALK_MODES, make_space
from ..errors import LabelError
from ..model.scaffold import Scaffold
from ..model.specs import LabelSetSpec
from ..symmetry.group import SymmetryMode
from .batches import design_batches, space_batches
from .options import Selection
from .residue_rows import residue_batches

if TYPE_CHECKING:
    import pandas as pd
    import pyarrow as pa


def designs(
    scaffold: Scaffold,
    label_set: LabelSetSpec = "-2..2",
    symmetry: SymmetryMode = "rotations",
    *,
    selection: Selection | None = None,
    no_zero: bool = False,
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
    selection : Selection, optional
        Which rows (:class:`~lkspace.catalog.options.Selection`: ``mode``, ``components``,
        ``max_designs``, ``sample``, ``seed``; default every design), as for
        :func:`~lkspace.write_catalog`.
    no_zero : bool
        Leave out designs with a zero label.
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
    >>> trees = next(lkspace.designs("cube", "-1..1", selection=lkspace.Selection(mode="spanning-trees")))
    >>> int(trees.components.max())
    1
    """
    sel = selection or Selection()
    space = make_space(scaffold, label_set, symmetry, no_zero, tolerance)
    if sel.mode not in WALK_MODES:
        raise LabelError(f"unknown mode {sel.mode!r}; choose one of {', '.join(WALK_MODES)}")
    if sel.mode == "designs":
        batches = design_batches(space, None, sel.components, sel.max_designs, batch_rows)
    elif sel.mode == "residues":
        batches = residue_batches(space, None, sel.components, sel.max_designs, batch_rows)
    else:
        batches = space_batches(space, sel.mode, sample=sel.sample, seed=sel.seed, max_designs=sel.max_designs)
    for batch in batches:
        yield batch if as_arrow else batch.to_pandas()
