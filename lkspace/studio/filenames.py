"""File names that say which design a download holds: scaffold and labels, safe characters only.

``cube_t1.-1.0.2.1.1.1.1.1.1.1.1`` for a short label list (no nulls), else the scaffold and
8 hex digits of a hash of the labels and nulls: ``honeycomb-cP_3f2a9c01``.  The page asks
the server (``/api/filename``) for the stem of its own downloads, so the rule lives here only.
"""

from __future__ import annotations

import hashlib
import re
from collections.abc import Iterable

MAX_SHORT = 48
"""Longest label text written out in a file name (longer lists are hashed)."""

UNSAFE = re.compile(r"[^A-Za-z0-9_.-]+")


def design_stem(scaffold_name: str, labels: Iterable[int], nulls: Iterable[int] = ()) -> str:
    """Return the file name stem of a design: scaffold name, then its labels or their hash.

    ``nulls`` are side indices.

    Examples
    --------
    >>> design_stem("cube", [1, -1, 0, 2] + [1] * 8)
    'cube_t1.-1.0.2.1.1.1.1.1.1.1.1'
    >>> design_stem("honeycomb:cP@3x3x3", [1] * 81)
    'honeycomb-cP-3x3x3_b9df3772'
    """
    base = UNSAFE.sub("-", scaffold_name).strip("-.")[:60] or "design"
    words = [str(int(t)) for t in labels]
    sides = [str(int(s)) for s in nulls]
    short = ".".join(words)
    if not sides and len(short) <= MAX_SHORT:
        return f"{base}_t{short}"
    key = ",".join(words) + (";" + ",".join(sides) if sides else "")
    return f"{base}_{hashlib.sha256(key.encode()).hexdigest()[:8]}"
