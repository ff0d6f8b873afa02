"""``EDGE=VALUE`` options of the command line (``--fix``, ``--parity``) shared by ``solve``'s modes."""

from __future__ import annotations

from collections.abc import Callable, Iterable

from ..errors import UsageError
from ..model.scaffold import Scaffold
from ..model.specs import edge_index


def edge_values(
    scaffold: Scaffold, items: Iterable[str], option: str, parse: Callable[[str, str], int]
) -> dict[int, int]:
    """``EDGE=VALUE`` items -> {edge index: parsed value}; an edge named twice is an error."""
    out: dict[int, int] = {}
    for item in items:
        name, eq, value = item.rpartition("=")
        if not eq or not name.strip():
            raise UsageError(
                f"{option} {item!r}: write EDGE=VALUE, e.g. {option} 3-7={'odd' if 'parity' in option else '2'}"
            )
        e = edge_index(scaffold, name)
        if e in out:
            raise UsageError(f"{option}: edge {scaffold.edge_name(e)} given twice")
        out[e] = parse(value.strip(), item)
    return out


MAX_FIX_LABEL = 1_000_000
"""Largest ``|t|`` a ``--fix`` label may have (costs and labels stay far inside 64-bit integers)."""


def fix_label(value: str, item: str) -> int:
    """Parse the label of a ``--fix EDGE=T`` item (within ``MAX_FIX_LABEL``)."""
    try:
        label = int(value)
    except ValueError:
        raise UsageError(f"--fix {item!r}: {value!r} is not an integer label") from None
    if abs(label) > MAX_FIX_LABEL:
        raise UsageError(f"--fix {item!r}: labels must lie in -{MAX_FIX_LABEL:,}..{MAX_FIX_LABEL:,}")
    return label
