"""Reading and writing scaffold files by extension: ``.obj`` and ``.json``."""

from __future__ import annotations

import os

from numpy.typing import ArrayLike

from ..errors import ScaffoldError
from ..model.scaffold import Scaffold
from .atomic import write_text
from .obj import format_obj, read_obj
from .scaffold_json import format_scaffold_json, read_scaffold_json

READERS = {".obj": read_obj, ".json": read_scaffold_json}


def read(path: str | os.PathLike[str]) -> Scaffold:
    """Read a scaffold from ``.obj`` or ``.json`` (the lkspace scaffold file)."""
    ext = os.path.splitext(str(path))[1].lower()
    if ext not in READERS:
        raise ScaffoldError(f"{path}: unknown file type {ext!r}; expected .obj or .json")
    if not os.path.exists(path):
        raise ScaffoldError(f"{path}: no such file")
    return READERS[ext](path)


def write(
    scaffold: Scaffold, path: str | os.PathLike[str], labels: ArrayLike | None = None, nulls: ArrayLike | None = None
) -> None:
    """Write ``scaffold`` to ``.obj`` or ``.json`` atomically."""
    ext = os.path.splitext(str(path))[1].lower()
    if ext == ".obj":
        text = format_obj(scaffold)
    elif ext == ".json":
        text = format_scaffold_json(scaffold, labels, nulls)
    else:
        raise ScaffoldError(f"{path}: unknown file type {ext!r}; expected .obj or .json")
    try:
        write_text(path, text)
    except OSError as exc:
        raise ScaffoldError(f"{path}: cannot write: {exc}") from None
