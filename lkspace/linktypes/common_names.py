"""Common names of knots and links, both ways: ``"Borromean rings"`` <-> ``L6a4``.

Table names follow KnotInfo/LinkInfo (Rolfsen's ``3_1`` for knots, Thistlethwaite's
``L6a4`` for links, an orientation suffix such as ``{0,1}`` dropped), with ``m`` in front
for the mirror image of the table's diagram; they are spelled by
:func:`~lkspace.linktypes.spelling.canonical_name`.  KnotInfo's ``3_1`` is the right-handed
trefoil (its diagram has writhe +3), so ``m3_1`` is the left-handed one.  A split link
is the atlas type ``split: 0_1 + 0_1`` (:func:`lkspace.linktypes.atlas.type_key`); its
pieces all unknots, it is the unlink of that many components.

Each pair was checked against ``database_knotinfo``: the knots by name, writhe and
signature; the links by LinkInfo's ``rolfsen_name`` and braid word (``L2a1`` = 2^2_1,
the Hopf link; ``L4a1`` = 4^2_1 = the closed braid σ₁⁴, the (2,4) torus link; ``L5a1`` =
5^2_1; ``L6a3`` = σ₁⁶, the (2,6) torus link; ``L6a4`` = 6^3_2).
"""

from __future__ import annotations

import difflib
import re

from ..errors import UsageError
from .spelling import Chirality, chiral_name, chiral_parts, is_table_name

COMMON: dict[str, tuple[str, ...]] = {
    "0_1": ("unknot", "trivial knot"),
    "3_1": ("trefoil", "trefoil knot", "(2,3) torus knot", "(3,2) torus knot"),
    "4_1": ("figure-eight knot", "figure-eight", "figure eight knot"),
    "5_1": ("cinquefoil", "cinquefoil knot", "pentafoil", "(2,5) torus knot", "(5,2) torus knot"),
    "5_2": ("three-twist knot",),
    "6_1": ("stevedore knot", "stevedore"),
    "6_2": ("Miller Institute knot",),
    "7_1": ("septafoil", "septafoil knot", "(2,7) torus knot", "(7,2) torus knot"),
    "L2a1": ("Hopf link", "Hopf"),
    "L4a1": ("Solomon link", "Solomon's knot", "Solomon", "(2,4) torus link", "(4,2) torus link"),
    "L5a1": ("Whitehead link", "Whitehead"),
    "L6a3": ("(2,6) torus link", "(6,2) torus link"),
    "L6a4": ("Borromean rings", "Borromean link", "Borromean"),
}
"""Table name -> its common names, the one shown first."""

CHIRAL: dict[str, tuple[str, str]] = {"3_1": ("right-handed trefoil", "left-handed trefoil")}
"""Table name -> the common names of the table's diagram and of its mirror image."""

MAX_UNLINK = 64
"""Most components of an unlink named in words (``unlink of 3 components``)."""

UNLINK = re.compile(r"(?:unlink of (\d+) components?|(\d+)[- ]?components? unlink|unlink (\d+))")


def _key(text: str) -> str:
    """``"Borromean  Rings"`` -> ``"borromeanrings"``: case, spaces, hyphens and apostrophes ignored."""
    return re.sub(r"[\s\-_'’]+", "", text.lower())


def _aliases() -> dict[str, tuple[str, Chirality]]:
    out: dict[str, tuple[str, Chirality]] = {}
    for name, words in COMMON.items():
        for w in words:
            out[_key(w)] = (name, "any")
    for name, (table, mirror) in CHIRAL.items():
        out[_key(table)] = (name, "table")
        out[_key(mirror)] = (name, "mirror")
    return out


ALIASES = _aliases()
"""Normalized common name -> (table name, chirality)."""


def common_name(name: str, mirror: bool | None = None) -> str | None:
    """Return the common name of a table name or atlas type, or ``None``.

    ``mirror``: the chirality identify found (``m`` in front of ``name`` says mirror too);
    a chiral type with a name per chirality (the trefoil) gets the one that fits.

    Examples
    --------
    >>> common_name("L6a4"), common_name("m3_1"), common_name("3_1"), common_name("8_19")
    ('Borromean rings', 'left-handed trefoil', 'trefoil', None)
    >>> common_name("3_1", mirror=False)
    'right-handed trefoil'
    >>> common_name("split: 0_1 + 0_1 + 0_1")
    'unlink of 3 components'
    """
    if name.startswith("split: "):
        pieces = name[len("split: ") :].split(" + ")
        return f"unlink of {len(pieces)} components" if all(p == "0_1" for p in pieces) else None
    base, marked = chiral_parts(name)
    mirror = True if marked else mirror
    if mirror is not None and base in CHIRAL:
        return CHIRAL[base][int(mirror)]
    words = COMMON.get(base)
    return words[0] if words else None


def resolve_type(text: str) -> tuple[str, Chirality]:
    """Return ``(table name or atlas type, chirality)`` of what a user typed.

    Table names (``3_1``, ``m3_1``, ``l6a4``, ``L6a4{0,1}``, ``3_1#4_1``), atlas types
    (``split: 0_1 + 3_1``) and common names (case, spaces, hyphens ignored: ``"Borromean
    rings"``, ``borromean``, ``left-handed trefoil``, ``unlink of 2 components``).
    Raises :class:`~lkspace.errors.UsageError` (parameter ``name``) for anything else,
    suggesting close common names.
    """
    typed = text
    text = " ".join(text.split())
    if not text:
        raise UsageError("name: empty; give a type such as 3_1, L6a4 or 'Borromean rings'", parameter="name")
    if text.startswith("split: "):
        return text, "any"
    parts = text.split("#")
    if all(is_table_name(p.strip()) for p in parts):
        if len(parts) > 1:
            return "#".join(chiral_name(p.strip()) for p in parts), "any"
        name, mirror = chiral_parts(text)
        return name, "mirror" if mirror else "any"
    found = common_type(text)
    if found:
        return found
    m = UNLINK.fullmatch(text.lower())
    if m:
        n = int(next(g for g in m.groups() if g))
        if 1 <= n <= MAX_UNLINK:
            return ("0_1" if n == 1 else "split: " + " + ".join(["0_1"] * n)), "any"
    close = difflib.get_close_matches(_key(text), list(ALIASES), n=6, cutoff=0.6)
    shown = list(dict.fromkeys(_first_name(ALIASES[k]) for k in close))[:3]
    hint = f"; did you mean {' or '.join(repr(s) for s in shown)}?" if shown else ""
    raise UsageError(
        f"name {typed!r}: not a knot or link name (table names like 3_1, m3_1, 5_2, L6a4, 3_1#4_1, or common "
        f"names like 'trefoil', 'Borromean rings', 'Whitehead link'){hint}",
        parameter="name",
    )


def common_type(text: str) -> tuple[str, Chirality] | None:
    """Return ``(table name, chirality)`` of a common name (``"Hopf link"``, ``"left-handed trefoil"``), else ``None``."""
    return ALIASES.get(_key(text))


def resolve_name(text: str) -> str:
    """Return the table name (``m`` in front for a mirror image) or atlas type of what a user typed.

    The table's own chirality (``"right-handed trefoil"``) comes back as the plain name
    (``3_1``, either chirality); :func:`resolve_type` keeps it apart.

    Examples
    --------
    >>> resolve_name("Borromean rings"), resolve_name("left-handed trefoil"), resolve_name("L6a4{0,1}")
    ('L6a4', 'm3_1', 'L6a4')
    """
    name, chirality = resolve_type(text)
    return f"m{name}" if chirality == "mirror" else name


def _first_name(found: tuple[str, Chirality]) -> str:
    """Return the common name shown for a type and chirality: ``("3_1", "mirror")`` -> ``"left-handed trefoil"``."""
    name, side = found
    return CHIRAL[name][side == "mirror"] if side != "any" else COMMON[name][0]
