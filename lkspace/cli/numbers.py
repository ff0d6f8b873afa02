"""Numeric option types that refuse ``nan``, ``inf`` and out-of-range values (exit 2, one line).

Both take numbers written as the help shows them: ASCII digits, no ``_`` separators (Python's
``int`` and ``float`` read ``١`` as 1 and ``1_000`` as 1000, which a flag should not do silently).
"""

from __future__ import annotations

import math
import re

import click

_SPELLED = re.compile(r"\s*[+-]?[0-9a-zA-Z.]+(?:[+-][0-9]+)?\s*")  # 1e-3: a signed exponent
"""How a number given on the command line is spelled (``int``/``float`` then read its value)."""


def plainly_spelled(value: object) -> bool:
    """Whether ``value`` (a string from the command line, or a value already converted) spells a number plainly."""
    return not isinstance(value, str) or (value.isascii() and _SPELLED.fullmatch(value) is not None)


class Count(click.IntRange):
    """:class:`click.IntRange` that refuses digits other than ASCII's and ``_`` separators."""

    def convert(self, value: object, param: click.Parameter | None, ctx: click.Context | None) -> int:
        """Return ``value`` as an int in range, or fail naming the option."""
        if not plainly_spelled(value):
            self.fail(f"{value!r} is not an integer written in digits 0-9", param, ctx)
        return int(super().convert(value, param, ctx))  # type: ignore[arg-type]


class Finite(click.ParamType):
    """A finite float in ``[low, high]`` (``low_open``: ``low`` itself refused); ``nan``/``inf`` refused."""

    name = "float"

    def __init__(self, low: float = -math.inf, high: float = math.inf, low_open: bool = False) -> None:
        self.low, self.high, self.low_open = low, high, low_open

    def describe(self) -> str:
        """Return the accepted range as text, e.g. ``a finite number > 0``."""
        parts = []
        if self.low > -math.inf:
            parts.append(f"{'>' if self.low_open else '>='} {self.low:g}")
        if self.high < math.inf:
            parts.append(f"<= {self.high:g}")
        return "a finite number" + (" " + " and ".join(parts) if parts else "")

    def convert(self, value: object, param: click.Parameter | None, ctx: click.Context | None) -> float:
        """Return ``value`` as a float, or fail naming the option and the accepted range."""
        try:
            if not plainly_spelled(value):
                raise ValueError(value)
            number = float(value)  # type: ignore[arg-type]
        except (TypeError, ValueError):
            self.fail(f"{value!r} is not a number; expected {self.describe()}", param, ctx)
        below = number <= self.low if self.low_open else number < self.low
        if not math.isfinite(number) or below or number > self.high:
            self.fail(f"{value} is out of range; expected {self.describe()}", param, ctx)
        return number
