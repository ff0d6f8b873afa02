"""Where scaffolds come from: :func:`load` takes a scaffold, a path or a built-in name.

Every public function of lkspace that works on a scaffold calls :func:`load` on its
first argument, so ``lkspace.trace("cube", 1)``, ``lkspace.trace("cube.obj", 1)`` and
``lkspace.trace(scaffold, 1)`` all work.
"""

from __future__ import annotations

import os
from typing import TypeAlias

from .. import scaffolds
from ..errors import ScaffoldError
from ..model.scaffold import Scaffold
from .files import read

ScaffoldSource: TypeAlias = Scaffold | str | os.PathLike[str]
"""What every function that works on a scaffold accepts: a scaffold, a built-in name or a path."""


def load(source: ScaffoldSource, *, weld: float | bool | None = None) -> Scaffold:
    """Return a scaffold from a :class:`Scaffold` (returned as is), a built-in name or a path.

    Parameters
    ----------
    source : Scaffold, str or os.PathLike
        A built-in name (``"cube"``, ``"book:3"``, ``"honeycomb:cP@2x2x2"``; see
        ``lkspace scaffold --help``) or a ``.obj`` / ``.json`` scaffold file.  A file of
        that name wins over a built-in name.
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
    if scaffolds.is_builtin_name(text) and not os.path.lexists(text):
        if weld is not None and weld is not False:
            raise ScaffoldError(
                f"{text!r}: weld applies to files, not to built-in scaffolds", usage=True, mentions=("weld",)
            )
        return scaffolds.builtin(text)
    if os.path.lexists(text) or os.path.splitext(text)[1] or os.sep in text:
        return read(text, weld)
    raise ScaffoldError(f"{text!r} is neither a file nor a built-in scaffold name; see 'lkspace scaffold --help'")
