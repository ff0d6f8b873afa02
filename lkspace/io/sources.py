"""Where scaffolds come from: :func:`load` takes a scaffold, a path or a built-in name.

Paths and names are read here, at the boundary: the public functions of lkspace that work
on a scaffold load their first argument once (:mod:`lkspace.api`), so
``lkspace.trace("cube", 1)``, ``lkspace.trace("cube.obj", 1)`` and
``lkspace.trace(scaffold, 1)`` all work, while the computing layers take a
:class:`Scaffold`.

A text that is both a built-in name and the name of a file means the built-in, in every
folder: a file is read when the text has a scaffold extension (``.obj``, ``.json``) or a
path separator (``./cube``), or when it is no built-in name and a file of that name
exists.  A ``pathlib.Path`` (any ``os.PathLike``) is always a file.
"""

from __future__ import annotations

import difflib
import os
from typing import TypeAlias

from .. import scaffolds
from ..errors import ScaffoldError
from ..model.scaffold import Scaffold
from .files import READERS, read

ScaffoldSource: TypeAlias = Scaffold | str | os.PathLike[str]
"""What every public function that works on a scaffold accepts: a scaffold, a built-in name or a path."""


def reads_builtin(text: str) -> bool:
    """Whether :func:`load` reads the text ``text`` as a built-in name (the rule of the module docstring).

    Examples
    --------
    >>> reads_builtin("cube"), reads_builtin("./cube"), reads_builtin("cube.obj"), reads_builtin("my-mesh")
    (True, False, False, False)
    """
    if "/" in text or os.sep in text or os.path.splitext(text)[1].lower() in READERS:
        return False
    return scaffolds.is_builtin_name(text)


def load(source: ScaffoldSource, *, weld: float | bool | None = None) -> Scaffold:
    """Return a scaffold from a :class:`Scaffold` (returned as is), a built-in name or a path.

    Parameters
    ----------
    source : Scaffold, str or os.PathLike
        A built-in name (``"cube"``, ``"book:3"``, ``"honeycomb:cP@2x2x2"``; see
        ``lkspace scaffold --help``) or a ``.obj`` / ``.json`` scaffold file.  A built-in
        name means the built-in even where a file of that name exists: write ``./cube``
        for the file (module docstring).
    weld : float or bool, optional
        Merge vertices of a file closer than this tolerance (``True``: ``1e-6`` times the
        bounding-box diagonal); see :mod:`lkspace.io.weld`.

    Examples
    --------
    >>> load("cube")
    Scaffold(cube: 8 vertices, 12 edges, 6 faces)
    """
    if isinstance(source, Scaffold):
        return source
    if not isinstance(source, (str, os.PathLike)):
        raise ScaffoldError(f"expected a Scaffold, a path or a built-in name, got {type(source).__name__}")
    text = os.fspath(source)
    if isinstance(source, str) and reads_builtin(text):
        if weld is not None and weld is not False:
            raise ScaffoldError(f"{text!r}: `weld` applies to files, not to built-in scaffolds", usage=True)
        return scaffolds.builtin(text)
    if isinstance(source, os.PathLike) or os.path.lexists(text) or os.path.splitext(text)[1] or os.sep in text:
        return read(text, weld)
    names = scaffolds.builtin_names()
    close = difflib.get_close_matches(text, names, n=2, cutoff=0.75)
    hint = f"did you mean {' or '.join(map(repr, close))}?" if close else "the built-in names are " + ", ".join(names)
    raise ScaffoldError(f"{text!r} is neither a file nor a built-in scaffold name; {hint}")
