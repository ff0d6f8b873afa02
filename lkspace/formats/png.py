"""``.png`` and ``.svg`` pictures: a 3D render, or with ``diagram=True`` a 2D knot diagram.

The render is :mod:`~lkspace.formats.render` (as ``.svg``, the line art of
:mod:`~lkspace.formats.lineart`), the diagram :mod:`~lkspace.formats.diagram` (extra
``[render]``, diagrams also ``[knots]``).

Both are drawn on a matplotlib ``Figure`` with its own canvas: the caller's pyplot state
and backend are left alone.
"""

from __future__ import annotations

import io
from typing import Literal

from ..geometry.realization import Realization
from .options import PictureOptions
from .render import render


def picture_bytes(real: Realization, options: PictureOptions, fmt: Literal["png", "svg"]) -> bytes:
    """Draw the picture of ``options`` and return it encoded as ``fmt``."""
    look = options.look
    if options.diagram:
        from .diagram import draw_diagram

        fig = draw_diagram(real, look, title=options.title)
    else:
        fig = render(real, look, show_mesh=options.show_mesh, radius=options.tube_radius, title=options.title)
    buffer = io.BytesIO()
    fig.savefig(buffer, format=fmt, dpi=100, transparent=look.transparent)
    return buffer.getvalue()


def png_bytes(real: Realization, options: PictureOptions) -> bytes:
    """Return the picture as PNG."""
    return picture_bytes(real, options, "png")


def svg_bytes(real: Realization, options: PictureOptions) -> bytes:
    """Return the picture as SVG: the diagram drawn by matplotlib, the 3D picture as line art (:mod:`.lineart`)."""
    if options.diagram:
        return picture_bytes(real, options, "svg")
    from .lineart import svg_lineart

    return svg_lineart(real, options)
