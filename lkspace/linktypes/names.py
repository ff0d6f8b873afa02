"""Knot and link types named by the user: ``3_1``, ``m3_1``, ``4_1``, ``L6a4``, ``K14n10910``, ``3_1#4_1``.

Common names are understood too (``"Borromean rings"``, ``"left-handed trefoil"``:
:mod:`~lkspace.linktypes.common_names`).

Names are those ``identify`` reports: ``0_1``; Rolfsen's ``3_1`` ... ``10_165`` and
KnotInfo's ``11a_1`` ... ``13n_5110`` for knots (SnapPy's spelling ``K11a1`` is accepted);
Thistlethwaite's ``L2a1`` ... ``L11n459`` for links (an orientation suffix such as
``{0,1}`` is ignored; every spelling is read by
:func:`~lkspace.linktypes.spelling.canonical_name`); ``K14n10910`` / ``L13n4723``: SnapPy's ``HTLinkExteriors``
(hyperbolic knots to 15 crossings, links to 14); ``A#B``: a connected sum of knots.

**Mirror images.**  A plain name matches both chiralities.  ``m`` in front (``m3_1``, or
``--chirality mirror``) asks for the mirror image of the table's diagram;
``--chirality table`` for the table's own (KnotInfo's ``3_1`` is the right-handed
trefoil).  This is identify's ``mirror`` field: ``m3_1`` is a design whose
``chiral_name`` is ``m3_1``.  An amphichiral type (``4_1``) matches either way.  A
design whose chirality identify cannot tell (``mirror: null``) neither matches nor is
ruled out by a chirality request.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from functools import lru_cache
from typing import Any, Literal, TypeAlias

import numpy as np

from ..errors import UsageError
from ..knots.determinant import determinant
from ..knots.hoste import HT_NAME, ht_crossings, ht_manifold
from ..knots.naming import name_key, one_based
from ..knots.tables import JONES_POINT, TableEntry, knot_modules, laurent_value, tables
from .common_names import common_type
from .fields import JsonObject
from .spelling import CHIRALITIES, Chirality, canonical_name, chiral_parts

Verdict: TypeAlias = Literal["match", "other", "undetermined"]
"""An identification against a target (:func:`judge`)."""


@dataclass(frozen=True, eq=False)
class LinkType:
    """A knot or link type to design.

    Attributes
    ----------
    name : str
        The name as ``identify`` reports it (``"3_1"``, ``"L6a4"``, ``"3_1#4_1"``).
    chirality : ``"any"``, ``"table"`` or ``"mirror"``
    components, crossings : int
        Components; the crossing number (no diagram of the type has fewer crossings).
    table : str
        ``"knotinfo"``, ``"linkinfo"`` or ``"HTLinkExteriors"`` (``+`` joined for a sum).
    fingerprints : frozenset of Fraction
        Jones polynomial at ``sqrt t = 2/3`` of the type, its mirror and every orientation.
    linking : (n, n) int64 or None
        Absolute linking numbers of a link (up to renumbering).
    amphichiral : bool or None
        The type equals its mirror image (``None``: not known here).
    factors : tuple of str
        Chiral names of the prime factors of a sum (``("3_1", "m3_1")``), else ``()``.
    determinant : int or None
        ``|V(-1)|`` of the type (:func:`lkspace.knots.determinant.determinant`; ``None``: not known).
    """

    name: str
    chirality: Chirality
    components: int
    crossings: int
    table: str
    fingerprints: frozenset[Fraction]
    linking: np.ndarray | None = None
    amphichiral: bool | None = None
    factors: tuple[str, ...] = field(default=())
    determinant: int | None = None

    @property
    def label(self) -> str:
        """The name with its chirality: ``"m3_1"``, ``"3_1 (table chirality)"`` or ``"3_1"``."""
        if self.factors and self.chirality != "any":
            return "#".join(self.factors)
        return {"any": self.name, "mirror": f"m{self.name}", "table": f"{self.name} (table chirality)"}[self.chirality]

    def to_dict(self) -> JsonObject:
        """Return the JSON form (name, chirality, components, crossing number, table)."""
        return {
            "name": self.name,
            "chirality": self.chirality,
            "components": self.components,
            "crossing_number": self.crossings,
            "table": self.table,
            "amphichiral": self.amphichiral,
        }


@lru_cache(maxsize=1)
def table_entries() -> dict[str, list[TableEntry]]:
    """KnotInfo/LinkInfo entries by name (``identify``'s names), every orientation of a link."""
    out: dict[str, list[TableEntry]] = {}
    for entries in tables().values():
        for e in entries:
            out.setdefault(e.name, []).append(e)
    return out


def _jones_values(pd: list[list[int]]) -> set[Fraction]:
    """Jones polynomial of a PD code at ``sqrt t = 2/3`` and ``3/2`` (the mirror's), every orientation.

    Reversing the components in a set S multiplies the Jones polynomial by ``t^(-3 lam)``,
    ``lam`` the linking number of S with the rest (Morton); both signs are kept, so the
    set holds every orientation of the link and of its mirror image.
    """
    spherogram, regina, _ = knot_modules()
    if not pd:
        return {Fraction(1)}
    jones = regina.Link.fromPD(pd).jones()
    lk = np.asarray(spherogram.Link(pd).linking_matrix(), np.int64)
    n = len(lk)
    lams = set()
    for mask in range(1 << max(n - 1, 0)):
        inside = np.array([(mask >> i) & 1 for i in range(n)], bool)
        lams.add(abs(int(lk[inside][:, ~inside].sum())))
    out = set()
    for x in (JONES_POINT, 1 / JONES_POINT):
        value = laurent_value(jones, x)
        for lam in lams:
            out |= {value * x ** (6 * lam), value * x ** (-6 * lam)}
    return out


def _abs_linking(pd: list[list[int]]) -> np.ndarray:
    spherogram, _, _ = knot_modules()
    return np.abs(np.asarray(spherogram.Link(pd).linking_matrix(), np.int64))


@lru_cache(maxsize=1)
def _amphichiral_knots() -> frozenset[str]:
    """KnotInfo's amphichiral knots (``symmetry_type`` fully, positive or negative amphicheiral)."""
    _, _, dki = knot_modules()
    return frozenset(r["name"] for r in dki.link_list() if "amphicheiral" in str(r.get("symmetry_type") or ""))


def _prime(name: str, chirality: Chirality, typed: str) -> LinkType:
    """Return the target of one prime (or trivial) name."""
    if name == "0_1":
        return LinkType("0_1", "any", 1, 0, "knotinfo", frozenset({Fraction(1)}), None, True, determinant=1)
    entries = table_entries().get(name)
    if entries:
        fps: set[Fraction] = set()
        for e in entries:
            fps |= _jones_values(e.pd_code())
        first = entries[0]
        n = int(first.components)
        linking = _abs_linking(first.pd_code()) if n > 1 else None
        amphi = name in _amphichiral_knots() if n == 1 and chirality != "any" else None
        table = "knotinfo" if n == 1 else "linkinfo"
        det = determinant(first.pd_code())
        return LinkType(
            name, chirality, n, int(first.crossings), table, frozenset(fps), linking, amphi, determinant=det
        )
    small = (ht_crossings(name) or 99) <= (10 if name.startswith("K") else 11)
    manifold = ht_manifold(name) if HT_NAME.fullmatch(name) and not small else None
    if manifold is None:
        raise UsageError(
            f"type_name {typed!r}: no such knot or link type (names like 3_1, m3_1, 5_2, 11a_1, L6a4, "
            "K14n10910, L13n4723 or 3_1#4_1: KnotInfo/LinkInfo and SnapPy's HTLinkExteriors)",
            parameter="type_name",
        )
    link = manifold.link()
    pd = one_based(link.PD_code())
    n = int(manifold.num_cusps())
    amphi = None
    if chirality != "any":
        from ..knots.hoste import meridian_isometries

        amphi = -1 in meridian_isometries(manifold, manifold)
    crossings = ht_crossings(name) or 0
    linking = _abs_linking(pd) if n > 1 else None
    jones = frozenset(_jones_values(pd))
    return LinkType(
        name, chirality, n, crossings, "HTLinkExteriors", jones, linking, amphi, determinant=determinant(pd)
    )


def parse_type(type_name: str, chirality: str = "any") -> LinkType:
    """Parse a type name (see the module docstring) into a :class:`LinkType`.

    Raises :class:`~lkspace.errors.UsageError` for an unknown name or a chirality that
    contradicts an ``m`` prefix.

    Examples
    --------
    >>> t = parse_type("m3_1")
    >>> t.name, t.chirality, t.components, t.crossings
    ('3_1', 'mirror', 1, 3)
    >>> parse_type("L6a4").components
    3
    """
    typed = type_name
    text = type_name.strip()
    if chirality not in CHIRALITIES:
        raise UsageError(f"chirality {chirality!r}: expected one of {', '.join(CHIRALITIES)}", parameter="chirality")
    asked: Chirality = chirality
    if not text:
        raise UsageError("type_name: empty name", parameter="type_name")
    common = common_type(text)  # "Borromean rings", "left-handed trefoil"
    if common is not None:
        text, side = common
        if side != "any" and asked not in ("any", side):
            raise UsageError(
                f"type_name {typed!r} names one chirality but `chirality` is {asked}", parameter="type_name"
            )
        asked = side if side != "any" else asked
        return _prime(text, asked, typed)
    if "#" in text:
        return _sum(text, asked, typed)
    name, mirror = chiral_parts(text)
    if mirror:
        if asked == "table":
            raise UsageError(
                f"type_name {typed!r} asks for the mirror image but `chirality` is table",
                parameter="type_name",
            )
        asked = "mirror"
    return _prime(name, asked, typed)


def _sum(text: str, chirality: Chirality, typed: str) -> LinkType:
    """Return the target of a connected sum of knots: the Jones polynomial is the product of the factors'."""
    parts = [p.strip() for p in text.split("#")]
    chiral = []
    primes = []
    for p in parts:
        base, mirror = chiral_parts(p)
        prime = _prime(base, "any", typed)
        if prime.components != 1 or prime.name == "0_1":
            raise UsageError(
                f"type_name {typed!r}: a connected sum is written with non-trivial knots, e.g. 3_1#4_1",
                parameter="type_name",
            )
        if chirality == "mirror":
            mirror = not mirror
        chiral.append(("m" if mirror else "") + prime.name)
        primes.append(prime)
    asked = chirality != "any" or any(p.strip().startswith("m") for p in parts)
    fps = {Fraction(1)}
    for prime in primes:
        fps = {a * b for a in fps for b in prime.fingerprints}
    name = "#".join(sorted((p.name for p in primes), key=name_key))
    table = "+".join(sorted({p.table for p in primes}))
    factors = tuple(sorted(chiral, key=name_key)) if asked else ()
    dets = [p.determinant for p in primes if p.determinant is not None]
    det = math.prod(dets) if len(dets) == len(primes) else None
    return LinkType(name, "table" if asked else "any", 1, 3, table, frozenset(fps), None, None, factors, det)


def judge(target: LinkType, ident: dict[str, Any]) -> Verdict:
    """Compare an identification (``Identification.to_dict()``) with ``target``.

    Returns ``"match"``, ``"other"`` (proved a different type) or ``"undetermined"``
    (identify could not name it, or could not tell its chirality).
    """
    if ident.get("components") != target.components:
        return "other"
    name = ident.get("name")
    if name is None:
        if ident.get("split") and ident.get("status") == "identified":
            return "other"  # a split link: targets are non-split
        cands = ident.get("candidates") or []
        if (
            cands
            and target.table in ("knotinfo", "linkinfo")
            and target.name not in {canonical_name(c.split(" ")[0]) for c in cands}
        ):
            return "other"
        return "undetermined"
    if name != target.name:
        return "other"
    if target.chirality == "any" or target.amphichiral:
        return "match"
    if target.factors:
        got = ident.get("chiral_name")
        if got is None:
            return "undetermined"
        return "match" if tuple(sorted(got.split("#"), key=name_key)) == target.factors else "other"
    mirror = ident.get("mirror")
    if mirror is None:
        return "undetermined"
    return "match" if bool(mirror) == (target.chirality == "mirror") else "other"
