"""``.3mf`` solids: a 3MF package (zip + XML) with one coloured mesh object per piece.

Written directly: ``[Content_Types].xml``, ``_rels/.rels`` and ``3D/3dmodel.model`` with
``<model unit="millimeter">`` (or the ``units`` given), one ``<basematerials>`` colour
per strand, one ``<object type="model">`` per printable piece and a ``<build>`` item for
each.  Coordinates are written with 7 significant digits.
"""

from __future__ import annotations

import io
import zipfile
from xml.sax.saxutils import escape

import numpy as np

from ..geometry.fabrication import UNITS, Printable
from ..geometry.realization import Realization
from .colors import colors
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


def model_xml(pieces: Printable, name: str, sides: int) -> str:
    """Return the ``3D/3dmodel.model`` document."""
    n_strands = int(pieces.strand_of.max()) + 1 if len(pieces.strand_of) else 1
    rgb = (colors(n_strands) * 255).round().astype(int)
    parts = [
        '<?xml version="1.0" encoding="UTF-8"?>\n',
        f'<model unit="{UNITS[pieces.units][0]}" xml:lang="en-US" '
        'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">',
        f'<metadata name="Title">{escape(name)}</metadata>',
        '<metadata name="Application">lkspace</metadata>',
        "<resources>",
        '<basematerials id="1">',
    ]
    parts += [f'<base name="strand {k}" displaycolor="#{r:02X}{g:02X}{b:02X}"/>' for k, (r, g, b) in enumerate(rgb)]
    parts.append("</basematerials>")
    for k, (v, _, f) in enumerate(print_meshes(pieces, sides)):
        parts.append(f'<object id="{k + 2}" type="model" name="piece {k}" pid="1" pindex="{int(pieces.strand_of[k])}">')
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
    return pieces_3mf(pieces_of(real, options), real.scaffold.name, options.sides)


def pieces_3mf(pieces: Printable, name: str, sides: int) -> bytes:
    """Return the 3MF package (zip) of ``pieces``."""
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED, compresslevel=1) as zf:
        zf.writestr("[Content_Types].xml", CONTENT_TYPES)
        zf.writestr("_rels/.rels", RELS)
        zf.writestr("3D/3dmodel.model", model_xml(pieces, name, sides))
    return buf.getvalue()
