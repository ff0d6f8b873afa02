"""Reading and writing scaffold files by extension: ``.obj`` and ``.json``."""

from __future__ import annotations

import os
import warnings

from numpy.typing import ArrayLike

from ..errors import LkspaceWarning, ScaffoldError
from ..model.scaffold import Scaffold
from .atomic import write_text
from .obj import format_obj, read_obj
from .paths import input_file
from .scaffold_json import format_scaffold_json, read_scaffold_json
from .weld import weld as weld_scaffold

READERS = {".obj": read_obj, ".json": read_scaffold_json}
"""Readers by lower-case extension."""


def read(path: str | os.PathLike[str], weld: float | bool | None = None) -> Scaffold:
    """Read a scaffold from ``.obj`` or ``.json`` (the lkspace scaffold file).

    ``weld``: merge vertices closer than this tolerance (``True``: the default, see
    :mod:`lkspace.io.weld`).  A file whose faces share no edge at all gets a
    :class:`~lkspace.errors.LkspaceWarning` suggesting ``--weld``.
    """
    ext = os.path.splitext(str(path))[1].lower()
    if ext not in READERS:
        raise ScaffoldError(f"{path}: unknown file type {ext!r}; expected .obj or .json")
    input_file(path, "scaffold")
    if ext == ".obj":
        scaffold = read_obj(path, weld)
    else:
        scaffold = read_scaffold_json(path)
        if weld is not None and weld is not False:
            tol = None if weld is True else float(weld)
            try:
                scaffold = weld_scaffold(scaffold, tol)
            except ScaffoldError as exc:
                raise ScaffoldError(f"{os.path.basename(str(path))}: {exc}", usage=exc.exit_code == 2) from None
    if scaffold.n_faces > 1 and scaffold.edge_degrees.max() == 1 and not weld:
        warnings.warn(
            f"{os.path.basename(str(path))}: its {scaffold.n_faces} faces share no edge, so every face traces "
            "on its own; if the file has one vertex copy per face, load it with `weld`",
            LkspaceWarning,
            stacklevel=2,
        )
    return scaffold


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
