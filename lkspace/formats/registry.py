"""Export: one writer per file type behind a registry, chosen by the output's extension.

========  =====================================================================
``.obj``  one object per strand: polylines (``l``) or, with ``tubes=True``, tube meshes
``.ply``  binary PLY with a colour per strand: polylines as ``edge``, tubes as ``face``
``.glb``  glTF 2.0 binary: one tube mesh, node and material per strand
``.stl``  binary STL: one closed tube shell per printable piece (``thickness``, ``clearance``)
``.3mf``  3MF package: one coloured mesh object per printable piece, with its ``units``
``.png``  a picture: shaded tubes, the scaffold drawn faintly, or with ``diagram=True``
          a 2D knot/link diagram (``[render]``; diagrams also ``[knots]``)
``.svg``  the same picture as vector graphics
========  =====================================================================

Each format is a module of :mod:`lkspace.formats` with a ``write(real, path, **options)``
function, imported only when used.  The output path is checked before any work
(:func:`lkspace.io.paths.output_file`: an existing folder, not a device, an extension of
:data:`FORMATS`); every file is written to a temporary name and renamed when complete,
replacing the file a symlink points to.  Tubes are bounded by :data:`MAX_TUBE_VERTICES`.
Printable formats (:data:`PRINTABLE`) get their pieces from
:func:`lkspace.geometry.fabrication.printable`, which proves the clearance first.
"""

from __future__ import annotations

import importlib
import math
import os
from collections.abc import Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any, Literal, cast

import numpy as np
from numpy.typing import ArrayLike

from ..errors import ExportError, TooLargeError
from ..geometry.limits import MAX_POINTS, MAX_RELATIVE
from ..geometry.params import GeometryParams, RealizeOptions
from ..geometry.realization import Realization, realize
from ..io.paths import only_extension, output_file
from ..model.scaffold import Scaffold
from ..progress import task

if TYPE_CHECKING:
    from ..geometry.fabrication import Printable
    from .render import Look

WRITERS = {
    ".obj": "obj",
    ".ply": "ply",
    ".glb": "glb",
    ".stl": "stl",
    ".3mf": "threemf",
    ".png": "png",
    ".svg": "png",
}
"""Extension -> module of :mod:`lkspace.formats` whose ``write`` writes it."""
FORMATS = tuple(WRITERS)
Format = Literal["obj", "ply", "glb", "stl", "3mf", "png", "svg"]
"""A format :func:`export` writes: an extension of :data:`WRITERS` without its dot."""
PRINTABLE = (".stl", ".3mf")
"""Formats of solid, printable pieces."""
PICTURES = (".png", ".svg")
"""Formats drawn with matplotlib."""

TUBE_SIDES = 12
"""Vertices around a tube's circle (the writers' default ``sides``)."""

MAX_TUBE_VERTICES = 6_000_000
"""Most tube vertices an export writes (curve points times :data:`TUBE_SIDES`).

A vertex is about 60 bytes of ``.obj`` text or 15-24 bytes of binary: past this bound a
file runs into gigabytes and minutes.
"""


def output_target(path: str | os.PathLike[str], inputs: tuple[str | None, ...] = ()) -> str:
    """Check the output ``path`` before any work; return the file to write (a symlink resolved).

    The extension picks the format (one of :data:`FORMATS`); the checks of
    :func:`lkspace.io.paths.output_file` follow (folder exists and is writable, not a
    device, a folder or a FIFO, not one of ``inputs``, not a name that is only an extension).
    """
    text = os.fspath(path)
    only_extension(text, FORMATS)
    ext = os.path.splitext(text)[1].lower()
    if text.strip() and ext not in WRITERS:
        raise ExportError(
            f"{text}: unknown output format {ext or '(no extension)'!r}; the extension picks one of {', '.join(FORMATS)}"
        )
    return output_file(text, FORMATS, inputs)


def needs_tubes(path: str | os.PathLike[str], tubes: bool) -> bool:
    """Whether an export to ``path`` writes tubes: ``tubes``, or ``.glb``, printable formats and pictures."""
    return tubes or os.path.splitext(os.fspath(path))[1].lower() in (".glb", *PRINTABLE, *PICTURES)


@contextmanager
def point_budget(path: str | os.PathLike[str], tubes: bool) -> Iterator[int]:
    """Yield the most curve points worth realizing for an export to ``path`` (``max_points`` of ``realize``).

    Polylines allow :data:`MAX_POINTS`, tubes (:func:`needs_tubes`) :data:`MAX_TUBE_VERTICES` /
    :data:`TUBE_SIDES`.  A refusal past the tubes' bound (an error about ``max_points``,
    raised inside the ``with`` block) is raised again naming that bound; past
    :data:`MAX_POINTS` it stays as it is (the command line shows ``max_points`` as its bound).
    """
    if not needs_tubes(path, tubes):
        yield MAX_POINTS
        return
    try:
        yield min(MAX_POINTS, MAX_TUBE_VERTICES // TUBE_SIDES)
    except TooLargeError as exc:
        message = str(exc)
        if exc.parameter != "max_points" or not message.startswith("max_points"):
            raise
        bound = f"MAX_TUBE_VERTICES / {TUBE_SIDES} for tubes (polylines allow more)"
        raise TooLargeError(bound + message[len("max_points") :]) from None


PICTURE_RING_SPACING = 1.2
"""A 3D picture's tubes get a ring of vertices every 1.2 tube radii along the curves (:mod:`.render`)."""


def check_picture_rings(real: Realization, radius: float) -> None:
    """Refuse a picture whose tubes, a ring every 1.2 ``radius``, would pass :data:`MAX_TUBE_VERTICES`.

    A tiny tube radius on long curves means rings beyond count; refused before drawing.
    """
    length = sum(float(np.linalg.norm(np.diff(c, axis=0), axis=1).sum()) for c in real.curves)
    rings = length / (PICTURE_RING_SPACING * radius) + len(real.curves)
    if rings * TUBE_SIDES > MAX_TUBE_VERTICES:
        raise TooLargeError(
            f"tubes of radius {radius:.3g} along {length:.4g} of curves need about {rings * TUBE_SIDES:.3g} "
            f"vertices > {MAX_TUBE_VERTICES:,} (MAX_TUBE_VERTICES); use a larger tube radius or thickness"
        )


def export(
    design: Realization | Scaffold,
    path: str | os.PathLike[str],
    labels: ArrayLike | None = None,
    nulls: ArrayLike | None = None,
    *,
    params: GeometryParams | None = None,
    tubes: bool = False,
    radius: float | None = None,
    show_mesh: bool = True,
    title: str | None = None,
    thickness: float | None = None,
    clearance: float | None = None,
    units: str | None = None,
    scale: float = 1.0,
    look: Look | None = None,
    diagram: bool = False,
    pieces: Printable | None = None,
) -> Format:
    """Write a design's strands to ``path``; the format follows the extension.

    Parameters
    ----------
    design : Realization or Scaffold
        Realized strands, or a scaffold realized here with ``labels``, ``nulls`` and
        ``params`` (see :func:`lkspace.realize`); ``lkspace.export`` also takes a path or
        a built-in name (:func:`lkspace.load`).
    path : str or os.PathLike
        ``.obj``, ``.ply``, ``.glb``, ``.stl``, ``.3mf``, ``.png`` or ``.svg``.
    tubes : bool
        Tube meshes instead of polylines (``.obj``, ``.ply``; the other formats are always tubes).
    radius : float, optional
        Tube radius in scaffold units (default: the realization's).
    show_mesh, title
        Pictures only: draw the scaffold faintly; a title.
    thickness, clearance : float, optional
        Tube diameter and the least surface gap between distinct pieces, in output
        units (``.stl``, ``.3mf``; see :func:`lkspace.geometry.fabrication.printable`).
        ``thickness`` also sets the tube of the other formats (``radius = thickness / 2 / scale``);
        ``clearance`` given with a tube format is checked there too.
    units : str, optional
        What one output unit is (``mm``, ``cm``, ``m``, ``in``, ``ft``, ``um``): the 3MF
        ``unit`` and the STL header (default ``mm``), a PLY/OBJ comment (none by default).
    scale : float
        Output units per scaffold unit (printable formats).
    look : Look, optional
        Pictures: view, size, background and colours (:func:`lkspace.formats.render.look_of`).
    diagram : bool
        Pictures: draw the 2D knot/link diagram instead of the 3D render.
    pieces : Printable, optional
        Printable formats: pieces already made by :func:`~lkspace.geometry.fabrication.printable`.

    Returns
    -------
    {"obj", "ply", "glb", "stl", "3mf", "png", "svg"}
        The format written (:data:`Format`).

    Examples
    --------
    >>> import tempfile, os
    >>> import lkspace
    >>> export(lkspace.load("tetrahedron"), os.path.join(tempfile.mkdtemp(), "t.obj"), 1)
    'obj'
    >>> lkspace.export("tetrahedron", os.path.join(tempfile.mkdtemp(), "t.stl"), 1, thickness=0.1, clearance=0.05)
    'stl'
    """
    if radius is not None and not (math.isfinite(radius) and radius > 0):
        raise ExportError(f"radius: the tube radius must be a finite number > 0, got {radius}", parameter="radius")
    from ..geometry.fabrication import check_options

    check_options(thickness, clearance, units or "mm", scale)
    target = output_target(path)  # checked before any work: extension, folder, device, not the input
    ext = os.path.splitext(os.fspath(path))[1].lower()
    if diagram and ext not in PICTURES:
        raise ExportError(
            f"diagram: a diagram is drawn as {' or '.join(PICTURES)}, not {ext} ({path})", parameter="diagram"
        )
    if ext in PICTURES:
        from .render import check_title

        check_title(title)
    with task(f"export {os.path.basename(os.fspath(path))}") as step:
        if not isinstance(design, Realization):
            step.note("realizing")
            with point_budget(path, tubes) as max_points:
                design = realize(design, labels, nulls, params, options=RealizeOptions(max_points=max_points))
        real = design
        given = "radius" if radius is not None else "thickness"  # the parameter that sets the tube
        if radius is None and thickness is not None and ext not in PRINTABLE:
            radius = thickness / 2 / scale
        if radius is not None and radius > MAX_RELATIVE * real.scale:
            raise ExportError(
                f"{given}: the tube radius {radius:g} exceeds {MAX_RELATIVE:g} x the shortest edge ({real.scale:.4g})",
                parameter=given,
            )
        points = sum(len(c) for c in real.curves)
        if needs_tubes(path, tubes) and points * TUBE_SIDES > MAX_TUBE_VERTICES:
            raise TooLargeError(
                f"{path}: tubes of {points:,} curve points need {points * TUBE_SIDES:,} vertices "
                f"> {MAX_TUBE_VERTICES:,} (MAX_TUBE_VERTICES); write polylines (.obj or .ply without `tubes`)"
            )
        if ext in PICTURES and not diagram:
            check_picture_rings(real, radius if radius is not None else real.tube_radius)
        if (pieces is None and ext in PRINTABLE) or (clearance is not None and (tubes or ext == ".glb")):
            from ..geometry.fabrication import printable

            step.note("checking clearance")
            if ext in PRINTABLE and pieces is None:
                pieces = printable(real, thickness, clearance, units or "mm", scale)
            elif ext not in PRINTABLE:
                tube = 2 * (radius if radius is not None else real.tube_radius) * scale
                printable(real, tube, clearance, units or "mm", scale)
        step.note(f"writing {points:,} points")
        writer = importlib.import_module(f"{__package__}.{WRITERS[ext]}")
        options: dict[str, Any] = {"tubes": tubes, "radius": radius, "show_mesh": show_mesh, "title": title}
        options.update(pieces=pieces, units=units, look=look, diagram=diagram)
        writer.write(real, target, **options)
    return cast(Format, ext[1:])  # an extension of WRITERS: output_target checked it
