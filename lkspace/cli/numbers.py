"""Numeric option types that refuse ``nan``, ``inf`` and out-of-range values (exit 2, one line)."""

from __future__ import annotations

import math

import click


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
            number = float(value)  # type: ignore[arg-type]
        except (TypeError, ValueError):
            self.fail(f"{value!r} is not a number; expected {self.describe()}", param, ctx)
        below = number <= self.low if self.low_open else number < self.low
        if not math.isfinite(number) or below or number > self.high:
            self.fail(f"{value} is out of range; expected {self.describe()}", param, ctx)
        return number
