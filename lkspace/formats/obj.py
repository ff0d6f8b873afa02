"""``.obj`` strands: one object per strand, polylines (``l``) or tube meshes (``f``).

A polyline is one ``l`` element listing its vertices in order (a closed strand repeats
its first vertex at the end), as the OBJ specification defines polylines.  Lines are formatted from
plain lists (``ndarray.tolist``), not numpy scalars; the text is UTF-8 with ``\\n`` line ends.
"""

from __future__ import annotations

import numpy as np

from ..geometry.realization import Realization
from ..words import plural
from .options import MeshOptions
from .tubes import tube_meshes


def vertex_lines(v: np.ndarray) -> str:
    """``v x y z`` lines of ``v`` (n, 3)."""
    if not len(v):
        return ""
    return "".join(["v {:.6f} {:.6f} {:.6f}\n".format(*r) for r in v.tolist()])


def face_lines(f: np.ndarray) -> str:
    """``f a b c`` lines (1-based indices already added)."""
    if not len(f):
        return ""
    return "".join(["f {} {} {}\n".format(*r) for r in f.tolist()])


def obj_bytes(real: Realization, options: MeshOptions) -> bytes:
    """Return polylines (``l``) or tube meshes, one ``o strand_k`` object per curve, as OBJ text.

    In a block, curve ``k`` of thread class ``s`` (a strand of the quotient) is ``o thread_s_k``.
    """
    out = [f"# lkspace strands of {real.scaffold.name}: {plural(real.n_curves, 'curve')}\n"]
    if options.units:
        out.append(f"# units {options.units}\n")
    base = 1
    names = (
        [f"strand_{k}" for k in range(real.n_curves)]
        if real.block is None
        else [f"thread_{s}_{k}" for k, s in enumerate(real.strand_of.tolist())]
    )
    if options.tubes:
        for k, (v, _, f) in enumerate(tube_meshes(real, options.tube_radius, options.sides)):
            out += [f"o {names[k]}\n", vertex_lines(v), face_lines(f + base)]
            base += len(v)
    else:
        for k, (curve, closed) in enumerate(zip(real.curves, real.closed, strict=False)):
            idx = np.arange(base, base + len(curve))
            if closed:
                idx = np.append(idx, base)
            out += [f"o {names[k]}\n", vertex_lines(curve), "l " + " ".join(idx.astype(str).tolist()) + "\n"]
            base += len(curve)
    return "".join(out).encode("utf-8")
