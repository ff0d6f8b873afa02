"""2D knot and link diagrams of realized strands (extras ``[knots]`` and ``[render]``).

The closed curves are projected to a PD code (:func:`lkspace.knots.diagram.project`,
the projection ``identify`` uses), the link is simplified with spherogram
(``Link.simplify("global")``, as ``identify`` does) and split into its split pieces;
each piece is laid out by spherogram's orthogonal planar embedding
(``OrthogonalLinkDiagram.plink_data``: grid polylines and which segment crosses over
which, no Tk window) and drawn with rounded corners on a matplotlib ``Figure``: the under
strand is cut at every crossing, each component has its colour, and unknotted split
components are drawn as circles beside.  The drawing therefore has exactly as many
crossings as the simplified diagram that ``identify`` reports.
"""

from __future__ import annotations

import random
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import GeometryError, require
from ..geometry.realization import Realization
from .render import Look, new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

GRID = 10.0
"""Grid spacing of spherogram's orthogonal layout (its coordinates are multiples of it)."""


@dataclass(frozen=True)
class PlanarDiagram:
    """A drawn diagram: per component a polyline with NaN rows at the gaps.

    Attributes
    ----------
    paths : list of (n, 2) float64
        One path per drawn component (closed; NaN rows break the line at under-crossings).
    n_crossings : int
        Crossings drawn (those of the simplified diagram).
    n_components : int
        Components, including unknotted split ones (drawn as circles).
    """

    paths: list[np.ndarray]
    n_crossings: int
    n_components: int


def simplified_pieces(real: Realization) -> tuple[list[Any], int]:
    """Return the split pieces of the simplified link of ``real`` (spherogram links) and the free unknots."""
    if not bool(np.all(real.closed)) or real.scaffold.periodic:
        raise GeometryError(
            f"{real.scaffold.name}: a knot diagram needs closed strands of a finite scaffold "
            "(open or periodic strands are not a link)",
            usage=True,
            parameter="diagram",
        )
    spherogram = require("spherogram", "knots", "knot diagrams")
    from ..knots.diagram import project

    diagram = project(real.curves, seed=0)
    if not diagram.pd:
        return [], len(real.curves)
    free = len(real.curves) - len(spherogram.Link(diagram.pd).link_components)
    link = reduced_link(spherogram, diagram.pd)
    pieces = link.split_link_diagram()
    free += link.unlinked_unknot_components
    return [p for p in pieces if len(p.crossings)], free + sum(1 for p in pieces if not len(p.crossings))


SEEDS, ROUNDS, SEARCHED = 12, 3, 30
"""The reduction's search: seeds, rounds of random moves after simplifying, and most crossings searched."""


def reduced_link(spherogram: Any, pd: list[list[int]]) -> Any:
    """Return the link of ``pd`` simplified to the fewest crossings found.

    ``simplify("global")`` alone often stops above the crossing number (8 crossings for
    the Borromean rings); from each of :data:`SEEDS` seeds of Python's ``random`` (put
    back afterwards), :data:`ROUNDS` rounds of ``backtrack(10)`` then
    ``simplify("global")`` follow, and the fewest crossings seen are kept.  Diagrams past
    :data:`SEARCHED` crossings after the first simplification are simplified once.  The
    search is a heuristic (spherogram's moves also follow its objects' hash order), so it
    may stop above the crossing number; the diagram is always of the same link.
    """
    state = random.getstate()
    try:

        def run(seed: int, rounds: int) -> tuple[Any, list[int]]:
            random.seed(seed)
            link = spherogram.Link(pd)
            link.simplify("global")
            counts = [len(link.crossings)]
            for _ in range(rounds):
                link.backtrack(10)
                link.simplify("global")
                counts.append(len(link.crossings))
            return link, counts

        first, counts = run(0, 0)
        if counts[0] > SEARCHED:
            return first
        found = [(n, rounds, seed) for seed in range(SEEDS) for rounds, n in enumerate(run(seed, ROUNDS)[1])]
        _, rounds, seed = min(found)
        return run(seed, rounds)[0]
    finally:
        random.setstate(state)


def piece_paths(link: Any, corner: float = 0.3 * GRID, gap: float = 0.22 * GRID) -> list[np.ndarray]:
    """Lay out one connected link diagram; return one path per component (NaN at gaps)."""
    from spherogram.links.orthogonal import OrthogonalLinkDiagram

    vertices, arrows, crossings = OrthogonalLinkDiagram(link).plink_data()
    pts = np.array(vertices, np.float64)
    pts[:, 1] *= -1  # screen y runs down
    arrows = [tuple(a) for a in arrows]
    cuts: dict[int, list[np.ndarray]] = {}
    for over, under, *_ in crossings:
        p, q = pts[arrows[under][0]], pts[arrows[under][1]]
        r, s = pts[arrows[over][0]], pts[arrows[over][1]]
        d1, d2 = q - p, s - r
        den = d1[0] * d2[1] - d1[1] * d2[0]
        if abs(den) < 1e-12:
            continue
        u = ((r[0] - p[0]) * d2[1] - (r[1] - p[1]) * d2[0]) / den
        cuts.setdefault(under, []).append(p + u * d1)
    start_of = {a[0]: k for k, a in enumerate(arrows)}
    seen: set[int] = set()
    paths = []
    for k0 in range(len(arrows)):
        if k0 in seen:
            continue
        chain = [k0]
        seen.add(k0)
        while True:
            k = start_of.get(arrows[chain[-1]][1])
            if k is None or k in seen:
                break
            chain.append(k)
            seen.add(k)
        paths.append(component_path(pts, [arrows[k] for k in chain], [cuts.get(k, []) for k in chain], corner, gap))
    return paths


def component_path(
    pts: np.ndarray, arrows: list[tuple[int, int]], cuts: list[list[np.ndarray]], corner: float, gap: float
) -> np.ndarray:
    """One closed component: straight runs with gaps, quadratic corners of radius ``corner``."""
    out: list[np.ndarray] = []
    nan = np.full((1, 2), np.nan)
    n = len(arrows)
    for i, ((a, b), marks) in enumerate(zip(arrows, cuts, strict=True)):
        p, q = pts[a], pts[b]
        length = float(np.linalg.norm(q - p))
        d = (q - p) / max(length, 1e-12)
        r = min(corner, 0.45 * length)
        start, end = p + r * d, q - r * d
        along = sorted(float((m - p) @ d) for m in marks)
        run = [start]
        for s in along:
            run += [p + (s - gap) * d, nan[0], p + (s + gap) * d]
        run.append(end)
        out.append(np.array(run))
        a2, b2 = arrows[(i + 1) % n]
        nxt = pts[b2] - pts[a2]
        nlen = float(np.linalg.norm(nxt))
        r2 = min(corner, 0.45 * nlen)
        c_end = q + r2 * nxt / max(nlen, 1e-12)
        t = np.linspace(0, 1, 7)[1:-1, None]
        out.append((1 - t) ** 2 * end + 2 * t * (1 - t) * q + t**2 * c_end)
    path = np.vstack(out)
    return np.vstack([path, path[:1]])


def planar_diagram(real: Realization) -> PlanarDiagram:
    """Lay out the simplified diagram of ``real``: pieces side by side, free unknots as circles."""
    pieces, free = simplified_pieces(real)
    paths: list[np.ndarray] = []
    x0 = 0.0
    crossings = 0
    for link in pieces:
        comp = piece_paths(link)
        stack = np.vstack([c[np.isfinite(c[:, 0])] for c in comp])
        lo, hi = stack.min(0), stack.max(0)
        shift = np.array([x0 - lo[0], -0.5 * (lo[1] + hi[1])])
        paths += [c + shift for c in comp]
        x0 += (hi[0] - lo[0]) + 2 * GRID
        crossings += len(link.crossings)
    t = np.linspace(0, 2 * np.pi, 73)
    for _ in range(free):
        paths.append(np.column_stack([x0 + 1.5 * GRID + 1.5 * GRID * np.cos(t), 1.5 * GRID * np.sin(t)]))
        x0 += 4 * GRID
    return PlanarDiagram(paths, crossings, len(paths))


def draw_diagram(real: Realization, look: Look | None = None, title: str | None = None) -> Figure:
    """Draw :func:`planar_diagram` on a new Figure (a colour per component)."""
    look = look or Look()
    drawn = planar_diagram(real)
    fig = new_figure(look)
    ax = fig.add_axes((0.04, 0.04, 0.92, 0.88 if title else 0.92))
    ax.set_axis_off()
    if look.transparent:
        ax.patch.set_alpha(0.0)
    palette = look.colors(max(drawn.n_components, 1))
    width = max(1.5, 3.5 * min(look.width, look.height) / 480)
    for path, rgb in zip(drawn.paths, palette, strict=False):
        ax.plot(path[:, 0], path[:, 1], color=tuple(rgb), linewidth=width, solid_capstyle="butt")
    ax.set_aspect("equal")
    ax.margins(0.06)
    if title:
        fig.suptitle(title, fontsize=12)
    return fig
