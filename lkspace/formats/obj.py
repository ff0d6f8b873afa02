"""``.obj`` strands: one object per strand, polylines (``l``) or tube meshes."""

from __future__ import annotations

import os

from ..geometry.realization import Realization
from ..io.atomic import write_text
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
    """Write polylines (``l``) or tube meshes to ``path``, one ``o strand_k`` object per curve."""
    lines = [f"# lkspace strands of {real.scaffold.name}: {real.n_curves} curve(s)"]
    base = 1
    if tubes:
        for k, (v, _, f) in enumerate(tube_meshes(real, radius, sides)):
            lines.append(f"o strand_{k}")
            lines.extend(f"v {x:.6f} {y:.6f} {z:.6f}" for x, y, z in v)
            lines.extend(f"f {a + base} {b + base} {c + base}" for a, b, c in f)
            base += len(v)
    else:
        for k, (curve, closed) in enumerate(zip(real.curves, real.closed, strict=False)):
            lines.append(f"o strand_{k}")
            lines.extend(f"v {x:.6f} {y:.6f} {z:.6f}" for x, y, z in curve)
            idx = list(range(base, base + len(curve))) + ([base] if closed else [])
            lines.append("l " + " ".join(map(str, idx)))
            base += len(curve)
    write_text(path, "\n".join(lines) + "\n")
