"""Export: one writer per file type behind a registry, chosen by the output's extension.

======  =======================================================================
``.obj``  one object per strand: polylines (``l``) or, with ``tubes=True``, tube meshes
``.ply``  ASCII PLY with a colour per strand: polylines as ``edge``, tubes as ``face``
``.glb``  glTF 2.0 binary: one tube mesh, node and material per strand
``.png``  a matplotlib picture: shaded tubes, the scaffold drawn faintly (``[render]``)
======  =======================================================================

Each format is a module of :mod:`lkspace.formats` with a ``write(real, path, **options)``
function, imported only when used.  The output path is checked before any work
(:func:`lkspace.io.paths.output_file`: an existing folder, not a device, an extension of
:data:`FORMATS`); every file is written to a temporary name and renamed when complete,
replacing the file a symlink points to.  Tubes are bounded by :data:`MAX_TUBE_VERTICES`.
"""

from __future__ import annotations

import importlib
import math
import os

from numpy.typing import ArrayLike

from ..errors import ExportError, TooLargeError
from ..geometry.limits import MAX_POINTS, MAX_RELATIVE
from ..geometry.realization import GeometryParams, Realization, realize
from ..io.paths import output_file
from ..io.sources import ScaffoldSource
from ..progress import task

WRITERS = {".obj": "obj", ".ply": "ply", ".glb": "glb", ".png": "png"}
"""Extension -> module of :mod:`lkspace.formats` whose ``write`` writes it."""
FORMATS = tuple(WRITERS)

TUBE_SIDES = 12
"""Vertices around a tube's circle (the writers' default ``sides``)."""

MAX_TUBE_VERTICES = 6_000_000
"""Most tube vertices an export writes (curve points times :data:`TUBE_SIDES`).

A vertex is about 60 bytes of ``.obj``/``.ply`` text or 24 of ``.glb``, and the tube frames
are built point by point: past this bound a file runs into gigabytes and minutes.
"""


def output_target(path: str | os.PathLike[str]) -> str:
    """Check the output ``path`` before any work; return the file to write (a symlink resolved).

    The extension picks the format (one of :data:`FORMATS`); the checks of
    :func:`lkspace.io.paths.output_file` follow (folder exists and is writable, not a
    device, a folder or a FIFO).
    """
    text = os.fspath(path)
    ext = os.path.splitext(text)[1].lower()
    if text.strip() and ext not in WRITERS:
        raise ExportError(
            f"{text}: unknown output format {ext or '(no extension)'!r}; the extension picks one of {', '.join(FORMATS)}"
        )
    return output_file(text, FORMATS)


def point_budget(path: str | os.PathLike[str], tubes: bool) -> tuple[int, str]:
    """Most curve points worth realizing for an export to ``path``, and the bound's name.

    Tubes (``tubes``, ``.glb``, ``.png``) allow :data:`MAX_TUBE_VERTICES` / :data:`TUBE_SIDES`.
    """
    ext = os.path.splitext(os.fspath(path))[1].lower()
    if tubes or ext in (".glb", ".png"):
        return min(
            MAX_POINTS, MAX_TUBE_VERTICES // TUBE_SIDES
        ), "MAX_TUBE_VERTICES / 12 for tubes; polylines allow more"
    return MAX_POINTS, "MAX_POINTS"


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
    if radius is not None and not (math.isfinite(radius) and radius > 0):
        raise ExportError(f"tube radius must be a finite number > 0, got {radius}")
    target = output_target(path)  # checked before any work: extension, folder, device
    ext = os.path.splitext(os.fspath(path))[1].lower()
    with task(f"export {os.path.basename(os.fspath(path))}") as step:
        if not isinstance(design, Realization):
            step.note("realizing")
        budget, bound = point_budget(path, tubes)
        if not isinstance(design, Realization):
            design = realize(design, labels, nulls, params, max_points=budget, bound=bound)
        real = design
        if radius is not None and radius > MAX_RELATIVE * real.scale:
            raise ExportError(f"tube radius {radius:g} exceeds {MAX_RELATIVE:g} x the shortest edge ({real.scale:.4g})")
        points = sum(len(c) for c in real.curves)
        if budget < MAX_POINTS and points * TUBE_SIDES > MAX_TUBE_VERTICES:
            raise TooLargeError(
                f"{path}: tubes of {points:,} curve points need {points * TUBE_SIDES:,} vertices "
                f"> {MAX_TUBE_VERTICES:,} (MAX_TUBE_VERTICES); write polylines (.obj or .ply without --tubes)"
            )
        step.note(f"writing {points:,} points")
        writer = importlib.import_module(f"{__package__}.{WRITERS[ext]}")
        writer.write(real, target, tubes=tubes, radius=radius, show_mesh=show_mesh, title=title)
    return ext[1:]
