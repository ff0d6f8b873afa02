"""Names past KnotInfo/LinkInfo: SnapPy's ``HTLinkExteriors`` (Hoste-Thistlethwaite tables).

KnotInfo ends at 13-crossing knots and LinkInfo at 11-crossing links; SnapPy's
``HTLinkExteriors`` holds the exteriors of the hyperbolic knots up to 15 crossings and
links up to 14 (names like ``K14n10910``, ``L13n4723``).

An exterior alone does not name a link: different links can have isometric exteriors.
So a name is accepted only through an isometry that takes **meridians to meridians**
(SnapPy's ``identify(extends_to_link=True)``, then each isometry's cusp maps checked
here): Dehn filling along the meridians turns such an isometry into a homeomorphism of
S^3 carrying our link onto the table's.  Its orientation says the chirality: an isometry
whose cusp maps have determinant +1 preserves orientation (``mirror: False``, the table
diagram's handedness); -1 reverses it (``mirror: True``); both kinds: amphichiral
(``mirror: None``).  For knots, exteriors alone already decide the type up to mirror
image (Gordon-Luecke); the meridian check costs nothing more.
"""

from __future__ import annotations

import re
from typing import Any, NamedTuple

HT_NAME = re.compile(r"([KL])(\d+)([an])(\d+)")
"""A Hoste-Thistlethwaite name: ``K14n10910`` (knot) or ``L13n4723`` (link)."""

TABLE = "HTLinkExteriors"


class HTName(NamedTuple):
    """A link named from ``HTLinkExteriors``: its name there, and whether it is that entry's mirror image."""

    name: str
    mirror: bool | None


def ht_crossings(name: str) -> int | None:
    """Crossing number in a Hoste-Thistlethwaite name (``"L13n4723"`` -> 13); ``None`` if not one."""
    m = HT_NAME.fullmatch(name)
    return int(m[2]) if m else None


def ht_manifold(name: str) -> Any | None:
    """Return the table's exterior of ``name`` (a ``snappy.Manifold``), ``None`` if the table has no such entry."""
    import snappy

    if HT_NAME.fullmatch(name) is None:
        return None
    try:
        return snappy.HTLinkExteriors[name]
    except (KeyError, IndexError, ValueError):
        return None


def meridian_isometries(exterior: Any, table: Any) -> list[int]:
    """Return the determinants (+1, -1) of the isometries ``exterior -> table`` that take meridians to meridians."""
    try:
        isometries = exterior.is_isometric_to(table, return_isometries=True)
    except Exception:  # noqa: BLE001 - SnapPy cannot decide (degenerate triangulation)
        return []
    dets = []
    for iso in isometries:
        maps = [[[int(m[0, 0]), int(m[0, 1])], [int(m[1, 0]), int(m[1, 1])]] for m in iso.cusp_maps()]
        if all(a[1][0] == 0 and abs(a[0][0]) == 1 for a in maps):  # (1, 0) -> (+-1, 0): meridian to meridian
            det = {a[0][0] * a[1][1] - a[0][1] * a[1][0] for a in maps}
            if len(det) == 1:
                dets.append(det.pop())
    return dets


def ht_name(exterior: Any, n_components: int) -> HTName | None:
    """Name a hyperbolic link exterior from ``HTLinkExteriors`` through a meridian-preserving isometry.

    Parameters
    ----------
    exterior : snappy.Manifold
        The exterior of our link, its cusps framed by meridians and longitudes (as
        ``spherogram.Link.exterior()`` makes it).
    n_components : int

    Returns
    -------
    HTName or None
        ``name`` (in the table :data:`TABLE`) and ``mirror``, or ``None`` when no single
        table link has a meridian-preserving isometric exterior.

    Examples
    --------
    >>> import snappy
    >>> link = snappy.HTLinkExteriors["L13n4723"].link()
    >>> ht_name(link.exterior(), 2).name, ht_name(link.mirror().exterior(), 2).mirror
    ('L13n4723', True)
    """
    try:
        found = exterior.identify(extends_to_link=True)
    except Exception:  # noqa: BLE001 - SnapPy may fail on a degenerate exterior
        return None
    letter = "K" if n_components == 1 else "L"
    names = sorted({str(m).split("(")[0] for m in found} & _ht_names(found, letter))
    results = []
    for name in names:
        table = ht_manifold(name)
        if table is None or table.num_cusps() != n_components:
            continue
        dets = set(meridian_isometries(exterior, table))
        if dets:
            mirror = None if len(dets) == 2 else dets.pop() < 0
            results.append(HTName(name, mirror))
    return results[0] if len(results) == 1 else None


def _ht_names(found: list[Any], letter: str) -> set[str]:
    """Return the names among SnapPy's answers that are Hoste-Thistlethwaite names of a knot (``K``) or link (``L``)."""
    out = set()
    for m in found:
        name = str(m).split("(")[0]
        match = HT_NAME.fullmatch(name)
        if match and match[1] == letter:
            out.add(name)
    return out
