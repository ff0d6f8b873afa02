"""The KnotInfo / LinkInfo tables (``database_knotinfo``), indexed by Jones value, cached on disk.

Each entry's Jones polynomial is evaluated exactly at ``sqrt(t) = 2/3``; the index maps
that value to the table entries (and mirrors) sharing it.  Building the index takes
seconds (15-20 s on a busy machine), so lkspace ships it for one table version
(``lkspace/data/knot-tables.pickle.xz``, :data:`SHIPPED_TABLES`, written by
``experiments/build_key_names.py``) and pickles it to ``~/.cache/lkspace`` for others.
"""

from __future__ import annotations

import json
import lzma
import os
import pickle
from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache
from types import ModuleType
from typing import Any

from ..errors import MissingDependencyError, require
from ..io.atomic import write_bytes
from ..runtime.workers import kept_interrupt_handler

PURPOSE = "knot identification"
HOMFLY_MAX_CROSSINGS = 40  # HOMFLY-PT (regina) of larger simplified diagrams is skipped
JONES_POINT = Fraction(2, 3)


@dataclass(frozen=True)
class TableEntry:
    """One KnotInfo or LinkInfo entry (a link once per orientation LinkInfo lists).

    ``name``: identify's name (LinkInfo's without its orientation, ``L4a1``);
    ``table_name``: the table's own (``L4a1{1}``); ``pd``: the PD code as JSON text
    (``None`` where the table has none); ``fp``: the Jones polynomial at
    ``sqrt t =`` :data:`JONES_POINT`; ``volume``: hyperbolic volume, ``None`` if blank.
    """

    name: str
    table_name: str
    components: int
    pd: str | None
    fp: Fraction
    crossings: int
    volume: float | None

    def pd_code(self) -> list[list[int]]:
        """Return the PD code (every entry of the current tables has one)."""
        if self.pd is None:
            raise ValueError(f"table entry {self.table_name} has no PD code")
        code: list[list[int]] = json.loads(self.pd)
        return code


def knot_modules() -> tuple[ModuleType, ModuleType, ModuleType]:
    """Return the modules spherogram, regina and database_knotinfo (after checking snappy too).

    Raises :class:`~lkspace.errors.MissingDependencyError` naming the extra ``[knots]`` when one is missing.
    Ctrl-C keeps the handler it had before SnapPy was imported
    (:func:`~lkspace.runtime.workers.kept_interrupt_handler`).
    """
    with kept_interrupt_handler():
        spherogram = require("spherogram", "knots", PURPOSE)
        regina = require("regina", "knots", PURPOSE)
        require("snappy", "knots", PURPOSE)
        dki = require("database_knotinfo", "knots", PURPOSE)
    return spherogram, regina, dki


def regina_module() -> ModuleType:
    """Return regina alone (for a simplification or a HOMFLY-PT polynomial: SnapPy's import is not needed)."""
    return require("regina", "knots", PURPOSE)


def check_knot_modules() -> None:
    """Raise what :func:`knot_modules` would when one of its modules is not installed, without importing any.

    For a design named from the key cache, which needs none of them (a check of
    milliseconds, where importing them takes a second).
    """
    import importlib.util
    import sys

    for name in ("spherogram", "regina", "snappy", "database_knotinfo"):
        loaded = sys.modules.get(name, False)
        if loaded is None or (loaded is False and importlib.util.find_spec(name) is None):
            raise MissingDependencyError(name, "knots", PURPOSE)


def _eval_table(poly: str, var: str, x: Fraction) -> Fraction | None:
    value = x * x if var == "t" else x
    try:
        return Fraction(eval(poly.replace("^", "**"), {"__builtins__": {}}, {var: value}))  # noqa: S307
    except Exception:  # noqa: BLE001 - a few table entries are blank
        return None


def laurent_value(laurent: Any, x: Fraction) -> Fraction:
    """Return the exact value of a regina ``Laurent`` (in ``sqrt(t)``) at ``x``."""
    total = Fraction(0)
    if laurent.isZero():
        return total
    for e in range(laurent.minExp(), laurent.maxExp() + 1):
        c = int(str(laurent[e]))
        if c:
            total += c * x**e
    return total


SHIPPED_TABLES = os.path.join(os.path.dirname(os.path.dirname(__file__)), "data", "knot-tables.pickle.xz")
"""The index shipped with lkspace: ``(database_knotinfo version, index)`` pickled, xz-compressed."""


def shipped_tables(version: str) -> dict[Fraction, list[TableEntry]] | None:
    """Return the shipped index when it was built from tables ``version``, else ``None``."""
    try:
        with lzma.open(SHIPPED_TABLES, "rb") as fh:
            built, index = pickle.load(fh)
    except Exception:  # noqa: BLE001 - a missing or broken file: build the index
        return None
    return index if built == version and isinstance(index, dict) else None


def _cache_path(version: str) -> str:

    root = os.environ.get("LKSPACE_CACHE") or os.path.join(os.path.expanduser("~"), ".cache", "lkspace")
    return os.path.join(root, f"knot-tables-{version}-v2.pickle")


@lru_cache(maxsize=1)
def tables() -> dict[Fraction, list[TableEntry]]:
    """Jones fingerprints of the KnotInfo and LinkInfo tables: ``{value: [entry, ...]}``.

    The shipped index (:data:`SHIPPED_TABLES`) when the installed ``database_knotinfo``
    is the version it was built from; else built once from ``database_knotinfo`` and kept
    in a pickle under ``$LKSPACE_CACHE`` (default ``~/.cache/lkspace``), keyed by the
    database version.
    """
    _, _, dki = knot_modules()
    version = str(getattr(dki, "version", lambda: "0")())
    path = _cache_path(version)
    if os.path.exists(path):
        try:
            with open(path, "rb") as fh:
                return pickle.load(fh)
        except Exception:  # noqa: BLE001 - a broken cache is rebuilt
            pass
    shipped = shipped_tables(version)
    if shipped is not None:
        return shipped
    index = build_tables(dki)
    try:
        os.makedirs(os.path.dirname(path), exist_ok=True)
        write_bytes(path, pickle.dumps(index, protocol=pickle.HIGHEST_PROTOCOL))
    except OSError:
        pass
    return index


def build_tables(dki: ModuleType) -> dict[Fraction, list[TableEntry]]:
    """Return the index :func:`tables` keeps, read from the module ``database_knotinfo`` (seconds)."""
    index: dict[Fraction, list[TableEntry]] = {}

    def add(entry: TableEntry) -> None:
        index.setdefault(entry.fp, []).append(entry)

    for row in dki.link_list():
        name = row.get("name")
        if not name or name == "Name" or not row.get("jones_polynomial"):
            continue
        fp = _eval_table(row["jones_polynomial"], "t", JONES_POINT)
        if fp is None:
            continue
        add(
            TableEntry(
                name=name,
                table_name=name,
                components=1,
                pd=row.get("pd_notation"),
                fp=fp,
                crossings=int(row.get("crossing_number") or 0),
                volume=_float(row.get("volume")),
            )
        )
    for row in dki.link_list(proper_links=True):
        name = row.get("name")
        if not name or name == "Name" or not row.get("jones_polynomial"):
            continue
        fp = _eval_table(row["jones_polynomial"], "x", JONES_POINT)
        if fp is None:
            continue
        pd = row.get("pd_notation_vector")
        add(
            TableEntry(
                name=name.split("{")[0],
                table_name=name,
                components=int(row.get("components") or 0),
                pd=pd.replace("{", "[").replace("}", "]") if pd else None,
                fp=fp,
                crossings=int(row.get("crossing_number") or 0),
                volume=_float(row.get("volume")),
            )
        )
    return index


def _float(text: Any) -> float | None:
    try:
        return float(text)
    except (TypeError, ValueError):
        return None
