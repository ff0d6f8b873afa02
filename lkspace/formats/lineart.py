"""``.svg`` of a 3D picture as line art: each strand a group of paths, broken where it passes under.

The view and frame are the PNG's (:mod:`.view`: orthographic, framed on the strands).  Each
curve is resampled every :data:`STEP` pixels of the picture and projected; wherever two
pieces cross in the projection (:func:`crossings`), the one farther from the eye is cut
for a short gap around the crossing point and the nearer runs on, as a knot diagram is
drawn: the gap is where the over strand covers the under one, plus a margin of
:data:`GAP` strokes each side, its ends cut square.  The stroke is the tube's diameter
in pixels; the scaffold (a block's cells and frame) is drawn faintly behind.  Colours are the PNG's (:func:`.render.strand_colors`),
or with ``gradient`` hues along each strand in :data:`BANDS` bands.

Document: ``<svg>`` with a background ``<rect>`` (unless transparent), ``<g
class="scaffold">``, then one ``<g class="strand" data-strand="K">`` per curve (K its
strand of the trace), far to near, each holding its pieces as ``<path>`` elements
(``M`` absolute, then relative ``l`` steps, coordinates to 0.1 pixel), and an optional
``<text class="title">``.
"""

from __future__ import annotations

from collections.abc import Callable
from xml.sax.saxutils import escape

import numpy as np

from ..geometry.clearance import resample
from ..geometry.realization import Realization
from .colors import arc_colors
from .options import PictureOptions
from .render import scaffold_polygons, strand_colors
from .view import TITLE_HEIGHT, direction, frame, pixels_per_unit, screen_axes, view_angles

STEP = 1.5
"""Pixels between the resampled points of a curve."""
GAP = 0.3
"""White margin each side of the over strand in a gap, in stroke widths (ends are cut square: butt caps)."""
MIN_SINE = 0.35
"""Smallest sine of a crossing angle used for its gap: the over strand covers 0.5 / sine stroke widths of the under one."""
BANDS = 48
"""Colour bands along a strand with ``gradient``."""


def hex_color(rgb: np.ndarray) -> str:
    """``#rrggbb`` of an RGB triple in ``[0, 1]``."""
    r, g, b = (int(round(float(np.clip(c, 0, 1)) * 255)) for c in rgb)
    return f"#{r:02x}{g:02x}{b:02x}"


def path_data(xy: np.ndarray, closed: bool = False) -> str:
    """SVG path data of a polyline ``(n, 2)`` in pixels: ``M`` then relative ``l`` steps (0.1 pixel)."""
    q = np.round(np.asarray(xy) * 10).astype(np.int64)
    q = q[np.concatenate([[True], np.any(np.diff(q, axis=0) != 0, axis=1)])]
    steps = np.diff(q, axis=0)
    head = f"M{q[0, 0] / 10:g} {q[0, 1] / 10:g}"
    body = " ".join(f"{dx / 10:g} {dy / 10:g}" for dx, dy in steps.tolist())
    return head + (f"l{body}" if body else "") + ("z" if closed else "")


def crossings(
    xy: list[np.ndarray], depth: list[np.ndarray], closed: np.ndarray, exclude: float
) -> list[tuple[int, float, float]]:
    """Under-crossings of projected polylines: ``(curve, position along it in pixels, sine of the angle)``.

    ``xy[k]`` are the pixels of curve ``k``'s points, ``depth[k]`` their depth (larger is
    nearer).  Two segments cross when their interiors meet; segments of one curve
    closer than ``exclude`` pixels along it are not compared (a bend is not a crossing).
    Each crossing is reported once, on the curve farther from the eye.
    """
    from scipy.spatial import cKDTree

    a, b, za, zb, owner, start, arc = [], [], [], [], [], [], []
    for k, (p, z) in enumerate(zip(xy, depth, strict=True)):
        q, w = (np.vstack([p, p[:1]]), np.concatenate([z, z[:1]])) if closed[k] else (p, z)
        seg = np.linalg.norm(np.diff(q, axis=0), axis=1)
        a.append(q[:-1])
        b.append(q[1:])
        za.append(w[:-1])
        zb.append(w[1:])
        owner.append(np.full(len(seg), k))
        start.append(np.concatenate([[0.0], np.cumsum(seg)[:-1]]))
        arc.append(np.full(len(seg), seg.sum()))
    pa, pb, qa, qb = np.vstack(a), np.vstack(b), np.concatenate(za), np.concatenate(zb)
    own, s0, total = np.concatenate(owner), np.concatenate(start), np.concatenate(arc)
    d = pb - pa
    reach = float(np.linalg.norm(d, axis=1).max()) if len(d) else 0.0
    pairs = cKDTree((pa + pb) / 2).query_pairs(reach * 1.01, output_type="ndarray")
    if not len(pairs):
        return []
    i, j = pairs[:, 0], pairs[:, 1]
    along = np.abs(s0[i] - s0[j])
    along = np.where(closed[own[i]], np.minimum(along, total[i] - along), along)
    keep = (own[i] != own[j]) | (along > exclude)
    i, j = i[keep], j[keep]
    cross = d[i, 0] * d[j, 1] - d[i, 1] * d[j, 0]
    safe = np.where(np.abs(cross) > 1e-12, cross, 1.0)
    r = pa[j] - pa[i]
    u = (r[:, 0] * d[j, 1] - r[:, 1] * d[j, 0]) / safe
    v = (r[:, 0] * d[i, 1] - r[:, 1] * d[i, 0]) / safe
    hit = (np.abs(cross) > 1e-12) & (u >= 0) & (u < 1) & (v >= 0) & (v < 1)
    i, j, u, v, cross = i[hit], j[hit], u[hit], v[hit], cross[hit]
    zi = qa[i] + u * (qb[i] - qa[i])
    zj = qa[j] + v * (qb[j] - qa[j])
    sine = np.abs(cross) / np.maximum(np.linalg.norm(d[i], axis=1) * np.linalg.norm(d[j], axis=1), 1e-12)
    seg_len = np.linalg.norm(d, axis=1)
    under = np.where(zi < zj, i, j)
    t = np.where(zi < zj, u, v)
    return [(int(own[g]), float(s0[g] + tt * seg_len[g]), float(sn)) for g, tt, sn in zip(under, t, sine, strict=True)]


def pieces(length: float, closed: bool, gaps: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """Arc intervals ``(start, end)`` of a curve of ``length`` left when the ``gaps`` are cut out.

    A closed curve's intervals may run past ``length`` (they wrap around); with no gap it is
    one interval ``(0, length)``.
    """
    if not gaps:
        return [(0.0, length)]
    spans = sorted(gaps)
    if closed:
        spans = (
            [(lo - length, hi - length) for lo, hi in spans] + spans + [(lo + length, hi + length) for lo, hi in spans]
        )
    merged: list[list[float]] = []
    for lo, hi in sorted(spans):
        if merged and lo <= merged[-1][1]:
            merged[-1][1] = max(merged[-1][1], hi)
        else:
            merged.append([lo, hi])
    if closed:
        first = next(m for m in merged if m[1] >= 0)  # the gap covering or following position 0
        base = first[1]
        out = [(m0[1], m1[0]) for m0, m1 in zip(merged, merged[1:], strict=False) if base <= m0[1] < base + length]
        return [(lo, hi) for lo, hi in out if hi > lo] or []
    edges = [(-np.inf, 0.0), *[(lo, hi) for lo, hi in merged], (length, np.inf)]
    out = [(max(e0[1], 0.0), min(e1[0], length)) for e0, e1 in zip(edges, edges[1:], strict=False)]
    return [(lo, hi) for lo, hi in out if hi > lo]


def unrolled(xy: np.ndarray, closed: bool) -> tuple[np.ndarray, np.ndarray]:
    """``(points, arc positions)`` of a polyline, a closed one run round three times (for :func:`cut`)."""
    q = np.vstack([xy, xy, xy, xy[:1]]) if closed else xy
    return q, np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(q, axis=0), axis=1))])


def cut(q: np.ndarray, s: np.ndarray, lo: float, hi: float) -> np.ndarray:
    """Return the polyline ``q`` (arc positions ``s``, :func:`unrolled`) between arc positions ``lo`` and ``hi``."""
    a, b = np.searchsorted(s, lo, side="right"), np.searchsorted(s, hi, side="left")
    ends = [np.column_stack([np.interp([x], s, q[:, 0]), np.interp([x], s, q[:, 1])]) for x in (lo, hi)]
    return np.vstack([ends[0], q[a:b], ends[1]])


def svg_lineart(real: Realization, options: PictureOptions) -> bytes:
    """Return the picture of ``options`` as SVG line art (module docstring)."""
    look = options.look
    radius = options.tube_radius if options.tube_radius is not None else real.tube_radius
    width, height = look.width, look.height
    top = TITLE_HEIGHT if options.title else 0
    azim, elev = view_angles(real, look, radius)
    view = direction(azim, elev)
    right, up = screen_axes(view)
    pts = np.vstack(real.curves) if real.curves else np.zeros((1, 3))
    (cx, cy), half = frame(pts, view, radius)
    scale = pixels_per_unit(half, width, height - top)

    def pixels(p: np.ndarray) -> np.ndarray:
        return np.column_stack([(p @ right - cx) * scale + width / 2, top + (height - top) / 2 - (p @ up - cy) * scale])

    stroke = 2 * radius * scale
    out = [
        '<?xml version="1.0" encoding="utf-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}">',
    ]
    if not look.transparent:
        out.append(f'<rect width="100%" height="100%" fill="{hex_color(np.array(look_rgb(look.background)))}"/>')
    if options.show_mesh:
        out.append(scaffold_group(real, pixels))
    curves = [resample(c, bool(cl), STEP / scale) for c, cl in zip(real.curves, real.closed, strict=True)]
    xy = [pixels(c.points) for c in curves]
    depth = [c.points @ view for c in curves]
    gaps: list[list[tuple[float, float]]] = [[] for _ in curves]
    for k, at, sine in crossings(xy, depth, real.closed, 3 * stroke) if curves else []:
        h = (0.5 / max(sine, MIN_SINE) + GAP) * stroke
        gaps[k].append((at - h, at + h))
    colors = strand_colors(real, look)
    copies = real.translations if real.translations is not None and len(real.translations) > 1 else None
    for k in np.argsort([float(z.mean()) for z in depth], kind="stable"):
        closed = bool(real.closed[k])
        q, s = unrolled(xy[k], closed)
        length = float(s[len(xy[k])] if closed else s[-1])
        spans = pieces(length, closed, gaps[k])
        whole = closed and not look.gradient and spans == [(0.0, length)]  # one closed path
        paint = "" if look.gradient else f' stroke="{hex_color(colors[k])}"'
        if copies is not None:
            paint += f' data-cell="{",".join(map(str, copies[real.copy_of[k]].tolist()))}"'
        out.append(
            f'<g class="strand" data-strand="{int(real.strand_of[k])}"{paint} stroke-width="{stroke:.2f}" '
            f'fill="none" stroke-linecap="butt" stroke-linejoin="round">'
        )
        for lo, hi in spans:
            for a, b in bands(lo, hi, length) if look.gradient else [(lo, hi)]:
                line = xy[k] if whole else cut(q, s, a, b)
                hue = f' stroke="{hex_color(arc_colors(np.array([(a + b) / 2 / length]))[0])}"' if look.gradient else ""
                out.append(f'<path{hue} d="{path_data(line, whole)}"/>')
        out.append("</g>")
    if options.title:
        out.append(
            f'<text class="title" x="{width / 2:g}" y="{top * 0.7:g}" text-anchor="middle" '
            f'font-family="sans-serif" font-size="16">{escape(options.title)}</text>'
        )
    out.append("</svg>")
    return ("\n".join(out) + "\n").encode()


def bands(lo: float, hi: float, length: float) -> list[tuple[float, float]]:
    """``(lo, hi)`` split at every ``length / BANDS`` (the colour bands of a gradient)."""
    step = length / BANDS
    cuts = np.arange(np.floor(lo / step) + 1, np.ceil(hi / step)) * step
    edges = [lo, *cuts.tolist(), hi]
    return list(zip(edges[:-1], edges[1:], strict=True))


def look_rgb(color: str) -> tuple[float, float, float]:
    """RGB in ``[0, 1]`` of a matplotlib colour (checked when the look was built)."""
    from matplotlib.colors import to_rgb

    r, g, b = to_rgb(color)
    return float(r), float(g), float(b)


def scaffold_group(real: Realization, pixels: Callable[[np.ndarray], np.ndarray]) -> str:
    """``<g class="scaffold">``: the scaffold's faces (a block's cells) and a block's frame, faint."""
    faces = "".join(f'<path d="{path_data(pixels(p), True)}"/>' for p in scaffold_polygons(real))
    frame = "".join(
        f'<path d="{path_data(pixels(np.asarray(e)))}"/>' for e in (real.block.frame() if real.block else [])
    )
    return (
        '<g class="scaffold" fill="#99a6bf" fill-opacity="0.06" stroke="#595973" stroke-opacity="0.3" '
        f'stroke-width="0.5" stroke-linejoin="round">{faces}'
        f'<g fill="none" stroke="#333340" stroke-opacity="0.7" stroke-width="1">{frame}</g></g>'
    )
