"""Knot and link identification of realized strands (extra ``[knots]``).

Pipeline: :func:`lkspace.geometry.realization.realize` -> :func:`lkspace.knots.diagram.project`
(generic projection, PD code) -> :func:`lkspace.knots.naming.name_pd` (spherogram
``simplify('global')``, then the tables of :mod:`lkspace.knots.tables`) -> names.

Naming.  The Jones polynomial (regina, no Sage) of the simplified diagram, evaluated
exactly at ``sqrt(t) = 2/3`` and ``3/2`` (its mirror), is looked up in the KnotInfo
(knots up to 13 crossings) and LinkInfo (links up to 11 crossings, every orientation)
tables of ``database_knotinfo``.  Candidates are narrowed by the HOMFLY-PT polynomial
(regina, computed on our diagram and on the table's own PD code, so conventions agree)
and by SnapPy's ``identify()`` of the exterior.  A single remaining table entry is
accepted only if the hyperbolic volume agrees (zero for torus and satellite knots and
links, which ``identify()`` cannot name); otherwise ``name`` is ``None`` and the
invariants are returned.  Names: ``"0_1"``, Rolfsen ``"3_1"``..., Thistlethwaite
``"L2a1"``...; ``mirror`` says whether the structure is the table diagram's mirror image
(``None`` when the knot or link equals its mirror as far as HOMFLY-PT tells).
KnotInfo's ``3_1`` is the right-handed (positive) trefoil.
"""

from __future__ import annotations

import json
import multiprocessing as mp
import sys
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd
from numpy.typing import ArrayLike

from ..errors import LkspaceError
from ..geometry.realization import GeometryParams, realize
from ..io.sources import ScaffoldSource, load
from ..model.scaffold import Scaffold
from .diagram import DiagramError, project
from .naming import name_pd
from .tables import knot_modules, tables


@dataclass(frozen=True, repr=False)
class Identification:
    """The knot or link type of a closed structure.

    Attributes
    ----------
    components : int
    name : str or None
        ``"0_1"``, Rolfsen (``"3_1"``) or Thistlethwaite (``"L6a4"``) name; ``None`` if unknown.
    linking_matrix : list of list of int
    mirror : bool or None
        The structure is the table diagram's mirror image (``None``: the tables cannot tell).
    split : bool or None
    crossings : int or None
        Crossings of the simplified diagram.
    details : dict
        Everything else: ``jones``, ``homfly``, ``volume``, ``candidates``, ``pieces``, ...
    """

    components: int
    name: str | None
    linking_matrix: list[list[int]]
    mirror: bool | None = None
    split: bool | None = None
    crossings: int | None = None
    details: dict[str, Any] = field(default_factory=dict)

    def __repr__(self) -> str:
        chirality = {True: ", mirror", False: "", None: ""}[self.mirror]
        return f"Identification({self.name or 'unknown'}{chirality}: {self.components} components, {self.crossings} crossings)"

    def to_dict(self) -> dict[str, Any]:
        """Return the JSON form (``components``, ``name``, ``linking_matrix``, and every invariant)."""
        return {
            "components": self.components,
            "name": self.name,
            "linking_matrix": self.linking_matrix,
            "mirror": self.mirror,
            "split": self.split,
            "crossings": self.crossings,
            **self.details,
        }


def identify_curves(curves: Sequence[np.ndarray], seed: int = 0) -> dict[str, Any]:
    """Identify the link formed by closed polylines ``curves`` (list of ``(n_k, 3)``).

    Returns
    -------
    dict
        ``components``, ``name``, ``linking_matrix``, ``projected_crossings`` and the
        results of :func:`name_pd` (invariants, see the module docstring).
    """
    diagram = project(curves, seed=seed)
    out = {
        "components": len(curves),
        "linking_matrix": diagram.linking_matrix().tolist(),
        "projected_crossings": diagram.n_crossings,
    }
    out.update(name_pd(diagram.pd, len(curves)))
    return out


def identify(
    scaffold: ScaffoldSource,
    labels: ArrayLike | None = None,
    nulls: ArrayLike | None = None,
    params: GeometryParams | None = None,
    seed: int = 0,
) -> Identification:
    """Knot or link type of a scaffold labelled by twist ``labels`` (extra ``[knots]``).

    Parameters
    ----------
    scaffold : Scaffold, path or built-in name
    labels, nulls : as for :func:`lkspace.trace`
    params : GeometryParams, optional
        Realization parameters.
    seed : int
        Seed of the generic projection.

    Examples
    --------
    >>> identify("dihedron:3", 1)
    Identification(3_1: 1 components, 3 crossings)
    """
    scaffold = load(scaffold)
    real = realize(scaffold, labels, nulls, params)
    if not real.closed.all():
        tr = real.trace
        reason = "open strands (null edge-sides)" if not tr.closed.all() else "infinite periodic threads"
        raise LkspaceError(f"{scaffold.name}: cannot identify a structure with {reason}")
    for attempt in range(3):  # a rare non-generic projection: turn again
        try:
            out = identify_curves(real.curves, seed=seed + attempt)
            break
        except DiagramError:
            if attempt == 2:
                raise
    out["min_distance"] = real.min_distance
    main = {k: out.pop(k, None) for k in ("components", "name", "linking_matrix", "mirror", "split", "crossings")}
    return Identification(**main, details=out)


_WORKER: dict[str, Any] = {}


def _init_worker(scaffold: Scaffold, seed: int) -> None:
    _WORKER["scaffold"], _WORKER["seed"] = scaffold, seed


def _identify_row(labels: ArrayLike) -> dict[str, Any]:
    try:
        r = identify(_WORKER["scaffold"], np.asarray(labels, np.int64), seed=_WORKER["seed"]).to_dict()
        return {
            "knot_name": r["name"],
            "components": r["components"],
            "split": r.get("split"),
            "mirror": r.get("mirror"),
            "crossings": r.get("crossings"),
            "jones": r.get("jones"),
            "linking_matrix": json.dumps(r["linking_matrix"]),
            "error": None,
        }
    except LkspaceError as exc:
        return {
            "knot_name": None,
            "components": None,
            "split": None,
            "mirror": None,
            "crossings": None,
            "jones": None,
            "linking_matrix": None,
            "error": str(exc),
        }


COLUMNS = ["knot_name", "components", "split", "mirror", "crossings", "jones", "linking_matrix", "error"]


def identify_batch(
    scaffold: Scaffold, labels_2d: ArrayLike, processes: int = 1, seed: int = 0, progress: bool | None = None
) -> pd.DataFrame:
    """Identify many designs of one scaffold: a ``pandas.DataFrame``, one row per design.

    Parameters
    ----------
    scaffold : Scaffold
    labels_2d : (n_designs, n_edges) int
    processes : int
        Worker processes (``1``: in this process).  Workers are forked and receive the
        scaffold once; rows travel in chunks.
    seed : int
        Seed of the generic projection.
    progress : bool, optional
        Show a progress bar on stderr (default: when stderr is a terminal).

    Returns
    -------
    pandas.DataFrame
        Columns ``knot_name`` (missing when unknown or split), ``components``, ``split``,
        ``mirror``, ``crossings`` (simplified diagram), ``jones``, ``linking_matrix`` (JSON
        text) and ``error`` (missing unless the design could not be identified, e.g.
        open strands), in the order of ``labels_2d``.

    Examples
    --------
    >>> identify_batch(load("dihedron:3"), [[1, 1, 1], [1, 0, 0]])["knot_name"].tolist()
    ['3_1', '0_1']
    """
    knot_modules()
    tables()  # loaded once, shared by forked workers
    labels_2d = np.asarray(labels_2d, np.int64).reshape(-1, scaffold.n_edges)
    if progress is None:
        progress = sys.stderr.isatty()
    _init_worker(scaffold, seed)
    chunk = max(1, min(64, len(labels_2d) // (4 * max(processes, 1)) or 1))
    rows_iter: Iterator[dict[str, Any]]
    if processes > 1 and len(labels_2d) > 1:
        pool = mp.get_context("fork").Pool(processes, initializer=_init_worker, initargs=(scaffold, seed))
        rows_iter = pool.imap(_identify_row, labels_2d, chunksize=chunk)
    else:
        pool = None
        rows_iter = map(_identify_row, labels_2d)
    try:
        if progress:
            from rich.console import Console
            from rich.progress import track

            rows = list(
                track(
                    rows_iter,
                    total=len(labels_2d),
                    description="identifying",
                    transient=True,
                    console=Console(stderr=True),
                )
            )
        else:
            rows = list(rows_iter)
    finally:
        if pool is not None:
            pool.close()
            pool.join()
    return pd.DataFrame(rows, columns=COLUMNS)
