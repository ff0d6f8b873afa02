"""Strand colours: 24 well-separated colours, given to strands by a stable key.

A strand's key is the smallest face it visits (:func:`strand_keys`):
strands take the palette's colours in the order of their keys, so the colours do not
depend on how the tracer numbered the strands, and an edit that leaves the strands'
order of keys alone leaves their colours alone.  Past 24 strands, golden-ratio hues.

Of a periodic design drawn in several cells, every copy and cut run of a thread (a
strand with a non-zero period) takes its class's colour, so one thread reads as one
colour across the cells; but a **ring** (a closed strand, period zero: each lattice
copy its own component) takes a colour of its class *and its cell*, its **tone**
(:func:`cell_tones`): the copy at lattice translation ``t`` has the tone of ``t``
modulo the ring periods ``m`` (:func:`ring_periods`: along each lattice vector one
more than the farthest copy whose box, widened by the tube, meets the ring's; at least
2).  Two copies of a ring whose boxes meet (every pair that links or touches) differ,
so neighbouring rings of a chainmail differ; a square or hexagonal chainmail takes 4
tones, a cubic one 8.  Tones are numbered so that consecutive tones alternate the
parity of the cell, and every (strand, tone) drawn is a colour **slot**
(:func:`colour_slots`): slots are ranked by strand key, then tone, and take the
palette's colours in that order (a two-colour palette gives a chainmail of one ring
class a checkerboard).
"""

from __future__ import annotations

import colorsys
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ..geometry.realization import Realization

PALETTE = np.array(
    [
        [0.89, 0.10, 0.11],
        [0.12, 0.47, 0.71],
        [0.20, 0.63, 0.17],
        [1.00, 0.50, 0.00],
        [0.42, 0.24, 0.60],
        [0.00, 0.00, 1.00],
        [1.00, 0.70, 0.70],
        [1.00, 0.00, 0.60],
        [0.40, 0.30, 0.00],
        [0.50, 0.80, 0.70],
        [1.00, 0.00, 1.00],
        [0.50, 0.10, 0.20],
        [0.80, 0.80, 0.00],
        [0.00, 0.30, 0.20],
        [1.00, 0.60, 1.00],
        [0.00, 0.90, 0.00],
        [0.00, 0.40, 1.00],
        [0.80, 0.70, 0.40],
        [0.50, 0.40, 0.40],
        [0.50, 0.10, 0.80],
        [1.00, 0.40, 0.50],
        [0.00, 0.80, 1.00],
        [0.80, 0.70, 0.90],
        [0.60, 0.20, 0.00],
    ]
)
"""(24, 3) RGB in ``[0, 1]``: five ColorBrewer colours, then each next colour the farthest (CIELAB) from
those chosen, among an 11-step RGB grid of lightness 25..80 (readable on white): every pair differs by
a CIELAB distance of at least 32."""


def colors(n: int) -> np.ndarray:
    """(n, 3) float64 distinct colours in ``[0, 1]`` (the palette, then golden-ratio hues)."""
    if n <= len(PALETTE):
        return PALETTE[:n].copy()
    extra = [colorsys.hsv_to_rgb((0.618034 * k) % 1.0, 0.75, 0.9) for k in range(n - len(PALETTE))]
    return np.vstack([PALETTE, np.array(extra)])


def hex_colors(rgb: np.ndarray) -> list[str]:
    """``#rrggbb`` of each colour of ``rgb (n, 3)`` in ``[0, 1]``."""
    return ["#{:02x}{:02x}{:02x}".format(*c) for c in (np.asarray(rgb) * 255).round().astype(int).tolist()]


def arc_colors(fractions: np.ndarray) -> np.ndarray:
    """(n, 3) colours cycling through the hues along a strand (``fractions`` of its length in ``[0, 1)``)."""
    hues = np.asarray(fractions, np.float64) % 1.0
    return np.array([colorsys.hsv_to_rgb(h, 0.8, 0.85) for h in hues]).reshape(-1, 3)


def strand_keys(real: Realization) -> np.ndarray:
    """(n_strands,) int64: the smallest face each strand visits (its stable colour key)."""
    tr = real.trace
    faces = real.scaffold.corner_face[tr.steps // 2]
    starts = tr.strand_starts[:-1]
    return np.minimum.reduceat(faces, starts) if len(faces) else np.zeros(0, np.int64)


def ring_periods(real: Realization) -> np.ndarray:
    """(dim,) int64: the tone periods of the rings of a periodic ``real`` (module docstring; ``(0,)`` if finite).

    Along each lattice vector, one more than the farthest lattice copy of a ring whose
    bounding box, widened by the tube radius, meets the ring's own; at least 2.
    """
    lattice = real.scaffold.lattice
    if lattice is None:
        return np.zeros(0, np.int64)
    periods = np.full(lattice.dim, 2, np.int64)
    inverse = np.abs(np.linalg.pinv(lattice.basis))  # (3, dim)
    kinds = real.trace.strand_kinds
    for strand in np.unique(real.strand_of):
        if kinds[strand] != "loop":
            continue
        curve = real.curves[int(np.argmax(real.strand_of == strand))]
        extent = np.ptp(curve, axis=0) + 2 * real.tube_radius  # two boxes meet where their shift is within this
        reach = np.floor(extent @ inverse).astype(np.int64) + 1  # no copy farther along a lattice vector meets it
        grid = np.array(list(np.ndindex(*(2 * reach + 1)))) - reach
        near = grid[np.all(np.abs(lattice.translate(grid)) <= extent, axis=1)]
        periods = np.maximum(periods, np.abs(near).max(axis=0) + 1)
    return periods


def cell_tones(translations: np.ndarray, periods: np.ndarray) -> np.ndarray:
    """(n,) int64: the tone of each lattice translation ``(n, dim)`` for ring ``periods`` (module docstring).

    The residues modulo ``periods`` are numbered so that consecutive tones alternate the
    parity of the cell (the sum of its coordinates); the zero translation has tone 0.

    Examples
    --------
    >>> cell_tones(np.array([[0, 0], [1, 0], [0, 1], [1, 1], [2, 3]]), np.array([2, 2])).tolist()
    [0, 3, 1, 2, 1]
    """
    residues = np.array(list(np.ndindex(*periods)), np.int64)  # mixed radix, the last axis fastest
    parity = residues.sum(axis=1) % 2
    within = np.zeros(len(residues), np.int64)
    for p in (0, 1):
        within[parity == p] = np.arange(int((parity == p).sum()))
    tone_of = np.empty(len(residues), np.int64)
    tone_of[np.lexsort((parity, within))] = np.arange(len(residues))
    index = np.ravel_multi_index(tuple((np.asarray(translations, np.int64) % periods).T), tuple(periods))
    return tone_of[index]


def curve_tones(real: Realization) -> np.ndarray:
    """(n_curves,) int64: the tone of each curve's cell for a ring copied over cells, else 0 (module docstring)."""
    tones = np.zeros(real.n_curves, np.int64)
    if real.scaffold.lattice is None or real.translations is None or len(real.translations) < 2:
        return tones
    rings = np.array([real.trace.strand_kinds[s] == "loop" for s in real.strand_of.tolist()], bool)
    if rings.any():
        tones[rings] = cell_tones(real.translations[real.copy_of[rings]], ring_periods(real))
    return tones


def colour_slots(real: Realization) -> np.ndarray:
    """(n_curves,) int64: each curve's colour slot, the rank of its (strand key, tone) (module docstring)."""
    if not real.n_curves:
        return np.zeros(0, np.int64)
    keys = strand_keys(real)
    rank = np.empty(len(keys), np.int64)
    rank[np.argsort(keys, kind="stable")] = np.arange(len(keys))  # distinct even where two strands share a key
    pairs = np.column_stack([rank[real.strand_of], curve_tones(real)])
    _, slots = np.unique(pairs, axis=0, return_inverse=True)
    return np.asarray(slots, np.int64).reshape(-1)


def curve_colors(real: Realization, palette: np.ndarray | None = None) -> np.ndarray:
    """(n_curves, 3) one colour per curve: its colour slot's (:func:`colour_slots`).

    Slots take the default colours (:func:`colors`), or ``palette`` ``(k, 3)`` repeated.
    """
    slots = colour_slots(real)
    n = int(slots.max()) + 1 if len(slots) else 0
    base = colors(n) if palette is None else np.asarray(palette, np.float64)[np.arange(n) % len(palette)]
    return np.asarray(base[slots], np.float64).reshape(-1, 3)
