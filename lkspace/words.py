"""Words for people: counts with the right plural, and measured floats rounded for reading."""

from __future__ import annotations

from typing import Any


def plural(n: int, word: str, many: str | None = None) -> str:
    """Return ``"1 component"`` or ``"3 components"`` (``many``: an irregular plural).

    Examples
    --------
    >>> plural(1, "component"), plural(3, "component"), plural(2, "face set", "face sets")
    ('1 component', '3 components', '2 face sets')
    """
    return f"{n:,} {noun(n, word, many)}"


def noun(n: float, word: str, many: str | None = None) -> str:
    """Return ``word`` for one of it and its plural for any other count (``many``: an irregular plural).

    >>> noun(1, "key"), noun(2, "key"), noun(0.5, "turn")
    ('key', 'keys', 'turns')
    """
    return word if n == 1 else (many or word + "s")


def rounded(value: Any, digits: int = 12) -> Any:
    """Return ``value`` with every float rounded to ``digits`` significant digits (lists, dicts inside).

    Measured values such as ``0.041999999999999996`` come out as ``0.042``; integers, strings
    and other values pass through unchanged.

    >>> rounded({"gap": 0.041999999999999996, "n": [1, 0.30000000000000004]})
    {'gap': 0.042, 'n': [1, 0.3]}
    """
    if isinstance(value, float):
        return float(f"{value:.{digits}g}")
    if isinstance(value, dict):
        return {k: rounded(v, digits) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [rounded(v, digits) for v in value]
    return value
