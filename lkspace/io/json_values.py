"""JSON values as :func:`json.loads` returns them: the one type of every wire record's ``from_json`` input."""

from __future__ import annotations

from typing import TypeAlias

Json: TypeAlias = "None | bool | int | float | str | list[Json] | dict[str, Json]"
"""A JSON value as :func:`json.loads` returns it."""

JsonObject: TypeAlias = dict[str, Json]
"""A JSON object."""
