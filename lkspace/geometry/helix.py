"""The edge pieces: strands leave their face tracks, wind as a regular helix, and return.

On an edge of degree ``K`` and twist ``t`` the ``K`` strands run from ``sigma = 0`` (end
``a``) to ``sigma = 1`` (end ``b``) at slot coordinates ``x_i(sigma) = i + t G(sigma)``
(``i`` the slot the strand starts in; ``G`` the **twist profile**).  A slot coordinate is
turned into an angle about the edge axis in two ways:

* ``Phi(x)``: the face angle, interpolated between the slots' own track angles (where the
  strands enter and leave the edge), and
* ``Psi(x) = theta_0 + 2 pi x / K``: evenly spaced angles, ``2 pi / K`` apart, turned so
  that they sit as close as possible to the face angles (``theta_0`` is the circular mean
  of ``Phi(j) - 2 pi j / K`` over the slots ``j``).

The strand's angle is ``(1 - w) Phi(x) + w Psi(x)`` and its distance from the axis
``(1 - w) R(x) + w r_h`` (``r_h`` the helix radius), where the **spacing weight**
``w(sigma)`` rises smoothly from 0 to 1 within the first ``RAMP`` of the edge and falls
back within the last.  ``G`` turns at a constant rate exactly where ``w = 1`` (a regular
helix of ``t / K`` turns), easing in and out with zero slope at both ends (C2: the
derivative of ``G`` is a trapezoid with smoothstep flanks), and ``G(1 - s) = 1 - G(s)``.

Both angle maps increase strictly with ``x`` and advance by ``2 pi`` when ``x`` advances
by ``K``, so every convex combination does too: at each ``sigma`` the ``K`` strands sit at
``K`` distinct angles and never meet, and the edge carries the braid of a ``2 pi t / K``
rotation, as the twist rule says.  With ``pitch`` (axial length per full turn) the twist
is confined to a window of the edge centred on its middle.
"""

from __future__ import annotations

import numpy as np

from ..errors import GeometryError
from ..model.scaffold import Scaffold
from ..words import noun
from .tracks import Tracks

RAMP = 0.4
"""Fraction of an edge's helix span at each end over which the strands move between their
face angles and the even spacing (and the twist rate eases in or out)."""


def ease(u: np.ndarray) -> np.ndarray:
    """Smoothstep of ``u`` clipped to ``[0, 1]``."""
    u = np.clip(u, 0.0, 1.0)
    return u * u * (3.0 - 2.0 * u)


def spacing_weight(sigma: np.ndarray, ramp: float = RAMP) -> np.ndarray:
    """``w(sigma)``: 0 at both ends, 1 on ``[ramp, 1 - ramp]``, smooth (C1) in between."""
    return ease(sigma / ramp) * ease((1.0 - sigma) / ramp)


def twist_profile(sigma: np.ndarray, ramp: float = RAMP) -> np.ndarray:
    """``G(sigma)``: 0 -> 1, constant slope on ``[ramp, 1 - ramp]``, zero slope at the ends.

    ``G`` is the normalized integral of :func:`spacing_weight` (in closed form:
    the integral of smoothstep is ``u**3 - u**4 / 2``).
    """
    s = np.clip(sigma, 0.0, 1.0)
    a = ramp
    total = 1.0 - a

    def part(u: np.ndarray) -> np.ndarray:
        return a * (u**3 - 0.5 * u**4)

    out = np.where(
        s <= a,
        part(s / a),
        np.where(s >= 1 - a, total - part((1 - s) / a), 0.5 * a + (s - a)),
    )
    return np.asarray(out / total)


def even_offsets(scaffold: Scaffold, fr: Tracks) -> np.ndarray:
    """(n_edges,) ``theta_0`` of every edge: the evenly spaced angles nearest the face angles."""
    radial = scaffold.radial
    starts = radial.edge_starts
    k = np.diff(starts)
    edge_of = np.repeat(np.arange(len(k)), k)
    j = np.arange(len(edge_of)) - starts[edge_of]
    d = fr.slot_angle - 2 * np.pi * j / np.maximum(k[edge_of], 1)
    c = np.bincount(edge_of, np.cos(d), minlength=len(k))
    s = np.bincount(edge_of, np.sin(d), minlength=len(k))
    theta = np.arctan2(s, c)
    first = fr.slot_angle[starts[:-1]]
    return np.asarray(theta + 2 * np.pi * np.round((first - theta) / (2 * np.pi)))


def helix_windows(
    scaffold: Scaffold, fr: Tracks, labels: np.ndarray, pitch: float | None
) -> tuple[np.ndarray, np.ndarray]:
    """Per edge, the window ``[start, width]`` (fractions of the helix span) where the twist happens.

    Without ``pitch`` the twist spans the whole edge.  With it, the regular part is
    ``pitch * |t| / K`` long; an edge too short for it is refused naming the edge.
    """
    n = scaffold.n_edges
    if pitch is None:
        return np.zeros(n), np.ones(n)
    k = scaffold.edge_degrees
    span = (1 - fr.margin[:, 0] - fr.margin[:, 1]) * fr.length
    turns = np.abs(np.asarray(labels, np.float64)) / np.maximum(k, 1)
    width = pitch * turns / (1 - 2 * RAMP) / span
    twisted = (k > 1) & (turns > 0)
    bad = np.flatnonzero(twisted & (width > 1))
    if len(bad):
        e = int(bad[np.argmax(width[bad])])
        raise GeometryError(
            f"{scaffold.name}: `pitch` {pitch:g} needs {pitch * turns[e] / (1 - 2 * RAMP):.4g} of edge "
            f"{scaffold.edge_name(e)} for its {turns[e]:.3g} {noun(turns[e], 'turn')}, but the edge leaves {span[e]:.4g}; use a smaller pitch",
            usage=True,
            parameter="pitch",
        )
    width = np.where(twisted, width, 1.0)
    return 0.5 * (1 - width), width


def edge_angles(
    fr: Tracks,
    scaffold: Scaffold,
    e: np.ndarray,
    xs: np.ndarray,
    sigma: np.ndarray,
    theta0: np.ndarray,
    helix_radius: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Angle and distance from the axis of strands at slot coordinates ``xs`` on edges ``e``."""
    k = scaffold.edge_degrees[e]
    j0 = np.floor(xs).astype(np.int64)
    rem = xs - j0
    jm = np.mod(j0, k)
    wraps = np.floor_divide(j0, k)
    idx = scaffold.radial.edge_starts[e] + jm
    nxt = np.where(jm + 1 == k, scaffold.radial.edge_starts[e], idx + 1)
    phi_face = fr.slot_angle[idx] + rem * fr.slot_gap[idx] + 2 * np.pi * wraps
    rad_face = (1 - rem) * fr.slot_radius[idx] + rem * fr.slot_radius[nxt]
    phi_even = theta0[e] + 2 * np.pi * xs / k
    w = np.where(k > 1, spacing_weight(sigma), 0.0)
    return (1 - w) * phi_face + w * phi_even, (1 - w) * rad_face + w * helix_radius[e]
