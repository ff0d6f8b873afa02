"""Sharing names by key: the trust rule, the second and third levels, and the cache kept on disk.

See :mod:`lkspace.knots.keyed` for the keys and what sharing promises.
"""

from __future__ import annotations

import functools
import hashlib
import json
import os
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np

from ..runtime.workers import interruptible
from .design_diagrams import DesignDiagrams
from .identification import NameFields
from .keyed import KEY_VERSION, DesignKeys
from .shipped_keys import ShippedKeys

Key = tuple[int | str, ...]
"""A key: ``(hash, hash)`` at the first level; the second adds the HOMFLY-PT polynomial and crossings; the third is ``("diagram", digest)``."""


@dataclass
class KeyCache:
    """Names found so far by key, shared by the batches of one run (and kept on disk).

    Attributes
    ----------
    named : dict
        Key -> the row fields (``knot_name``, ``split``, ``mirror``, ``crossings``,
        ``jones``, ``status``, ``error``) its designs share.  A first-level key is
        ``(hash, hash)``; a second-level one adds the HOMFLY-PT polynomial and crossings.
    own : set
        Keys whose designs are not named alike (module docstring).
    full : int
        Designs named in full so far.
    path : str or None
        File the trusted keys are appended to and read from (:func:`disk_cache`); keys
        depend on invariants only, so they hold for every scaffold.
    shipped : ShippedKeys
        The file shipped with lkspace (:func:`~lkspace.knots.shipped_keys.shipped_keys`):
        a key's line is read when the key is met and not in :attr:`named` or :attr:`own`.
    stored : dict
        A key's JSON text as :meth:`remember` writes it (``[1, 2]``) -> its line in
        :attr:`path` from earlier runs, read when the key is met (before the shipped file):
        a run parses only the lines of the keys it meets.
    """

    named: dict[Key, NameFields] = field(default_factory=dict)
    own: set[Key] = field(default_factory=set)
    full: int = 0
    path: str | None = None
    shipped: ShippedKeys = field(default_factory=lambda: ShippedKeys(""))
    stored: dict[str, str] = field(default_factory=dict)

    def known(self, key: Key) -> bool:
        """Whether ``key`` was judged (by this run, an earlier one, or the shipped file); moves stored and shipped keys in."""
        if key in self.named or key in self.own:
            return True
        text = self.stored.pop(json.dumps(list(key)), None) or self.shipped.get(key)
        if text is None:
            return False
        try:
            item = json.loads(text)
            if item["fields"] is None:
                self.own.add(key)
            else:
                self.named[key] = NameFields.from_json(item["fields"])
        except (json.JSONDecodeError, KeyError, TypeError, ValueError):
            return False
        return True

    def remember(self, key: Key, fields: NameFields | None) -> None:
        """Trust ``key`` (its designs take ``fields``) or, with ``None``, not; appended to :attr:`path`."""
        if fields is None:
            self.own.add(key)
        else:
            self.named[key] = fields
        if self.path is None:
            return
        line = json.dumps({"key": list(key), "fields": None if fields is None else fields.to_json()}) + "\n"
        try:
            fd = os.open(self.path, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
            try:
                os.write(fd, line.encode())
            finally:
                os.close(fd)
        except OSError:
            self.path = None  # a read-only cache folder: keep the names in memory only


def disk_cache(first: tuple[int, int] | None = None) -> KeyCache:
    """Return a :class:`KeyCache` holding the keys judged by earlier runs, appending new ones.

    The file is ``names-by-key-<KEY_VERSION>-tables-<database_knotinfo version>.jsonl`` under ``$LKSPACE_CACHE``
    (default ``~/.cache/lkspace``); a torn last line (an interrupted run) is skipped.
    Keys it lacks are looked up in the file shipped with lkspace (every table type's key:
    :mod:`lkspace.knots.shipped_keys`).  With ``first`` (a first-level key), only the lines
    of that key and of its second-level keys are read: what one design needs, without
    parsing the whole file.
    """
    try:  # the package's own version(), not importlib.metadata's: tens of milliseconds less per identify
        from database_knotinfo import version

        tables_version = str(version())
    except ImportError:
        tables_version = "none"
    from .shipped_keys import shipped_keys

    root = os.environ.get("LKSPACE_CACHE") or os.path.join(os.path.expanduser("~"), ".cache", "lkspace")
    path = os.path.join(root, f"names-by-key-{KEY_VERSION}-tables-{tables_version}.jsonl")
    cache = KeyCache(path=path, shipped=shipped_keys())
    try:
        os.makedirs(root, exist_ok=True)
        with open(path, encoding="utf-8") as fh:
            mark = None if first is None else f"[{first[0]}, {first[1]}"
            for line in fh:
                if mark is not None and mark not in line:
                    continue
                start, end = line.find("["), line.find('"fields"')
                cache.stored[line[start : line.rfind("]", 0, end) + 1]] = line  # a later line of a key wins
    except OSError:
        pass
    return cache


def candidates(
    jones: tuple[int, list[int]], n_components: int, homfly: str | None = None, crossings: int | None = None
) -> set[tuple[str, bool]]:
    """Table entries ``(name, mirror)`` with this Jones polynomial.

    With ``homfly`` also this HOMFLY-PT polynomial, and with ``crossings`` (of a diagram of
    the link) at most that crossing number.
    """
    from .tables import JONES_POINT, tables

    lowest, coeffs = jones
    x = Fraction(JONES_POINT)
    value = sum((c * x ** (lowest + i) for i, c in enumerate(coeffs)), Fraction(0))
    mirror_value = sum((c * x ** -(lowest + i) for i, c in enumerate(coeffs)), Fraction(0))
    index = tables()
    found = set()
    for mirror, v in ((False, value), (True, mirror_value)):
        for e in index.get(v, []):
            if e.components != n_components or (crossings is not None and e.crossings > crossings):
                continue
            if homfly is None or table_homfly(e.pd, mirror) == homfly:
                found.add((str(e.name), mirror))
    return found


@functools.lru_cache(maxsize=4096)
def table_homfly(pd_text: str | None, mirror: bool) -> str | None:
    """HOMFLY-PT polynomial (regina) of a table entry's PD code, or of its mirror image."""
    from .tables import regina_module

    if not pd_text:
        return None
    regina = regina_module()
    link = regina.Link.fromPD(json.loads(pd_text))
    if mirror:
        link.changeAll()
    return str(interruptible(link.homfly, 2 ** int(link.size())))  # its work: exponential in the crossings


def trusted(named: NameFields, found: set[tuple[str, bool]]) -> bool:
    """Whether every design with a key may take ``named`` (its first design's fields); ``found``: its :func:`candidates`."""
    if named.status.startswith(("unknown: time limit", "unknown: diagram too large")) or named.error:
        return False
    if not found:
        return True  # beyond the tables: the key is all there is to go by (module docstring)
    names = {name for name, _ in found}
    mirrors = {mirror for _, mirror in found}
    return names == {named.knot_name} and (len(mirrors) == 1 or named.mirror is None)


NOT_IN_TABLES = NameFields(
    status="unknown: not in the tables: no KnotInfo knot or LinkInfo link has its invariants (named by key only)"
)
"""What a design takes when naming by key only and its key is new: the shipped file holds the key of every
table type (KnotInfo knots up to 12 crossings, LinkInfo links up to 11, both mirror images), so a new key
proves the design none of them; sums and larger tables are not tried."""


UNDECIDED = NameFields(status="unknown: its invariants do not tell table types apart (named by key only)")
"""What a design takes when naming by key only and neither level of keys decides its type."""

UNKEYED = "unknown: no key: its diagram of {crossings:,} crossings is too wide for the compiled Jones polynomial (named by key only)"
"""The status of a design without a key when naming by key only (it is not named in full)."""


def share_names(
    found: DesignKeys,
    cache: KeyCache,
    name_designs: Callable[[list[int]], Iterable[NameFields]],
    by_key: bool = False,
) -> list[NameFields | None]:
    """Row fields of every design of ``found``, shared by key where the key is trusted.

    First level: the compiled key.  Designs of an untrusted key get a second-level key:
    the key, the HOMFLY-PT polynomial of their own diagram and the crossings left by
    simplifying it, trusted when these separate the table entries (a table entry with
    more crossings than the design's simplified diagram is not the design's type).  ``name_designs(indices)`` names designs in
    full (in worker processes, under the time limit): once per new key, then each design
    of a key trusted at neither level, whose name is kept by its own diagram (the PD code
    the template gives it, the same in every run: :func:`_diagram_key`).  Each name is
    kept (:meth:`KeyCache.remember`) as it comes: an interrupted run keeps what it named.

    ``by_key``: name by key only, never in full (names kept in memory, not on disk).  A
    new first-level key, or a new second-level one whose HOMFLY-PT polynomial no table
    entry with its Jones polynomial shares, is no table type: :data:`NOT_IN_TABLES`.  A
    new second-level key that table entries share lists them (``candidates``); designs
    the keys leave undecided take :data:`UNDECIDED` (:data:`UNKEYED` without a key).
    """
    first: list[Key | None] = [
        (int(a), int(b)) if ok else None for (a, b), ok in zip(found.keys.tolist(), found.keyed, strict=True)
    ]
    diagrams = DesignDiagrams(found)
    rows = _share(diagrams, first, cache, name_designs, second=False, by_key=by_key)
    left = [d for d, row in enumerate(rows) if row is None]
    diagrams.prepare(left)
    second: list[Key | None] = [None] * len(rows)
    for d in left:
        key = first[d]
        invariants = diagrams.homfly(d) if key is not None else None
        if key is not None and invariants is not None:
            second[d] = (*key, *invariants)
    for d, row in enumerate(_share(diagrams, second, cache, name_designs, second=True, by_key=by_key)):
        if rows[d] is None:
            rows[d] = row
    own: dict[int, Key] = {}
    for d in left:
        if rows[d] is None and by_key:
            unkeyed = first[d] is None
            rows[d] = NameFields.refused(UNKEYED.format(crossings=int(found.crossings[d]))) if unkeyed else UNDECIDED
        elif rows[d] is None:
            pd, n_comp, _ = diagrams.diagram(d)
            mine = _diagram_key(pd, n_comp)
            if cache.known(mine) and mine in cache.named:
                rows[d] = cache.named[mine]
            else:
                own[d] = mine
    for (d, mine), named in zip(own.items(), name_designs(list(own)), strict=True):
        cache.full += 1
        rows[d] = named
        if not named.error:
            cache.remember(mine, named)
    return rows


def _diagram_key(pd: list[list[int]], n_components: int) -> Key:
    """Return the third-level key: a design's own diagram (its PD code's digest), named once whichever run meets it again."""
    digest = hashlib.blake2b(json.dumps([pd, n_components]).encode(), digest_size=16).hexdigest()
    return ("diagram", digest)


def _share(
    diagrams: DesignDiagrams,
    keys: list[Key | None],
    cache: KeyCache,
    name_designs: Callable[[list[int]], Iterable[NameFields]],
    second: bool,
    by_key: bool = False,
) -> list[NameFields | None]:
    """One level of :func:`share_names`: name each new key's first design, share the trusted keys' names."""
    rows: list[NameFields | None] = [None] * len(keys)
    firsts: dict[Key, int] = {}
    for d, k in enumerate(keys):
        if k is not None and k not in firsts and not cache.known(k):
            if by_key:
                cache.named[k] = _by_key(diagrams, d, k, second)
            else:
                firsts[k] = d
    for (k, d), named in zip(firsts.items(), name_designs(list(firsts.values())), strict=True):
        cache.full += 1
        rows[d] = named
        pd, n_comp, signs = diagrams.diagram(d)
        jones = jones_of(pd, signs, n_comp)
        homfly, crossings = (str(k[2]), int(k[3])) if second else (None, None)
        if jones is not None and trusted(named, candidates(jones, n_comp, homfly, crossings)):
            cache.remember(k, named)
        elif jones is not None:
            cache.remember(k, None)
        else:
            cache.own.add(k)
    shared = [(d, cache.named[k]) for d, k in enumerate(keys) if rows[d] is None and k is not None and k in cache.named]
    if not second:
        diagrams.prepare([d for d, named in shared if diagrams.told(d, named) is None])
    for d, named in shared:
        if second or diagrams.reaches_crossing_number(d, named):
            rows[d] = named
    return rows


def _by_key(diagrams: DesignDiagrams, d: int, key: Key, second: bool) -> NameFields:
    """Fields of a new key named by key only (``d``: its first design): no table type, or the table entries it matches."""
    if not second:
        return NOT_IN_TABLES
    pd, n_comp, signs = diagrams.diagram(d)
    jones = jones_of(pd, signs, n_comp)
    if jones is None:
        return UNDECIDED
    found_entries = candidates(jones, n_comp, str(key[2]), int(key[3]))
    if not found_entries:
        return NOT_IN_TABLES
    names = tuple(sorted(name + (" (mirror)" if mirror else "") for name, mirror in found_entries))
    return NameFields(
        status=f"unknown: its invariants match {', '.join(names[:4])} (named by key only)", candidates=names
    )


def jones_of(pd: list[list[int]], signs: np.ndarray, n_components: int) -> tuple[int, list[int]] | None:
    """Return the Jones polynomial of a PD code (lowest exponent of ``x = sqrt(t)``, coefficients); ``None`` if too wide."""
    from .jones import jones

    try:
        lowest, coeffs = jones(pd, signs, n_components)
    except ValueError:
        return None
    return int(lowest), list(coeffs)
