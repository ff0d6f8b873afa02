"""Reading the text files lkspace takes as input: OBJ, scaffold files, twist files.

Every input is checked to be a regular file first (:func:`~lkspace.io.paths.input_file`:
a FIFO or a device would block), read as bytes, stripped of a UTF-8 byte-order mark and
decoded as UTF-8; bytes that are not UTF-8 are an error naming the file, the line and
the byte offset.  A file past :data:`MAX_INPUT_BYTES` is refused before it is read.  JSON nested past :data:`MAX_JSON_DEPTH` is refused before parsing.
"""

from __future__ import annotations

import json
import os
import re
from typing import Any

from ..errors import LkspaceError, ScaffoldError
from .paths import input_file

BOM = b"\xef\xbb\xbf"

MAX_INPUT_BYTES = 64 * 2**20
"""Largest input text file read (64 MiB): an OBJ takes about 35 times its size in memory while read
(a 5 MB grid of 90,000 quads: 180 MB), so this bounds a read at about 2 GB; past it, before any byte
is read, a one-line refusal (a sparse 10 GB file had been read until the machine ran out of memory)."""

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
            size = os.fstat(fh.fileno()).st_size
            if size > MAX_INPUT_BYTES:
                raise error(
                    f"{text}: {size / 2**20:,.0f} MiB is past the {MAX_INPUT_BYTES // 2**20} MiB lkspace reads "
                    f"as {what} input; use a smaller file (a mesh this large has millions of faces: decimate it)"
                )
            data = fh.read(MAX_INPUT_BYTES + 1)  # a file grown since: still no more than this
    except OSError as exc:
        raise error(f"{text}: cannot read {what}: {exc.strerror or exc}") from None
    if len(data) > MAX_INPUT_BYTES:
        raise error(f"{text}: grew past the {MAX_INPUT_BYTES // 2**20} MiB lkspace reads as {what} input while read")
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
