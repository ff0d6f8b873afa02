"""The strand curves as they travel to the page: one content key per curve, points only for new ones.

Every curve gets a **key**, a hash of its ``float32`` points and closed flag (16 hex
digits), so two curves with one key draw alike.  The page says which keys it holds
(``have``); the answer lists every curve (key, point count, strand, copy, the tone of a
ring's cell, :func:`lkspace.formats.colors.curve_tones`: the page colours a ring's copies
by it, and the colour slot ``export`` gives it, :func:`~lkspace.formats.colors.colour_slots`) but packs the
points of the others only, as base64 little-endian ``float32``.  An edit changes the
strands through one edge, so after an edit most curves travel as a key alone, and the
page rebuilds the tubes of the new ones only.
"""

from __future__ import annotations

import base64
import hashlib

import numpy as np

from .. import Realization
from ..formats.colors import colour_slots, curve_tones
from .answers import CurvesView


def curve_key(points: np.ndarray, closed: bool) -> str:
    """Return the content key of a curve: 16 hex digits of a hash of its ``float32`` points and closed flag."""
    h = hashlib.blake2b(np.ascontiguousarray(points, "<f4").tobytes(), digest_size=8)
    h.update(b"closed" if closed else b"open")
    return h.hexdigest()


def curves_view(real: Realization, have: frozenset[str] = frozenset()) -> CurvesView:
    """Return the page's view of ``real``'s curves, with the points of the curves whose key is not in ``have``."""
    keys = [curve_key(c, bool(cl)) for c, cl in zip(real.curves, real.closed, strict=True)]
    sent = [c for c, key in zip(real.curves, keys, strict=True) if key not in have]
    points = np.vstack(sent) if sent else np.zeros((0, 3))
    return {
        "keys": keys,
        "points": base64.b64encode(np.ascontiguousarray(points, "<f4").tobytes()).decode("ascii"),
        "sent": [key not in have for key in keys],
        "counts": [len(c) for c in real.curves],
        "closed": real.closed.tolist(),
        "strand": real.strand_of.tolist(),
        "copy": real.copy_of.tolist(),
        "tone": curve_tones(real).tolist(),
        "slot": colour_slots(real).tolist(),
        "radius": real.tube_radius,
        "scale": real.scale,
    }
