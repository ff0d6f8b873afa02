"""Strict checks on the values of a parsed JSON file, each error naming the field.

JSON has no integer type of its own and Python's ``bool`` is an ``int``: these checks
accept ``true`` nowhere a number is expected, refuse integers past the bounds the model
can hold, and say where a value of the wrong type sits (``cube.json: faces[3][1]``).
"""

from __future__ import annotations

import math
from typing import Any

from ..errors import ScaffoldError
from ..model.validation import MAX_COORDINATE

MAX_INDEX = 2**40
"""Largest vertex, face or side index (and lattice offset magnitude) read from a file."""


def shown(value: Any) -> str:
    """Return a short text of ``value`` for a message (long values cut)."""
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def integer(value: Any, where: str, low: int = -MAX_INDEX, high: int = MAX_INDEX) -> int:
    """Return ``value`` if it is an integer (not a bool) in ``low..high``."""
    if isinstance(value, bool) or not isinstance(value, int):
        raise ScaffoldError(f"{where}: expected an integer, got {shown(value)}")
    if not low <= value <= high:
        raise ScaffoldError(f"{where}: {shown(value)} out of range {low}..{high}")
    return value


def array(value: Any, where: str, length: int | None = None) -> list[Any]:
    """Return ``value`` if it is a list (of ``length`` entries, if given)."""
    if not isinstance(value, list):
        raise ScaffoldError(f"{where}: expected a list, got {type(value).__name__} {shown(value)}")
    if length is not None and len(value) != length:
        raise ScaffoldError(f"{where}: expected {length} entries, got {len(value)}")
    return value


def number(value: Any, where: str) -> float:
    """Return ``value`` as a float if it is a finite number within ``MAX_COORDINATE``."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ScaffoldError(f"{where}: expected a number, got {shown(value)}")
    if isinstance(value, int) and abs(value) > MAX_COORDINATE:
        raise ScaffoldError(f"{where}: {shown(value)} is past the bound +-{MAX_COORDINATE:g}")
    x = float(value)
    if not math.isfinite(x) or abs(x) > MAX_COORDINATE:
        raise ScaffoldError(f"{where}: {shown(value)} is not a finite number within +-{MAX_COORDINATE:g}")
    return x


def point(value: Any, where: str) -> list[float]:
    """Return a list of 3 coordinates."""
    return [number(x, where) for x in array(value, where, 3)]


def vectors(value: Any, where: str) -> list[list[float]]:
    """Return 2 or 3 lattice basis vectors of 3 numbers each."""
    rows = array(value, where)
    if len(rows) not in (2, 3):
        raise ScaffoldError(f"{where}: expected 2 or 3 basis vectors, got {len(rows)}")
    return [point(v, f"{where}[{i}]") for i, v in enumerate(rows)]


def text(value: Any, where: str) -> str:
    """Return ``value`` if it is a string."""
    if not isinstance(value, str):
        raise ScaffoldError(f"{where}: expected a string, got {shown(value)}")
    return value
