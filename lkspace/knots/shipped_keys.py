"""The key -> name file shipped with lkspace: every table type's key, so that a first run names them at once.

``lkspace/data/names-by-key.jsonl.gz`` (built by ``experiments/build_key_names.py`` from
:func:`lkspace.knots.table_keys.table_keys`) holds a JSON header, then one line per key:
``{"key":[...],"fields":{...} or null}`` (compact JSON), as the disk cache
(:class:`~lkspace.knots.key_names.KeyCache`) writes them.  A file written for another
:data:`~lkspace.knots.keyed.KEY_VERSION` is ignored.  The file is gzip (decompressed in
about 15 ms, against 115 ms as xz) and kept as text: the first keys met are found by
searching it (one design meets a few), and only a run that meets more reads every line.
"""

from __future__ import annotations

import functools
import gzip
import json
import os
import zlib

from .keyed import KEY_VERSION

SHIPPED = os.path.join(os.path.dirname(os.path.dirname(__file__)), "data", "names-by-key.jsonl.gz")
"""Path of the shipped file."""

SEARCHED = 16
"""Keys looked up by searching the text; the next lookup reads every line into a dict."""

Key = tuple[int | str, ...]


def line_of(key: Key, fields_json: str) -> str:
    """Return the file's line of ``key`` (``fields_json``: its fields as JSON, or ``null``)."""
    return f'{{"key":{key_text(key)},"fields":{fields_json}}}'


class ShippedKeys:
    """The shipped file's lines by key (``get``): searched in its text for the first keys, then indexed."""

    def __init__(self, text: str) -> None:
        self.text = text
        self.searched = 0
        self._index: dict[str, str] | None = None

    def get(self, key: Key) -> str | None:
        """Return the line of ``key``, or ``None``."""
        if self._index is None and self.searched < SEARCHED:
            self.searched += 1
            start = self.text.find(line_of(key, "")[:-1])
            if start < 0:
                return None
            end = self.text.find("\n", start)
            return self.text[start : end if end >= 0 else len(self.text)]
        return self.index().get(key_text(key))

    def index(self) -> dict[str, str]:
        """Return every line of the file by its key's compact JSON text (:func:`key_text`; no line parsed)."""
        if self._index is None:
            self._index = {}
            for item in self.text.splitlines():
                end = item.find('],"fields":')
                if item.startswith('{"key":[') and end > 0:
                    self._index[item[7 : end + 1]] = item
        return self._index

    def lines(self) -> dict[Key, str]:
        """Return every line of the file by its key (each key parsed: for checks and rebuilds, not lookups)."""
        out: dict[Key, str] = {}
        for text, item in self.index().items():
            try:
                key = json.loads(text)
            except json.JSONDecodeError:
                continue
            if isinstance(key, list):
                out[tuple(key)] = item
        return out


def key_text(key: Key) -> str:
    """Return ``key`` as the compact JSON text the file's lines hold (``[1,2]``)."""
    return json.dumps(list(key), separators=(",", ":"))


@functools.lru_cache(maxsize=1)
def shipped_keys() -> ShippedKeys:
    """Return the shipped file's keys (none when it is missing or of another key version)."""
    try:
        with open(SHIPPED, "rb") as fh:
            text = gzip.decompress(fh.read()).decode("utf-8")
    except (OSError, EOFError, zlib.error, UnicodeDecodeError):
        return ShippedKeys("")
    head, _, body = text.partition("\n")
    try:
        header = json.loads(head)
    except json.JSONDecodeError:
        return ShippedKeys("")
    if not isinstance(header, dict) or header.get("key_version") != KEY_VERSION:
        return ShippedKeys("")
    return ShippedKeys(body)
