"""``.png`` strands: a matplotlib (Agg) picture (extra ``[render]``).

Shaded tubes with a colour per strand and the scaffold drawn faintly behind.
"""

from __future__ import annotations

import os

import numpy as np

from ..errors import require
from ..geometry.realization import Realization
from ..io.atomic import atomic_path
from .colors import colors
from .tubes import tube_meshes


def write(
    real: Realization,
    path: str | os.PathLike[str],
    *,
    show_mesh: bool = True,
    radius: float | None = None,
    size: int = 900,
    elev: float | None = None,
    azim: float = -58.0,
    title: str | None = None,
    **ignored: object,
) -> None:
    """Draw a shaded picture of the tubes (one colour per strand), the input mesh faint behind.

    Lattice translates of one strand (a periodic block) share its colour.

    ``elev`` defaults to 24 degrees, or 55 for a flat scaffold seen from above.
    """
    require("matplotlib", "render", "PNG export")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    radius = real.tube_radius if radius is None else radius
    pts = np.vstack(real.curves)
    extent = np.ptp(pts, axis=0)
    if elev is None:
        elev = 55.0 if extent[2] < 0.25 * extent.max() else 24.0
    fig = plt.figure(figsize=(size / 100, size / 100), dpi=100)
    ax = fig.add_subplot(projection="3d", computed_zorder=False)
    ax.view_init(elev=elev, azim=azim)
    e, a = np.radians(elev), np.radians(azim)
    view = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
    light = view + np.array([0.3, -0.2, 0.6])
    light /= np.linalg.norm(light)
    sc = real.scaffold
    if show_mesh:
        base = [sc.corner_positions[s:t] for s, t in zip(sc.face_starts[:-1], sc.face_starts[1:], strict=True)]
        shifts = (
            sc.lattice.translate(real.translations)
            if sc.lattice is not None and real.translations is not None
            else np.zeros((1, 3))
        )
        polys = [p + d for d in shifts for p in base]
        ax.add_collection3d(
            Poly3DCollection(
                polys, facecolors=(0.6, 0.65, 0.75, 0.07), edgecolors=(0.35, 0.35, 0.4, 0.35), linewidths=0.6
            )
        )
    spacing = 1.2 * radius
    all_tris, all_cols = [], []
    palette = colors(int(real.strand_of.max()) + 1)[real.strand_of]  # translates share their strand's colour
    for (v, nrm, f), rgb in zip(tube_meshes(real, radius, 10, spacing), palette, strict=True):
        fn = nrm[f].mean(axis=1)
        fn /= np.maximum(np.linalg.norm(fn, axis=1, keepdims=True), 1e-12)
        lam = np.clip(fn @ light, 0, 1)
        spec = np.clip(fn @ ((light + view) / np.linalg.norm(light + view)), 0, 1) ** 24
        shade = np.clip(rgb[None] * (0.35 + 0.65 * lam[:, None]) + 0.35 * spec[:, None], 0, 1)
        facing = fn @ view > -0.2
        all_tris.append(v[f[facing]])
        all_cols.append(shade[facing])
    tris = np.concatenate(all_tris)
    cols = np.concatenate(all_cols)
    depth = tris.mean(axis=1) @ view
    order = np.argsort(depth)  # far first: painter's algorithm
    ax.add_collection3d(Poly3DCollection(tris[order], facecolors=cols[order], edgecolors=cols[order], linewidths=0.25))
    lo, hi = pts.min(0) - 2 * radius, pts.max(0) + 2 * radius
    center, half = (lo + hi) / 2, (hi - lo).max() / 2
    ax.set_xlim(center[0] - half, center[0] + half)
    ax.set_ylim(center[1] - half, center[1] + half)
    ax.set_zlim(center[2] - half, center[2] + half)
    ax.set_box_aspect((1, 1, 1), zoom=1.3)
    ax.set_axis_off()
    if title:
        ax.set_title(title, fontsize=13)
    fig.subplots_adjust(0, 0, 1, 1)
    with atomic_path(path, suffix=".png") as tmp:
        fig.savefig(tmp, format="png", dpi=100)
    plt.close(fig)
