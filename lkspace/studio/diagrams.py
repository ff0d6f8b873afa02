"""The knot beside the curve: a 2D diagram of a design's strands, and catalog thumbnails.

The realized curves are seen along the page's view (its camera's right, up and back
axes) or, without one, along the seeded generic rotation ``identify`` uses; they are
projected to the plane and drawn as an SVG.  Crossings are found as ``identify`` finds
them (:func:`lkspace.knots.diagram.near_pairs` and
:func:`~lkspace.knots.diagram.transverse`: the segment nearer the viewer is over), and
each one cuts the under strand with a gap.  Every path carries ``data-strand`` (the strand
index); the page colours it as the 3D view colours that strand.  For closed strands (up to
:data:`MAX_PD_CROSSINGS`) the PD code of the same projection
(:func:`lkspace.knots.diagram.project`) and its linking matrix come along.

This is the raw projection, with as many crossings as the curves show from that side:
it is cheap enough (milliseconds) to follow every edit.  Asked ``simplified``, the
diagram is the one ``lkspace export --diagram`` draws instead (:func:`simplified_of`:
the link simplified by spherogram and laid out on its grid, as the tables draw a knot,
one ink for every component), whatever the view.  Thumbnails
draw the same projection, small and without gaps, of the construction polylines (no
smoothing: about a millisecond a design), cached per scaffold and labels.
"""

from __future__ import annotations

import threading
import time
from collections import OrderedDict
from collections.abc import Sequence
from typing import TypeAlias

import numpy as np
from scipy.spatial.transform import Rotation

from .. import GeometryParams, Realization, RealizeOptions, Scaffold, realize
from ..errors import DiagramError, GeometryError, TooLargeError, UsageError
from ..knots.diagram import near_pairs, project, transverse
from ..linktypes.common_names import common_name
from .answers import DiagramView, Thumbs
from .designs import Cache, design, labels_from_page
from .requests import ThumbnailsRequest, View

SIZE = 360.0
"""Longer side of a diagram's viewBox (SVG user units)."""

THUMB_SIZE = 64.0
"""Longer side of a thumbnail's viewBox."""

MAX_DIAGRAM_POINTS = 300_000
"""Most curve points drawn as a diagram."""

MAX_THUMB_POINTS = 50_000
"""Most curve points of a design drawn as a thumbnail (past it: an empty box)."""

MAX_PD_CROSSINGS = 2_000
"""Most crossings of a diagram sent with its PD code and linking matrix."""

MAX_CROSSINGS_DRAWN = 20_000
"""Most crossings drawn with gaps (past it the diagram is refused: it would be a tangle of ink)."""


def rotation_of(view: View) -> np.ndarray:
    """Return the rotation (rows: right, up, towards the viewer) of the page's ``view`` ``(right, up, back)``."""
    right, _, back = (np.array(v, np.float64) for v in view)
    if np.linalg.norm(np.cross(right, back)) <= 1e-9 * np.linalg.norm(right) * np.linalg.norm(back):
        raise UsageError("view: right and back must be non-zero and not parallel")
    back = back / np.linalg.norm(back)
    right = right - (right @ back) * back
    right /= np.linalg.norm(right)
    return np.array([right, np.cross(back, right), back])


def crossings(curves: Sequence[np.ndarray], closed: Sequence[bool]) -> Crossings:
    """Return the crossings, seen along ``z``, of polylines ``curves`` (closed or open).

    Returns ``(over, under, t_over, t_under, owner, index)``: the segments and where along
    them (as :func:`~lkspace.knots.diagram.transverse`), then the curve and position of
    every segment.  Raises :class:`~lkspace.errors.DiagramError` for a non-generic view.
    """
    starts, ends, owner, index = [], [], [], []
    for c, (pts, shut) in enumerate(zip(curves, closed, strict=True)):
        nxt = np.roll(pts, -1, axis=0) if shut else pts[1:]
        starts.append(pts[: len(nxt)])
        ends.append(nxt)
        owner.append(np.full(len(nxt), c))
        index.append(np.arange(len(nxt)))
    p0, p1 = np.vstack(starts), np.vstack(ends)
    own, at = np.concatenate(owner), np.concatenate(index)
    i, j = near_pairs(p0, p1)
    n_own = np.array([len(s) for s in starts])[own[i]]
    shut_own = np.asarray(closed, bool)[own[i]]
    gap = np.abs(at[i] - at[j])
    adjacent = (own[i] == own[j]) & ((gap == 1) | (shut_own & (gap == n_own - 1)))
    over, under, t_over, t_under, _ = transverse(p0, p1, i[~adjacent], j[~adjacent])
    return over, under, t_over, t_under, own, at


Crossings: TypeAlias = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]
"""``(over, under, t_over, t_under, owner, index)`` of :func:`crossings`."""


def seen(
    curves: Sequence[np.ndarray], closed: Sequence[bool], rotation: np.ndarray
) -> tuple[list[np.ndarray], Crossings]:
    """Rotate ``curves`` by ``rotation`` and find their crossings; a non-generic view is nudged (three tries)."""
    for attempt in range(3):
        rot = rotation if attempt == 0 else Rotation.from_rotvec([1e-3 * attempt, 7e-4, 0]).as_matrix() @ rotation
        turned = [np.asarray(c, np.float64) @ rot.T for c in curves]
        try:
            return turned, crossings(turned, closed)
        except DiagramError:
            if attempt == 2:
                raise
    raise AssertionError("unreachable")  # pragma: no cover


def runs(arc: np.ndarray, closed: bool, cuts: list[float], gap: float) -> list[tuple[float, float]]:
    """Arc-length intervals of a curve to draw (``arc``: cumulative length, closed back to the start if ``closed``)."""
    length = float(arc[-1])
    if not cuts:
        return [(0.0, length)]
    holes = sorted((s - gap, s + gap) for s in cuts)
    if closed:  # start after the first gap, go once around
        start = holes[0][1]
        holes = sorted(holes + [(a + length, b + length) for a, b in holes])
        lo, hi = start, start + length
    else:
        lo, hi = 0.0, length
    out, pos = [], lo
    for a, b in holes:
        if b <= pos:
            continue
        if a > pos:
            out.append((pos, min(a, hi)))
        pos = max(pos, b)
        if pos >= hi:
            break
    if pos < hi:
        out.append((pos, hi))
    return [(a, b) for a, b in out if b > a]


def path_data(points: np.ndarray, closed: bool, cuts: list[float], gap: float, step: float) -> str:
    """SVG path ``d`` of a projected polyline ``(n, 2)`` with gaps at arc positions ``cuts``."""
    pts = np.vstack([points, points[:1]]) if closed else points
    arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    if closed:  # twice around, so an interval may run past the start
        pts = np.vstack([pts, pts[1:]])
        arc = np.concatenate([arc, arc[1:] + arc[-1]])
    parts = []
    whole = not cuts and closed
    for a, b in runs(arc[: len(arc) // 2 + 1] if closed else arc, closed, cuts, gap):
        keep = np.arange(np.searchsorted(arc, a, "right"), np.searchsorted(arc, b, "left"))
        keep = keep[np.concatenate([[True], np.diff(np.floor(arc[keep] / step)) > 0])] if len(keep) else keep
        ends = [np.array([np.interp(s, arc, pts[:, 0]), np.interp(s, arc, pts[:, 1])]) for s in (a, b)]
        run = np.vstack([ends[0], pts[keep], ends[1]])
        text = " ".join(f"{x:.1f},{y:.1f}" for x, y in run)
        parts.append(f"M{text}{'Z' if whole else ''}")
    return "".join(parts)


def to_screen(flat: list[np.ndarray], size: float, margin: float) -> tuple[list[np.ndarray], float, float, float]:
    """Fit the ``xy`` of ``flat`` into a ``size`` box (SVG's ``y`` runs down); return the points, width, height, scale."""
    xy = np.vstack([c[:, :2] for c in flat])
    lo, hi = xy.min(0), xy.max(0)
    scale = (size - 2 * margin) / max(float((hi - lo).max()), 1e-12)
    out = [np.column_stack([margin + (c[:, 0] - lo[0]) * scale, margin + (hi[1] - c[:, 1]) * scale]) for c in flat]
    return out, float((hi - lo)[0] * scale + 2 * margin), float((hi - lo)[1] * scale + 2 * margin), scale


def svg(paths: list[str], strands: Sequence[int], width: float, height: float, stroke: float, cls: str) -> str:
    """Return an SVG of ``paths`` (one per curve, ``data-strand`` its strand; grey until the page colours it)."""
    body = "".join(f'<path data-strand="{k}" d="{d}"/>' for k, d in zip(strands, paths, strict=True) if d)
    return (
        f'<svg xmlns="http://www.w3.org/2000/svg" class="{cls}" viewBox="0 0 {width:.1f} {height:.1f}">'
        f'<g fill="none" stroke="#555" stroke-width="{stroke:g}" stroke-linecap="round" stroke-linejoin="round">'
        f"{body}</g></svg>"
    )


def check_points(real: Realization) -> None:
    """Refuse a design whose curves have more than :data:`MAX_DIAGRAM_POINTS` points to project."""
    n_points = sum(len(c) for c in real.curves)
    if n_points > MAX_DIAGRAM_POINTS:
        raise TooLargeError(f"diagram: {n_points:,} curve points > {MAX_DIAGRAM_POINTS:,}; use smaller twists")


def diagram_of(real: Realization, view: View | None = None) -> DiagramView:
    """Return the diagram of ``real`` (a finite scaffold's) seen along ``view`` (or the generic rotation): SVG, crossings, PD code."""
    t0 = time.perf_counter()
    if not real.curves:
        return {"svg": None, "message": "no strands to draw"}
    check_points(real)
    closed = [bool(c) for c in real.closed]
    rot = Rotation.random(random_state=0).as_matrix() if view is None else rotation_of(view)
    turned, (over, under, t_over, t_under, own, at) = seen(real.curves, closed, rot)
    if len(over) > MAX_CROSSINGS_DRAWN:
        raise TooLargeError(f"diagram: {len(over):,} crossings > {MAX_CROSSINGS_DRAWN:,}; use smaller twists")
    flat, width, height, scale = to_screen(turned, SIZE, 12.0)
    steps = [np.linalg.norm(np.diff(np.vstack([p, p[:1]]), axis=0), axis=1) for p in flat]
    starts = [np.concatenate([[0.0], np.cumsum(s)]) for s in steps]
    cuts: list[list[float]] = [[] for _ in flat]
    for seg, t in zip(under.tolist(), t_under.tolist(), strict=True):
        c, k = int(own[seg]), int(at[seg])
        cuts[c].append(float(starts[c][k] + t * steps[c][k]))
    stroke = 2.4
    paths = [path_data(p, shut, cut, 2.6 * stroke, 0.8) for p, shut, cut in zip(flat, closed, cuts, strict=True)]
    out: DiagramView = {
        "svg": svg(paths, real.strand_of.tolist(), width, height, stroke, "knot-diagram"),
        "crossings": int(len(over)),
        "components": len(real.curves),
        "view": "generic" if view is None else "page",
        "pd": None,
        "linking_matrix": None,
    }
    if all(closed) and 0 < len(over) <= MAX_PD_CROSSINGS:
        drawn = project(turned, rotation=np.eye(3))
        out["pd"], out["linking_matrix"] = drawn.pd, drawn.linking_matrix().tolist()
        out["writhe"] = int(drawn.signs.sum())
    out["seconds"] = round(time.perf_counter() - t0, 4)
    return out


def simplified_of(real: Realization) -> DiagramView:
    """Return the simplified diagram of ``real`` (:func:`lkspace.formats.diagram.planar_diagram`): SVG and crossings.

    Paths carry ``data-component`` (no strand: simplification renumbers the components).
    """
    from ..formats.diagram import planar_diagram

    t0 = time.perf_counter()
    if not real.curves:
        return {"svg": None, "message": "no strands to draw"}
    check_points(real)
    if not all(real.closed):
        return {"svg": None, "message": "simplified diagram: only closed strands make a knot or link"}
    if len(project(real.curves, seed=0).pd) > MAX_PD_CROSSINGS:
        raise TooLargeError(f"simplified diagram: over {MAX_PD_CROSSINGS:,} crossings to simplify; use smaller twists")
    drawn = planar_diagram(real)
    finite = np.vstack([p[np.isfinite(p[:, 0])] for p in drawn.paths])
    lo, hi = finite.min(0), finite.max(0)
    margin, scale = 12.0, (SIZE - 24.0) / max(float((hi - lo).max()), 1e-12)
    body = []
    for i, path in enumerate(drawn.paths):
        screen = np.column_stack([margin + (path[:, 0] - lo[0]) * scale, margin + (hi[1] - path[:, 1]) * scale])
        pieces = [p[np.isfinite(p[:, 0])] for p in np.split(screen, np.flatnonzero(~np.isfinite(screen[:, 0])))]
        d = "".join("M" + " ".join(f"{x:.1f},{y:.1f}" for x, y in p) for p in pieces if len(p) > 1)  # NaN: a gap
        body.append(f'<path data-component="{i}" d="{d}"/>')
    width, height = (hi - lo) * scale + 2 * margin
    return {
        "svg": (
            f'<svg xmlns="http://www.w3.org/2000/svg" class="knot-diagram simplified" viewBox="0 0 {width:.1f} {height:.1f}">'
            f'<g fill="none" stroke="#222" stroke-width="2.4" stroke-linecap="round" stroke-linejoin="round">'
            f"{''.join(body)}</g></svg>"
        ),
        "crossings": drawn.n_crossings,
        "components": drawn.n_components,
        "view": "simplified",
        "seconds": round(time.perf_counter() - t0, 4),
    }


def diagram(
    scaffold: Scaffold,
    key: str,
    labels: np.ndarray,
    nulls: np.ndarray | None,
    cache: Cache,
    view: View | None,
    simplified: bool = False,
) -> DiagramView:
    """Return the diagram of a design, from the realization its redraw kept (realized now if it was not)."""
    if scaffold.periodic:
        return {"svg": None, "message": "periodic: an infinite structure has no knot diagram"}
    real = cache.get(Cache.key(key, labels, nulls, None))
    if real is None:
        drawn = design(scaffold, labels, nulls, None, cache, key)
        if "failure" in drawn:
            return {"svg": None, "message": f"no diagram: {drawn['failure']['message']}"}
        real = cache.get(Cache.key(key, labels, nulls, None))
        if real is None:
            return {"svg": None, "message": "no diagram: the design has no geometry"}
    return simplified_of(real) if simplified else diagram_of(real, view)


def thumbnail(scaffold: Scaffold, labels: np.ndarray) -> str:
    """Return a tiny SVG of a design's construction polylines seen along the generic rotation (no gaps)."""
    options = RealizeOptions(embedding="later", max_points=MAX_THUMB_POINTS)
    real = realize(scaffold, labels, None, GeometryParams(smooth=False), options=options)
    rot = Rotation.random(random_state=0).as_matrix()
    flat, width, height, _ = to_screen([np.asarray(c) @ rot.T for c in real.curves], THUMB_SIZE, 3.0)
    paths = [path_data(p, bool(shut), [], 0.0, 0.7) for p, shut in zip(flat, real.closed, strict=True)]
    return svg(paths, real.strand_of.tolist(), width, height, 1.6, "knot-thumb")


class Thumbnails:
    """Thumbnails of designs, kept per scaffold and labels (the last :attr:`size`)."""

    def __init__(self, size: int = 2000) -> None:
        self._items: OrderedDict[bytes, str] = OrderedDict()
        self._size = size
        self._lock = threading.Lock()

    def get(self, scaffold: Scaffold, key: str, labels: np.ndarray) -> str:
        """Return the thumbnail of ``labels`` on ``scaffold`` (drawn once; an unrealizable one is an empty box)."""
        cache_key = key.encode() + b"|" + labels.tobytes()
        with self._lock:
            found = self._items.get(cache_key)
        if found is not None:
            return found
        try:
            drawn = thumbnail(scaffold, labels)
        except (GeometryError, TooLargeError):
            drawn = svg([], [], THUMB_SIZE, THUMB_SIZE, 1.0, "knot-thumb")
        with self._lock:
            self._items[cache_key] = drawn
            while len(self._items) > self._size:
                self._items.popitem(last=False)
        return drawn

    def answer(self, scaffold: Scaffold, key: str, request: ThumbnailsRequest) -> Thumbs:
        """Thumbnails of the request's designs (label lists) and the common names of its table names."""
        if scaffold.periodic:
            raise UsageError(f"{scaffold.name}: periodic scaffolds have no thumbnails")
        thumbs = tuple(self.get(scaffold, key, labels_from_page(scaffold, d)) for d in request.designs)
        return Thumbs(thumbs, tuple(common_name(n) if n else None for n in request.names))
