"""The key -> name file shipped with lkspace: every table type's key, so that a first run names them at once.

``lkspace/data/names-by-key.jsonl.xz`` (built by ``experiments/build_key_names.py`` from
:func:`lkspace.knots.table_keys.table_keys`) holds a JSON header, then one line per key:
``{"key": [hash, hash], "fields": {...} or null}``, as the disk cache
(:class:`~lkspace.knots.key_names.KeyCache`) writes them.  A file written for another
:data:`~lkspace.knots.keyed.KEY_VERSION` is ignored.  Lines are kept as text and read
when their key is met (a run meets a few hundred of the file's keys).
"""

from __future__ import annotations

import functools
import json
import lzma
import os

from .keyed import KEY_VERSION

SHIPPED = os.path.join(os.path.dirname(os.path.dirname(__file__)), "data", "names-by-key.jsonl.xz")
"""Path of the shipped file."""

_SPLIT = '],"fields":'


@functools.lru_cache(maxsize=1)
def shipped_lines() -> dict[tuple[int | str, ...], str]:
    """Return ``{key: its JSON line}`` of the shipped file (``{}`` when missing or of another key version)."""
    try:
        with lzma.open(SHIPPED, "rt", encoding="utf-8") as fh:
            text = fh.read()
    except (OSError, lzma.LZMAError, EOFError):
        return {}
    lines = text.splitlines()
    try:
        header = json.loads(lines[0])
    except (IndexError, json.JSONDecodeError):
        return {}
    if not isinstance(header, dict) or header.get("key_version") != KEY_VERSION:
        return {}
    out: dict[tuple[int | str, ...], str] = {}
    for item in lines[1:]:
        end = item.find(_SPLIT)
        try:
            key = json.loads(item[7 : end + 1])  # the list after '{"key":'
        except json.JSONDecodeError:
            continue
        if isinstance(key, list):
            out[tuple(key)] = item
    return out
