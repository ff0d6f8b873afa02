"""``.png`` and ``.svg`` pictures: a 3D render, or with ``diagram=True`` a 2D knot diagram.

The render is :mod:`~lkspace.formats.render`, the diagram :mod:`~lkspace.formats.diagram`
(extra ``[render]``, diagrams also ``[knots]``).

Both are drawn on a matplotlib ``Figure`` with its own canvas: the caller's pyplot state
and backend are left alone.
"""

from __future__ import annotations

import os

from ..geometry.realization import Realization
from ..io.atomic import atomic_path
from .render import Look, render


def write(
    real: Realization,
    path: str | os.PathLike[str],
    *,
    show_mesh: bool = True,
    radius: float | None = None,
    title: str | None = None,
    look: Look | None = None,
    diagram: bool = False,
    size: int | None = None,
    elev: float | None = None,
    azim: float | None = None,
    **ignored: object,
) -> None:
    """Draw the picture and save it atomically; the format follows the extension (``.png``, ``.svg``).

    ``size`` (pixels, square), ``elev`` and ``azim`` are the older spelling of ``look``
    and are still honoured when ``look`` is not given.
    """
    if look is None:
        side = 900 if size is None else int(size)
        look = Look(
            azim=azim if azim is not None else (None if elev is None else -58.0), elev=elev, width=side, height=side
        )
    if diagram:
        from .diagram import draw_diagram

        fig = draw_diagram(real, look, title=title)
    else:
        fig = render(real, look, show_mesh=show_mesh, radius=radius, title=title)
    fmt = os.path.splitext(os.fspath(path))[1].lower().lstrip(".")
    with atomic_path(path, suffix="." + fmt) as tmp:
        fig.savefig(tmp, format=fmt, dpi=100, transparent=look.transparent)
