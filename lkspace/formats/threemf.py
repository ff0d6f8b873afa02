"""``.3mf`` solids: a 3MF package (zip + XML) with one coloured mesh object per piece.

Written directly: ``[Content_Types].xml``, ``_rels/.rels`` and ``3D/3dmodel.model`` with
``<model unit="millimeter">`` (or the ``units`` given), one ``<basematerials>`` colour
per colour drawn (the pictures' colours: :func:`.colors.curve_colors`), one ``<object type="model">`` per printable piece and a ``<build>`` item for
each.  Coordinates are written with 7 significant digits.
"""

from __future__ import annotations

import io
import zipfile
from xml.sax.saxutils import escape

import numpy as np

from ..geometry.fabrication import UNITS, Printable
from ..geometry.realization import Realization
from .colors import curve_colors
from .options import PrintOptions
from .stl import pieces_of, print_meshes

CONTENT_TYPES = (
    '<?xml version="1.0" encoding="UTF-8"?>\n'
    '<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
    '<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>'
    '<Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>'
    "</Types>"
)
RELS = (
    '<?xml version="1.0" encoding="UTF-8"?>\n'
    '<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
    '<Relationship Target="/3D/3dmodel.model" Id="rel0" '
    'Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>'
    "</Relationships>"
)


def model_xml(pieces: Printable, name: str, sides: int, colours: np.ndarray) -> str:
    """Return the ``3D/3dmodel.model`` document: ``colours (n_pieces, 3)`` in ``[0, 1]``, one base material each distinct."""
    rgb, index = np.unique((np.asarray(colours).reshape(-1, 3) * 255).round().astype(int), axis=0, return_inverse=True)
    index = index.reshape(-1)
    parts = [
        '<?xml version="1.0" encoding="UTF-8"?>\n',
        f'<model unit="{UNITS[pieces.units][0]}" xml:lang="en-US" '
        'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">',
        f'<metadata name="Title">{escape(name)}</metadata>',
        '<metadata name="Application">lkspace</metadata>',
        "<resources>",
        '<basematerials id="1">',
    ]
    parts += [f'<base name="colour {k}" displaycolor="#{r:02X}{g:02X}{b:02X}"/>' for k, (r, g, b) in enumerate(rgb)]
    parts.append("</basematerials>")
    for k, (v, _, f) in enumerate(print_meshes(pieces, sides)):
        parts.append(f'<object id="{k + 2}" type="model" name="piece {k}" pid="1" pindex="{int(index[k])}">')
        parts.append("<mesh><vertices>")
        parts.append(vertex_text(v))
        parts.append("</vertices><triangles>")
        parts.append(triangle_text(f))
        parts.append("</triangles></mesh></object>")
    parts.append("</resources><build>")
    parts += [f'<item objectid="{k + 2}"/>' for k in range(len(pieces.curves))]
    parts.append("</build></model>")
    return "".join(parts)


def vertex_text(v: np.ndarray) -> str:
    """``<vertex x= y= z=/>`` elements of ``v`` (n, 3)."""
    return "".join(['<vertex x="{:.7g}" y="{:.7g}" z="{:.7g}"/>'.format(*r) for r in v.tolist()])


def triangle_text(f: np.ndarray) -> str:
    """``<triangle v1= v2= v3=/>`` elements of ``f`` (m, 3)."""
    return "".join(['<triangle v1="{}" v2="{}" v3="{}"/>'.format(*r) for r in f.tolist()])


def threemf_bytes(real: Realization, options: PrintOptions) -> bytes:
    """Return the 3MF package (zip) of the printable pieces, titled with the scaffold's name."""
    pieces = pieces_of(real, options)
    return pieces_3mf(pieces, real.scaffold.name, options.sides, curve_colors(real)[pieces.first])


def pieces_3mf(pieces: Printable, name: str, sides: int, colours: np.ndarray) -> bytes:
    """Return the 3MF package (zip) of ``pieces``, coloured ``colours (n_pieces, 3)``."""
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED, compresslevel=1) as zf:
        zf.writestr("[Content_Types].xml", CONTENT_TYPES)
        zf.writestr("_rels/.rels", RELS)
        zf.writestr("3D/3dmodel.model", model_xml(pieces, name, sides, colours))
    return buf.getvalue()
