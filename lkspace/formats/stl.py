"""``.stl`` solids: binary STL of closed tube meshes, one shell per printable piece.

STL has no units and no objects: the 80-byte header says ``units=mm`` (or the
``units`` given) and the pieces are disjoint closed shells (a slicer or
``trimesh.Trimesh.split`` separates them).  Triangles are written with float32
coordinates and their unit normals, all at once with a numpy structured array.
"""

from __future__ import annotations

import numpy as np

from ..geometry.fabrication import Printable, printable
from ..geometry.realization import Realization
from .options import PrintOptions
from .tubes import merged, tube

STL_TRIANGLE = np.dtype([("normal", "<f4", 3), ("vertices", "<f4", (3, 3)), ("attribute", "<u2")])
"""One binary STL record: normal, three corners, a 16-bit attribute (0)."""


def print_meshes(pieces: Printable, sides: int) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """One closed tube per piece (flat caps on open pieces)."""
    return [tube(c, bool(cl), pieces.radius, sides) for c, cl in zip(pieces.curves, pieces.closed, strict=True)]


def pieces_of(real: Realization, options: PrintOptions) -> Printable:
    """Return the pieces of ``options`` (``pieces``), else made from ``real`` and checked now."""
    if options.pieces is not None:
        return options.pieces
    return printable(real, options.thickness, options.clearance, options.units, options.scale)


def stl_bytes(real: Realization, options: PrintOptions) -> bytes:
    """Return the binary STL of the printable pieces' tubes (header: the scaffold, units, pieces)."""
    return pieces_stl(pieces_of(real, options), options.sides, real.scaffold.name)


def pieces_stl(pieces: Printable, sides: int, name: str) -> bytes:
    """Return the binary STL of the tubes of ``pieces``, ``name`` in its header."""
    verts, faces, _ = merged(print_meshes(pieces, sides))
    tri = verts[faces]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normal /= np.maximum(np.linalg.norm(normal, axis=1, keepdims=True), 1e-300)
    records = np.zeros(len(faces), STL_TRIANGLE)
    records["normal"] = normal
    records["vertices"] = tri
    header = f"lkspace {name} units={pieces.units} pieces={len(pieces.curves)}".encode()[:80].ljust(80, b" ")
    return header + np.uint32(len(faces)).tobytes() + records.tobytes()
