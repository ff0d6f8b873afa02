"""Reading the text files lkspace takes as input: OBJ, scaffold files, twist files.

Every input is checked to be a regular file first (:func:`~lkspace.io.paths.input_file`:
a FIFO or a device would block), read as bytes, stripped of a UTF-8 byte-order mark and
decoded as UTF-8; bytes that are not UTF-8 are an error naming the file, the line and
the byte offset.  JSON nested past :data:`MAX_JSON_DEPTH` is refused before parsing.
"""

from __future__ import annotations

import json
import os
import re
from typing import Any

from ..errors import LkspaceError, ScaffoldError
from .paths import input_file

BOM = b"\xef\xbb\xbf"

MAX_JSON_DEPTH = 64
"""Deepest nesting of ``[`` and ``{`` accepted in an input JSON file (lkspace files need 4)."""

_STRINGS = re.compile(r'"(?:[^"\\]|\\.)*"')


def read_text(path: str | os.PathLike[str], what: str = "input", error: type[LkspaceError] = ScaffoldError) -> str:
    """Return the text of input file ``path`` (``what`` names it in messages); see the module docstring."""
    try:
        text = input_file(path, what)
    except ScaffoldError as exc:
        raise error(str(exc)) from None
    try:
        with open(text, "rb") as fh:
            data = fh.read()
    except OSError as exc:
        raise error(f"{text}: cannot read {what}: {exc.strerror or exc}") from None
    if data.startswith(BOM):
        data = data[len(BOM) :]
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise error(
            f"{os.path.basename(text)} line {line}: byte {exc.start} (0x{data[exc.start]:02x}) is not UTF-8 text"
        ) from None


def json_depth(text: str) -> int:
    """Return the deepest nesting of ``[`` and ``{`` in JSON ``text`` (brackets inside strings not counted)."""
    import numpy as np

    bare = _STRINGS.sub("", text).encode("utf-8", "replace")
    codes = np.frombuffer(bare, np.uint8)
    codes = codes[(codes | 0x20) >= ord("{")]  # "[", "]", "{", "}" (and a few others, dropped next)
    steps = (np.isin(codes, (ord("["), ord("{"))).astype(np.int64)) - np.isin(codes, (ord("]"), ord("}")))
    return int(np.cumsum(steps).max(initial=0))


def parse_json(text: str, name: str, error: type[LkspaceError] = ScaffoldError) -> Any:
    """Parse JSON ``text`` of file ``name``; syntax errors name the line, deep nesting is refused."""
    if text.count("[") + text.count("{") > MAX_JSON_DEPTH and json_depth(text) > MAX_JSON_DEPTH:
        raise error(f"{name}: JSON nested deeper than {MAX_JSON_DEPTH} levels")
    try:
        return json.loads(text)
    except json.JSONDecodeError as exc:
        raise error(f"{name} line {exc.lineno}: invalid JSON: {exc.msg}") from None
    except (RecursionError, ValueError) as exc:  # ValueError: an integer of more than 4300 digits
        raise error(f"{name}: invalid JSON: {' '.join(str(exc).split())[:120]}") from None
