"""lkspace: knots, links and chainmail designed by twist labels on polygon meshes.

The public API, loaded on first use (``import lkspace`` stays fast); every function that
works on a scaffold also takes a path or a built-in name (:mod:`lkspace.api` loads it):

===========================  ===============================================================
:func:`load`                 a scaffold from a built-in name or a ``.obj`` / ``.json`` file
:func:`trace`                the strands of a labelled scaffold (:class:`Trace`)
:func:`designs`              a design space, batch by batch (pandas DataFrames)
:func:`symmetric_designs`    the designs fixed by a subgroup of the symmetries (``--invariant``)
:func:`count_designs`        exact counts of a design space, without listing it
:func:`write_catalog`        a design space written to a Parquet catalog
:func:`read_catalog`         a catalog back, labels as one ``(n, n_edges) int8`` array
:func:`verify_catalog`       a catalog checked whole (every part's checksum) before pandas reads it
:func:`solve`                designs with exactly N components (CP-SAT)
:func:`realize`              strands as 3D curves (:class:`Realization`)
:func:`relax`                the curves drawn tight, link type kept
:func:`export`               strands to ``.obj``, ``.ply``, ``.glb`` or ``.png``
:func:`identify`             the knot or link type (extra ``[knots]``)
===========================  ===============================================================

Quick start
-----------
>>> import lkspace
>>> lkspace.trace("tetrahedron", 1)
Trace(tetrahedron: 3 components, holds together, lengths [4, 4, 4])
"""

from __future__ import annotations

import importlib
import warnings
from typing import TYPE_CHECKING, Any

from .errors import CatalogError, LabelError, LkspaceError, MissingDependencyError, ScaffoldError

if TYPE_CHECKING:
    from . import api
    from .catalog import listing, shards, symmetric
    from .catalog.options import Execution, Selection
    from .catalog.reader import Catalog, read_catalog
    from .catalog.shards import CatalogWritten
    from .catalog.verify import CatalogCheck, verify_catalog
    from .design import counting
    from .design.counting import DesignCount
    from .formats import registry
    from .formats.options import GlbOptions, MeshOptions, PictureOptions, PrintOptions
    from .geometry import realization
    from .geometry.params import RealizeOptions
    from .geometry.realization import GeometryParams, Realization
    from .geometry.relax import relax
    from .inverse import pipeline
    from .inverse.pipeline import Solution, SolveOptions, SolveResult
    from .io.sources import load
    from .knots import recognition
    from .knots.recognition import Identification
    from .model.lattice import Lattice
    from .model.scaffold import Scaffold
    from .strands import tracing
    from .strands.tracing import Trace

    # what type checkers see: the functions of ``api.SCAFFOLD_FIRST`` as lkspace.__getattr__ hands them out
    trace = api.loading(tracing.trace)
    designs = api.loading(listing.designs)
    symmetric_designs = api.loading(symmetric.symmetric_designs)
    count_designs = api.loading(counting.count_designs)
    write_catalog = api.loading(shards.write_catalog)
    solve = api.loading(pipeline.solve)
    realize = api.loading(realization.realize)
    export = api.loading(registry.export)
    identify = api.loading(recognition.identify)
    __version__: str

_LAZY = {
    "Scaffold": "model.scaffold",
    "Lattice": "model.lattice",
    "load": "io.sources",
    "trace": "strands.tracing",
    "Trace": "strands.tracing",
    "designs": "catalog.listing",
    "symmetric_designs": "catalog.symmetric",
    "count_designs": "design.counting",
    "DesignCount": "design.counting",
    "write_catalog": "catalog.shards",
    "CatalogWritten": "catalog.shards",
    "Selection": "catalog.options",
    "Execution": "catalog.options",
    "read_catalog": "catalog.reader",
    "Catalog": "catalog.reader",
    "verify_catalog": "catalog.verify",
    "CatalogCheck": "catalog.verify",
    "solve": "inverse.pipeline",
    "SolveResult": "inverse.pipeline",
    "SolveOptions": "inverse.pipeline",
    "Solution": "inverse.pipeline",
    "realize": "geometry.realization",
    "Realization": "geometry.realization",
    "GeometryParams": "geometry.realization",
    "RealizeOptions": "geometry.params",
    "relax": "geometry.relax",
    "export": "formats.registry",
    "MeshOptions": "formats.options",
    "GlbOptions": "formats.options",
    "PrintOptions": "formats.options",
    "PictureOptions": "formats.options",
    "identify": "knots.recognition",
    "Identification": "knots.recognition",
}
"""Public name -> the module (under ``lkspace``) that defines it, imported on first use."""

__all__ = [
    "load",
    "trace",
    "Trace",
    "designs",
    "symmetric_designs",
    "count_designs",
    "DesignCount",
    "write_catalog",
    "CatalogWritten",
    "Selection",
    "Execution",
    "read_catalog",
    "Catalog",
    "verify_catalog",
    "CatalogCheck",
    "solve",
    "SolveResult",
    "SolveOptions",
    "Solution",
    "realize",
    "Realization",
    "GeometryParams",
    "RealizeOptions",
    "relax",
    "export",
    "MeshOptions",
    "GlbOptions",
    "PrintOptions",
    "PictureOptions",
    "identify",
    "Identification",
    "Scaffold",
    "Lattice",
    "LkspaceError",
    "ScaffoldError",
    "LabelError",
    "CatalogError",
    "MissingDependencyError",
    "__version__",
]


SUBPACKAGES = (
    "model",
    "strands",
    "symmetry",
    "design",
    "catalog",
    "inverse",
    "geometry",
    "formats",
    "knots",
    "io",
    "scaffolds",
    "cli",
)
"""Subpackages reachable as attributes (``lkspace.io.write``), imported on first use."""


def __getattr__(name: str) -> Any:
    """Import public names and subpackages on first use; ``enumerate`` is a deprecated alias of :func:`designs`."""
    if name == "enumerate":
        warnings.warn("lkspace.enumerate is deprecated; use lkspace.designs", DeprecationWarning, stacklevel=2)
        name = "designs"
    if name in SUBPACKAGES:
        return importlib.import_module(f".{name}", __name__)
    if name == "__version__":  # read on first use: the program's first instants stay short (lkspace.__main__)
        globals()[name] = _version()
        return globals()[name]
    if name not in _LAZY:
        raise AttributeError(f"module 'lkspace' has no attribute {name!r}")
    value = getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
    from . import api

    if name in api.SCAFFOLD_FIRST:  # a path or a built-in name is loaded here, at the boundary
        value = api.loading(value, api.SCAFFOLD_FIRST[name])
    globals()[name] = value
    return value


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("lkspace")
    except PackageNotFoundError:  # pragma: no cover - running from a source tree without installing
        return "0+unknown"


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY) | set(SUBPACKAGES))
