"""``.ply`` strands: ASCII PLY with a colour per strand, polylines as ``edge`` or tubes as ``face``."""

from __future__ import annotations

import os

import numpy as np

from ..geometry.realization import Realization
from ..io.atomic import write_text
from .colors import colors
from .tubes import tube_meshes


def write(
    real: Realization,
    path: str | os.PathLike[str],
    *,
    tubes: bool = False,
    radius: float | None = None,
    sides: int = 12,
    **ignored: object,
) -> None:
    """Write ASCII PLY to ``path``, vertex colours per strand: ``edge`` polylines or tube ``face`` triangles."""
    cols = (colors(real.n_curves) * 255).round().astype(int)
    verts, vcols, elems = [], [], []
    base = 0
    if tubes:
        for k, (v, _, f) in enumerate(tube_meshes(real, radius, sides)):
            verts.append(v)
            vcols.append(np.repeat(cols[k][None], len(v), 0))
            elems.append(f + base)
            base += len(v)
    else:
        for k, (curve, closed) in enumerate(zip(real.curves, real.closed, strict=False)):
            n = len(curve)
            verts.append(curve)
            vcols.append(np.repeat(cols[k][None], n, 0))
            a = np.arange(n if closed else n - 1)
            elems.append(np.column_stack([a, (a + 1) % n]) + base)
            base += n
    v = np.vstack(verts)
    c = np.vstack(vcols)
    e = np.vstack(elems)
    kind = "face" if tubes else "edge"
    header = [
        "ply",
        "format ascii 1.0",
        f"comment lkspace strands of {real.scaffold.name}",
        f"element vertex {len(v)}",
        "property float x",
        "property float y",
        "property float z",
        "property uchar red",
        "property uchar green",
        "property uchar blue",
        f"element {kind} {len(e)}",
    ]
    header += ["property list uchar int vertex_indices"] if tubes else ["property int vertex1", "property int vertex2"]
    header.append("end_header")
    body = [f"{x:.6f} {y:.6f} {z:.6f} {r} {g} {b}" for (x, y, z), (r, g, b) in zip(v, c, strict=False)]
    body += [("3 " if tubes else "") + " ".join(map(str, row)) for row in e]
    write_text(path, "\n".join(header + body) + "\n")
