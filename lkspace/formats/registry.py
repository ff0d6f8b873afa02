"""Export: one encoder per file type behind a registry, chosen by the output's extension.

========  =====================================================================
``.obj``  one object per strand: polylines (``l``) or, with ``tubes=True``, tube meshes
``.ply``  binary PLY with a colour per strand: polylines as ``edge``, tubes as ``face``
``.glb``  glTF 2.0 binary: one tube mesh, node and material per strand
``.stl``  binary STL: one closed tube shell per printable piece (``thickness``, ``clearance``)
``.3mf``  3MF package: one coloured mesh object per printable piece, with its ``units``
``.png``  a picture: shaded tubes, the scaffold drawn faintly, or with ``diagram=True``
          a 2D knot/link diagram (``[render]``; diagrams also ``[knots]``)
``.svg``  the same view as line art: paths per strand, cut where a strand passes under
          (:mod:`.lineart`); with ``diagram=True`` the diagram
========  =====================================================================

Each format is a function ``(Realization, options) -> bytes`` (:data:`ENCODERS`, the
``exchange`` pattern of trimesh), imported only when used, with its own options record
(:data:`OPTIONS`, :mod:`lkspace.formats.options`).  :func:`export` checks the output path
before any work (:func:`lkspace.io.paths.output_file`: an existing folder, not a device, an
extension of :data:`FORMATS`), bounds the tubes (:data:`MAX_TUBE_VERTICES`), proves the
clearance, encodes, and writes the bytes once: to a temporary name, renamed when complete,
replacing the file a symlink points to (:func:`lkspace.io.atomic.write_bytes`).  Printable
formats (:data:`PRINTABLE`) get their pieces from :func:`lkspace.geometry.fabrication.printable`.
"""

from __future__ import annotations

import dataclasses
import importlib
import os
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Literal, cast

import numpy as np
from numpy.typing import ArrayLike

from ..errors import ExportError, TooLargeError
from ..geometry.limits import MAX_POINTS, MAX_RELATIVE
from ..geometry.params import GeometryParams, RealizeOptions
from ..geometry.realization import Realization, realize
from ..io.atomic import write_bytes
from ..io.paths import only_extension, output_file
from ..model.scaffold import Scaffold
from ..runtime.progress import Step, task
from .options import TUBE_SIDES, FormatOptions, GlbOptions, MeshOptions, PictureOptions, PrintOptions, TubeOptions

ENCODERS = {
    ".obj": "obj:obj_bytes",
    ".ply": "ply:ply_bytes",
    ".glb": "glb:glb_bytes",
    ".stl": "stl:stl_bytes",
    ".3mf": "threemf:threemf_bytes",
    ".png": "png:png_bytes",
    ".svg": "png:svg_bytes",
}
"""Extension -> ``module:function`` of :mod:`lkspace.formats` encoding it: ``(Realization, options) -> bytes``."""
OPTIONS: dict[str, type[FormatOptions]] = {
    ".obj": MeshOptions,
    ".ply": MeshOptions,
    ".glb": GlbOptions,
    ".stl": PrintOptions,
    ".3mf": PrintOptions,
    ".png": PictureOptions,
    ".svg": PictureOptions,
}
"""Extension -> the options record its encoder takes (:mod:`lkspace.formats.options`)."""
FORMATS = tuple(ENCODERS)
Format = Literal["obj", "ply", "glb", "stl", "3mf", "png", "svg"]
"""A format :func:`export` writes: an extension of :data:`ENCODERS` without its dot."""
PRINTABLE = (".stl", ".3mf")
"""Formats of solid, printable pieces."""
PICTURES = (".png", ".svg")
"""Picture formats (matplotlib; the 3D ``.svg`` is line art written directly)."""

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
    if text.strip() and ext not in ENCODERS:
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


def options_for(ext: str, options: FormatOptions | None) -> FormatOptions:
    """Return ``options``, or the default record of format ``ext``; refuse a record of another format."""
    wanted = OPTIONS[ext]
    if options is None:
        return wanted()
    if type(options) is not wanted:
        takes = ", ".join(f.name for f in dataclasses.fields(wanted))
        raise ExportError(
            f"options: {ext} takes {wanted.__name__} ({takes}), not {type(options).__name__}", parameter="options"
        )
    return options


def encoder(ext: str) -> Callable[[Realization, FormatOptions], bytes]:
    """Return the encoder of format ``ext`` (its module imported now)."""
    module, name = ENCODERS[ext].split(":")
    return cast(
        Callable[[Realization, FormatOptions], bytes], getattr(importlib.import_module(f"{__package__}.{module}"), name)
    )


def check_tubes(real: Realization, path: str | os.PathLike[str], options: FormatOptions) -> None:
    """Refuse tubes that are too thick for the scaffold or have too many vertices to write."""
    radius = options.tube_radius if isinstance(options, TubeOptions) else None
    if isinstance(options, TubeOptions) and radius is not None and radius > MAX_RELATIVE * real.scale:
        raise ExportError(
            f"{options.given}: the tube radius {radius:g} exceeds {MAX_RELATIVE:g} x the shortest edge ({real.scale:.4g})",
            parameter=options.given,
        )
    points = sum(len(c) for c in real.curves)
    sides = options.sides if isinstance(options, (MeshOptions, GlbOptions)) else TUBE_SIDES  # pieces: as ever
    if needs_tubes(path, isinstance(options, MeshOptions) and options.tubes) and points * sides > MAX_TUBE_VERTICES:
        raise TooLargeError(
            f"{path}: tubes of {points:,} curve points need {points * sides:,} vertices "
            f"> {MAX_TUBE_VERTICES:,} (MAX_TUBE_VERTICES); write polylines (.obj or .ply without `tubes`)"
        )
    if isinstance(options, PictureOptions) and not options.diagram:
        check_picture_rings(real, radius if radius is not None else real.tube_radius)


def proved(real: Realization, options: FormatOptions, step: Step) -> FormatOptions:
    """Prove the clearance of the tubes; return ``options`` (printable: holding their pieces)."""
    from ..geometry.fabrication import printable

    if isinstance(options, PrintOptions) and options.pieces is None:
        step.note("checking clearance")
        pieces = printable(real, options.thickness, options.clearance, options.units, options.scale)
        return dataclasses.replace(options, pieces=pieces)
    if isinstance(options, TubeOptions) and options.clearance is not None:
        step.note("checking clearance")
        radius = options.tube_radius if options.tube_radius is not None else real.tube_radius
        printable(real, 2 * radius * options.scale, options.clearance, "mm", options.scale)
    return options


def export(
    design: Realization | Scaffold,
    path: str | os.PathLike[str],
    labels: ArrayLike | None = None,
    nulls: ArrayLike | None = None,
    *,
    params: GeometryParams | None = None,
    options: FormatOptions | None = None,
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
    options : MeshOptions, GlbOptions, PrintOptions or PictureOptions, optional
        The record of the format (:data:`OPTIONS`; default: its defaults); a record of
        another format is refused (:mod:`lkspace.formats.options`).

    Returns
    -------
    {"obj", "ply", "glb", "stl", "3mf", "png", "svg"}
        The format written (:data:`Format`).

    Examples
    --------
    >>> import tempfile, os
    >>> import lkspace
    >>> from lkspace.formats.options import PrintOptions
    >>> export(lkspace.load("tetrahedron"), os.path.join(tempfile.mkdtemp(), "t.obj"), 1)
    'obj'
    >>> stl = os.path.join(tempfile.mkdtemp(), "t.stl")
    >>> lkspace.export("tetrahedron", stl, 1, options=PrintOptions(thickness=0.1, clearance=0.05))
    'stl'
    """
    target = output_target(path)  # checked before any work: extension, folder, device, not the input
    ext = os.path.splitext(os.fspath(path))[1].lower()
    options = options_for(ext, options)
    with task(f"export {os.path.basename(os.fspath(path))}") as step:
        if not isinstance(design, Realization):
            step.note("realizing")
            with point_budget(path, isinstance(options, MeshOptions) and options.tubes) as max_points:
                design = realize(design, labels, nulls, params, options=RealizeOptions(max_points=max_points))
        check_tubes(design, path, options)
        options = proved(design, options, step)
        step.note(f"writing {sum(len(c) for c in design.curves):,} points")
        write_bytes(target, encoder(ext)(design, options))
    return cast(Format, ext[1:])  # an extension of ENCODERS: output_target checked it
