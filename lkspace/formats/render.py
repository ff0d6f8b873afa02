"""3D pictures of realized strands on a matplotlib ``Figure`` (extra ``[render]``).

The figure is a :class:`matplotlib.figure.Figure` with its own Agg canvas: pyplot and
``matplotlib.use`` are never touched, so the caller's backend and open figures stay as
they were.  Tubes are shaded per triangle (Lambert plus a specular highlight) and drawn
back to front; the scaffold (or, for a block, its cells and frame) is drawn faintly.  The
projection is orthographic and framed on the strands (:mod:`.view`).

Picture options (:class:`Look`): ``view`` (``"AZIMUTH,ELEVATION"`` in degrees or a name of
:data:`VIEWS`), ``size`` (``"WxH"`` pixels), ``background`` (``"transparent"`` or a
colour) and ``colors`` (a comma list of colours, a matplotlib colormap name, or
``gradient``: hues along each strand instead of a colour per strand).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import UsageError, require
from ..geometry.realization import Realization
from .colors import arc_colors, curve_colors
from .colors import colors as default_colors
from .tubes import tube_meshes
from .view import TITLE_HEIGHT, direction, pixels_per_unit, screen_axes, view_angles
from .view import frame as strand_frame

if TYPE_CHECKING:
    from matplotlib.figure import Figure

VIEWS: dict[str, tuple[float, float]] = {
    "iso": (-58.0, 24.0),
    "front": (-90.0, 0.0),
    "back": (90.0, 0.0),
    "left": (180.0, 0.0),
    "right": (0.0, 0.0),
    "top": (-90.0, 90.0),
    "bottom": (-90.0, -90.0),
}
"""Named views: ``(azimuth, elevation)`` in degrees (matplotlib's convention; z is up)."""

GRADIENT = "gradient"
"""The ``colors`` value that colours each strand by hues along its length."""

MAX_SIZE = 4000
"""Largest width or height of a picture, in pixels."""

MAX_TITLE = 1000
"""Longest picture title, in characters."""


@dataclass(frozen=True)
class Look:
    """How a picture looks: view angles, pixel size, background and strand colours.

    Strands take one colour each (``palette``, else the default colours), or with
    ``gradient`` hues cycling along each strand.
    """

    azim: float | None = None
    elev: float | None = None
    width: int = 900
    height: int = 900
    background: str = "white"
    palette: tuple[tuple[float, float, float], ...] | None = None
    gradient: bool = False

    def colors(self, n: int) -> np.ndarray:
        """(n, 3) colours: the palette repeated, or the default colours."""
        if not self.palette:
            return default_colors(n)
        return np.array([self.palette[k % len(self.palette)] for k in range(n)], np.float64)

    @property
    def transparent(self) -> bool:
        """Whether the background is transparent."""
        return self.background == "transparent"


def parse_view(text: str | None) -> tuple[float | None, float | None]:
    """``"iso"`` or ``"AZ,EL"`` -> ``(azimuth, elevation)``; ``None`` -> the defaults."""
    if text is None:
        return None, None
    key = text.strip().lower()
    if key in VIEWS:
        return VIEWS[key]
    m = re.fullmatch(r"\s*(-?[0-9.]+)\s*,\s*(-?[0-9.]+)\s*", text)
    if not m:
        raise UsageError(
            f"view {text!r}: expected AZIMUTH,ELEVATION in degrees or one of {', '.join(VIEWS)}", parameter="view"
        )
    azim, elev = float(m.group(1)), float(m.group(2))
    if not (np.isfinite(azim) and np.isfinite(elev) and -90 <= elev <= 90):
        raise UsageError(f"view {text!r}: the elevation must lie in -90..90 degrees", parameter="view")
    return azim, elev


def parse_size(text: str | None, default: tuple[int, int] = (900, 900)) -> tuple[int, int]:
    """``"WxH"`` (or one number for a square) -> ``(width, height)`` in pixels."""
    if text is None:
        return default
    m = re.fullmatch(r"\s*([0-9]{1,6})\s*(?:[xX]\s*([0-9]{1,6}))?\s*", text)
    if not m:
        raise UsageError(f"size {text!r}: expected WIDTHxHEIGHT in pixels, e.g. 480x480", parameter="size")
    w = int(m.group(1))
    h = int(m.group(2) or m.group(1))
    if not (16 <= w <= MAX_SIZE and 16 <= h <= MAX_SIZE):
        raise UsageError(f"size {text!r}: width and height must lie in 16..{MAX_SIZE} pixels", parameter="size")
    return w, h


def parse_color(text: str, parameter: str) -> tuple[float, float, float]:
    """Parse a matplotlib colour (name, ``#rrggbb``, ``0.5`` grey) -> RGB in ``[0, 1]`` (``parameter``: whose)."""
    require("matplotlib", "render", "colours")
    from matplotlib.colors import to_rgb

    try:
        r, g, b = to_rgb(text.strip())
    except ValueError:
        raise UsageError(
            f"{parameter} {text!r}: not a colour (a name such as 'navy', '#1f77b4' or a grey '0.8')",
            parameter=parameter,
        ) from None
    return float(r), float(g), float(b)


def parse_colors(text: str | None) -> tuple[tuple[float, float, float], ...] | None:
    """Parse a comma list of colours, or a matplotlib colormap name (sampled at 8 points); ``gradient`` -> ``None``."""
    if text is None or text.strip().lower() == GRADIENT:
        return None
    require("matplotlib", "render", "colours")
    import matplotlib

    name = text.strip()
    if "," not in name and name in matplotlib.colormaps:
        cmap = matplotlib.colormaps[name]
        n = getattr(cmap, "N", 256)
        ks = np.linspace(0, 1, 8) if n > 32 else (np.arange(min(n, 12)) + 0.5) / min(n, 12)
        return tuple((float(cmap(k)[0]), float(cmap(k)[1]), float(cmap(k)[2])) for k in ks)
    parts = [p for p in name.split(",") if p.strip()]
    if not parts:
        raise UsageError("colors: give a comma list of colours or a colormap name", parameter="colors")
    return tuple(parse_color(p, "colors") for p in parts)


def look_of(view: str | None, size: str | None, background: str | None, colors: str | None) -> Look:
    """Build a :class:`Look` from the command line's strings (checked; a usage error names the option)."""
    azim, elev = parse_view(view)
    width, height = parse_size(size)
    bg = "white" if background is None else background.strip()
    if bg.lower() != "transparent":
        parse_color(bg, "background")
    else:
        bg = "transparent"
    gradient = colors is not None and colors.strip().lower() == GRADIENT
    return Look(azim, elev, width, height, bg, parse_colors(colors), gradient)


def check_title(title: str | None) -> None:
    """Refuse a picture title that cannot be drawn (a usage error): too long, or broken mathtext.

    Text between an even number of unescaped ``$`` signs is matplotlib mathtext; it is
    parsed here, before any work, so ``$\\frac{$`` fails with one line naming the title.
    """
    if title is None:
        return
    if len(title) > MAX_TITLE:
        raise UsageError(f"title of {len(title):,} characters: at most {MAX_TITLE} (MAX_TITLE)")
    require("matplotlib", "render", "pictures")
    from matplotlib import cbook
    from matplotlib.mathtext import MathTextParser

    if not cbook.is_math_text(title):
        return
    try:
        MathTextParser("path").parse(title)
    except ValueError as exc:
        why = " ".join(str(exc).split())[:120]
        raise UsageError(f"title {title[:60]!r}: broken mathtext ({why}); write a literal dollar as \\$") from None


def new_figure(look: Look) -> Figure:
    """Return a new Figure of the look's size with its own Agg canvas (no pyplot)."""
    require("matplotlib", "render", "pictures")
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(look.width / 100, look.height / 100), dpi=100)
    FigureCanvasAgg(fig)
    if look.transparent:
        fig.patch.set_alpha(0.0)
    else:
        fig.patch.set_facecolor(look.background)
    return fig


def scaffold_polygons(real: Realization) -> list[np.ndarray]:
    """Return the faces to draw faintly: the block's cells, the translates' faces, or the scaffold."""
    sc = real.scaffold
    base = [sc.corner_positions[s:t] for s, t in zip(sc.face_starts[:-1], sc.face_starts[1:], strict=True)]
    if real.block is not None:
        from ..geometry.block import block_faces

        return block_faces(sc, real.block)
    shifts = (
        sc.lattice.translate(real.translations)
        if sc.lattice is not None and real.translations is not None
        else np.zeros((1, 3))
    )
    return [p + d for d in shifts for p in base]


def render(
    real: Realization,
    look: Look | None = None,
    *,
    show_mesh: bool = True,
    radius: float | None = None,
    title: str | None = None,
) -> Figure:
    """Draw shaded tubes on a new Figure, framed on the strands: a colour per strand (:func:`strand_colors`)."""
    require("mpl_toolkits.mplot3d", "render", "3D pictures")
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

    look = look or Look()
    radius = real.tube_radius if radius is None else radius
    fig = new_figure(look)
    ax: Any = fig.add_subplot(projection="3d", computed_zorder=False)
    if look.transparent:
        ax.patch.set_alpha(0.0)
    else:
        ax.set_facecolor(look.background)
    pts = np.vstack(real.curves) if real.curves else np.zeros((1, 3))
    polys = scaffold_polygons(real) if show_mesh else []
    frame = real.block.frame() if real.block is not None else []
    azim, elev = view_angles(real, look, radius)
    ax.view_init(elev=elev, azim=azim)
    ax.set_proj_type("ortho")
    view = direction(azim, elev)
    light = view + np.array([0.3, -0.2, 0.6])
    light /= np.linalg.norm(light)
    if polys:
        ax.add_collection3d(
            Poly3DCollection(
                polys, facecolors=(0.6, 0.65, 0.75, 0.06), edgecolors=(0.35, 0.35, 0.45, 0.3), linewidths=0.5
            )
        )
    if frame:
        ax.add_collection3d(Line3DCollection(frame, colors=[(0.2, 0.2, 0.25, 0.7)], linewidths=1.0))
    if real.curves:
        tris, cols = shaded_tubes(real, look, radius, view, light)
        order = np.argsort(tris.mean(axis=1) @ view)  # far first: painter's algorithm
        ax.add_collection3d(
            Poly3DCollection(tris[order], facecolors=cols[order], edgecolors=cols[order], linewidths=0.25)
        )
    right, up = screen_axes(view)
    (cx, cy), half = strand_frame(pts, view, radius)
    center = cx * right + cy * up + float((pts @ view).mean()) * view  # projects to the frame's centre
    reach = float(np.abs(pts - center).max()) + 2 * radius
    limits(ax, center, reach)
    ax.set_axis_off()
    top = TITLE_HEIGHT if title else 0
    if title:
        fig.text(0.5, 1 - 0.7 * top / look.height, title, ha="center", fontsize=12)
    fig.subplots_adjust(0, 0, 1, 1)
    ax.set_box_aspect((1, 1, 1), zoom=1.0)
    scale = pixels_per_unit(half, look.width, look.height - top)
    ax.set_box_aspect((1, 1, 1), zoom=fill_zoom(ax, center, scale))
    ax.apply_aspect()
    offset = pixel_of(ax, center) - np.array([look.width / 2, (look.height - top) / 2])  # pixels from the bottom
    limits(ax, center + (offset[0] * right + offset[1] * up) / scale, reach)
    return fig


def limits(ax: Any, center: np.ndarray, reach: float) -> None:
    """Set the 3D axes' limits to the cube of half side ``reach`` about ``center``."""
    ax.set_xlim(center[0] - reach, center[0] + reach)
    ax.set_ylim(center[1] - reach, center[1] + reach)
    ax.set_zlim(center[2] - reach, center[2] + reach)


def pixel_of(ax: Any, point: np.ndarray) -> np.ndarray:
    """(2,) pixel position of the 3D ``point`` in the figure."""
    from mpl_toolkits.mplot3d import proj3d

    x, y, _ = proj3d.proj_transform(np.array([point[0]]), np.array([point[1]]), np.array([point[2]]), ax.get_proj())
    return np.asarray(ax.transData.transform(np.column_stack([x, y]))[0], np.float64)


def fill_zoom(ax: Any, center: np.ndarray, scale: float) -> float:
    """Zoom of the 3D axes (set at zoom 1) that draws ``scale`` pixels per scaffold unit.

    The pixels of one unit at ``center`` are measured at zoom 1 (the projection is linear).
    """
    ax.apply_aspect()
    right, _ = screen_axes(direction(ax.azim, ax.elev))
    unit = float(np.linalg.norm(pixel_of(ax, center + right) - pixel_of(ax, center)))
    return scale / max(unit, 1e-12)


TUBE_SIDES, THICK_SIDES = 16, 32
"""Facets around a pictured tube; around a thick one (radius over 2% of the drawing, a relaxed rope)."""


def strand_colors(real: Realization, look: Look) -> np.ndarray:
    """(n_curves, 3) RGB: one colour per curve, by its strand and, for a ring copied over cells, its cell.

    The colour slots of :func:`~lkspace.formats.colors.colour_slots` (a strand's stable
    key, then a ring copy's tone) take the look's palette, repeated, else the default
    colours: translates and cut runs of one thread class share its colour, and
    neighbouring copies of a ring differ.
    """
    if not real.curves:
        return np.zeros((0, 3))
    return curve_colors(real, np.array(look.palette, np.float64) if look.palette else None)


def shaded_tubes(
    real: Realization, look: Look, radius: float, view: np.ndarray, light: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Front-facing tube triangles ``(m, 3, 3)`` and their shaded colours ``(m, 3)`` (:func:`strand_colors`)."""
    palette = strand_colors(real, look)
    extent = float(np.ptp(np.vstack(real.curves), axis=0).max())
    sides, spacing = (THICK_SIDES, 0.3 * radius) if radius > 0.02 * extent else (TUBE_SIDES, 0.6 * radius)
    all_tris, all_cols = [], []
    for (v, nrm, f), rgb in zip(tube_meshes(real, radius, sides, spacing), palette, strict=True):
        fn = nrm[f].mean(axis=1)
        fn /= np.maximum(np.linalg.norm(fn, axis=1, keepdims=True), 1e-12)
        lam = np.clip(fn @ light, 0, 1)
        spec = np.clip(fn @ ((light + view) / np.linalg.norm(light + view)), 0, 1) ** 24
        base_rgb = arc_colors(f[:, 0] // sides / max(len(v) // sides, 1)) if look.gradient else rgb[None]
        shade = np.clip(base_rgb * (0.3 + 0.7 * lam[:, None]) + 0.3 * spec[:, None], 0, 1)
        facing = fn @ view > -0.2
        all_tris.append(v[f[facing]])
        all_cols.append(shade[facing])
    return np.concatenate(all_tris), np.concatenate(all_cols)
