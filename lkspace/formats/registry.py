"""Export: one writer per file type behind a registry, chosen by the output's extension.

======  =======================================================================
``.obj``  one object per strand: polylines (``l``) or, with ``tubes=True``, tube meshes
``.ply``  ASCII PLY with a colour per strand: polylines as ``edge``, tubes as ``face``
``.glb``  glTF 2.0 binary: one tube mesh, node and material per strand
``.png``  a matplotlib picture: shaded tubes, the scaffold drawn faintly (``[render]``)
======  =======================================================================

Each format is a module of :mod:`lkspace.formats` with a ``write(real, path, **options)``
function, imported only when used.  Every file is written to a temporary name and renamed
when complete.
"""

from __future__ import annotations

import importlib
import os

from numpy.typing import ArrayLike

from ..errors import ExportError
from ..geometry.realization import GeometryParams, Realization, realize
from ..io.sources import ScaffoldSource

WRITERS = {".obj": "obj", ".ply": "ply", ".glb": "glb", ".png": "png"}
"""Extension -> module of :mod:`lkspace.formats` whose ``write`` writes it."""
FORMATS = tuple(WRITERS)


def export(
    design: Realization | ScaffoldSource,
    path: str | os.PathLike[str],
    labels: ArrayLike | None = None,
    nulls: ArrayLike | None = None,
    *,
    params: GeometryParams | None = None,
    tubes: bool = False,
    radius: float | None = None,
    show_mesh: bool = True,
    title: str | None = None,
) -> str:
    """Write a design's strands to ``path``; the format follows the extension.

    Parameters
    ----------
    design : Realization, Scaffold, path or built-in name
        Realized strands, or a scaffold realized here with ``labels``, ``nulls`` and
        ``params`` (see :func:`lkspace.realize`).
    path : str or os.PathLike
        ``.obj``, ``.ply``, ``.glb`` or ``.png``.
    tubes : bool
        Tube meshes instead of polylines (``.obj``, ``.ply``; ``.glb`` is always tubes).
    radius : float, optional
        Tube radius (default: the realization's).
    show_mesh, title
        ``.png`` only: draw the scaffold faintly; a title.

    Returns
    -------
    str
        The format written (``"obj"``, ...).

    Examples
    --------
    >>> import tempfile, os
    >>> export("tetrahedron", os.path.join(tempfile.mkdtemp(), "t.obj"), 1)
    'obj'
    """
    ext = os.path.splitext(os.fspath(path))[1].lower()
    if ext not in WRITERS:
        raise ExportError(f"{path}: unknown output format {ext or '(none)'!r}; use one of {', '.join(FORMATS)}")
    directory = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(directory):
        raise ExportError(f"{path}: directory {directory} does not exist")
    real = design if isinstance(design, Realization) else realize(design, labels, nulls, params)
    writer = importlib.import_module(f"{__package__}.{WRITERS[ext]}")
    writer.write(real, path, tubes=tubes, radius=radius, show_mesh=show_mesh, title=title)
    return ext[1:]
