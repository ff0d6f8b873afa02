"""``.stl`` solids: binary STL of closed tube meshes, one shell per printable piece.

STL has no units and no objects: the 80-byte header says ``units=mm`` (or the
``units`` given) and the pieces are disjoint closed shells (a slicer or
``trimesh.Trimesh.split`` separates them).  Triangles are written with float32
coordinates and their unit normals, all at once with a numpy structured array.
"""

from __future__ import annotations

import os

import numpy as np

from ..geometry.fabrication import Printable
from ..io.atomic import atomic_path
from .tubes import merged, tube

STL_TRIANGLE = np.dtype([("normal", "<f4", 3), ("vertices", "<f4", (3, 3)), ("attribute", "<u2")])
"""One binary STL record: normal, three corners, a 16-bit attribute (0)."""


def print_meshes(pieces: Printable, sides: int) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """One closed tube per piece (flat caps on open pieces)."""
    return [tube(c, bool(cl), pieces.radius, sides) for c, cl in zip(pieces.curves, pieces.closed, strict=True)]


def stl_bytes(pieces: Printable, sides: int = 16, name: str = "lkspace") -> bytes:
    """Return the binary STL of the pieces' tubes."""
    verts, faces, _ = merged(print_meshes(pieces, sides))
    tri = verts[faces]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normal /= np.maximum(np.linalg.norm(normal, axis=1, keepdims=True), 1e-300)
    records = np.zeros(len(faces), STL_TRIANGLE)
    records["normal"] = normal
    records["vertices"] = tri
    header = f"lkspace {name} units={pieces.units} pieces={len(pieces.curves)}".encode()[:80].ljust(80, b" ")
    return header + np.uint32(len(faces)).tobytes() + records.tobytes()


def write(
    real: object,
    path: str | os.PathLike[str],
    *,
    pieces: Printable | None = None,
    sides: int = 16,
    **ignored: object,
) -> None:
    """Write the printable ``pieces`` (made by the registry) to ``path`` atomically."""
    assert pieces is not None, "the registry passes the printable pieces"
    name = getattr(getattr(real, "scaffold", None), "name", "lkspace")
    with atomic_path(path) as tmp, open(tmp, "wb") as fh:
        fh.write(stl_bytes(pieces, sides, name))
