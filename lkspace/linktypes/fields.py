"""Reading JSON fields for the wire records (:mod:`~lkspace.linktypes.records`, :mod:`~lkspace.linktypes.answers`).

Each reader returns the field if it has the type asked for and raises
:class:`~lkspace.errors.CatalogError` naming the record, the field and what arrived
otherwise (``bool`` is never an ``int`` here).  Lists are checked at C speed: an atlas
index holds ~10^4 label lists.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import cast

from ..errors import CatalogError
from ..io.json_values import Json as Json
from ..io.json_values import JsonObject as JsonObject
from .spelling import CHIRALITIES, Chirality


def get_field(data: Mapping[str, object], key: str, where: str) -> object:
    """Return ``data[key]``, or raise: no such field."""
    if key not in data:
        raise CatalogError(f"{where}: no field {key!r}")
    return data[key]


def wrong(where: str, key: str, value: object, want: str) -> CatalogError:
    """Return the error for a field of the wrong type."""
    return CatalogError(f"{where}: field {key!r} is {value!r}, expected {want}")


def read_int(data: Mapping[str, object], key: str, where: str) -> int:
    """Return an integer field."""
    value = get_field(data, key, where)
    if isinstance(value, int) and not isinstance(value, bool):
        return value
    raise wrong(where, key, value, "an integer")


def read_opt_int(data: Mapping[str, object], key: str, where: str) -> int | None:
    """Return an integer field that may be null."""
    return None if get_field(data, key, where) is None else read_int(data, key, where)


def read_float(data: Mapping[str, object], key: str, where: str) -> float:
    """Return a number field (an integer is a number too)."""
    value = get_field(data, key, where)
    if isinstance(value, int | float) and not isinstance(value, bool):
        return float(value)
    raise wrong(where, key, value, "a number")


def read_str(data: Mapping[str, object], key: str, where: str) -> str:
    """Return a string field."""
    value = get_field(data, key, where)
    if isinstance(value, str):
        return value
    raise wrong(where, key, value, "a string")


def read_opt_str(data: Mapping[str, object], key: str, where: str) -> str | None:
    """Return a string field that may be null."""
    return None if get_field(data, key, where) is None else read_str(data, key, where)


def read_bool(data: Mapping[str, object], key: str, where: str) -> bool:
    """Return a true/false field."""
    value = get_field(data, key, where)
    if isinstance(value, bool):
        return value
    raise wrong(where, key, value, "true or false")


def read_opt_bool(data: Mapping[str, object], key: str, where: str) -> bool | None:
    """Return a true/false field that may be null."""
    return None if get_field(data, key, where) is None else read_bool(data, key, where)


def read_list(data: Mapping[str, object], key: str, where: str) -> list[object]:
    """Return a list field."""
    value = get_field(data, key, where)
    if isinstance(value, list | tuple):
        return list(value)
    raise wrong(where, key, value, "a list")


def read_ints(data: Mapping[str, object], key: str, where: str) -> tuple[int, ...]:
    """Return a list of integers."""
    values = read_list(data, key, where)
    if not set(map(type, values)) <= {int}:  # exactly int: no bool (C speed: an atlas holds ~10^4 label lists)
        raise wrong(where, key, values, "a list of integers")
    return tuple(cast(list[int], values))


def read_strs(data: Mapping[str, object], key: str, where: str) -> tuple[str, ...]:
    """Return a list of strings."""
    values = read_list(data, key, where)
    if not set(map(type, values)) <= {str}:
        raise wrong(where, key, values, "a list of strings")
    return tuple(cast(list[str], values))


def as_object(value: object, where: str) -> Mapping[str, object]:
    """Return ``value`` as a JSON object, or raise."""
    if isinstance(value, Mapping) and set(map(type, value)) <= {str}:
        return cast(Mapping[str, object], value)
    raise CatalogError(f"{where}: {value!r} is no JSON object")


def read_chirality(text: str, where: str) -> Chirality:
    """Return ``text`` as a :data:`~lkspace.linktypes.spelling.Chirality`, or raise."""
    for side in CHIRALITIES:
        if text == side:
            return side
    raise wrong(where, "chirality", text, " or ".join(CHIRALITIES))
