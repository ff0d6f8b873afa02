"""lkspace: knots, links and chainmail designed by twist labels on polygon meshes.

Quick start
-----------
>>> import lkspace
>>> s = lkspace.load("tetrahedron")
>>> lkspace.trace(s, 1).components
3
"""

from __future__ import annotations

import os

# ``lkspace.enumerate`` is the function (its module stays importable: ``from lkspace.enumerate import ...``)
from .enumerate import enumerate_designs as enumerate  # noqa: A001
from .errors import LabelError, LkspaceError, MissingDependencyError, ScaffoldError
from .lattice import Lattice
from .mesh import Scaffold
from .solve import solve  # eager: importing lkspace.solve would shadow a lazy wrapper; ortools loads on use
from .tracing import Trace, trace

__version__ = "0.1.0"

__all__ = [
    "load",
    "trace",
    "enumerate",
    "solve",
    "Scaffold",
    "Lattice",
    "Trace",
    "LkspaceError",
    "ScaffoldError",
    "LabelError",
    "MissingDependencyError",
    "__version__",
]


def load(source: str | os.PathLike | Scaffold) -> Scaffold:
    """A scaffold from a built-in name (``"cube"``, ``"book:3"``) or a ``.obj``/``.json`` path."""
    from . import io, scaffolds

    if isinstance(source, Scaffold):
        return source
    text = os.fspath(source)
    if scaffolds.is_builtin_name(text) and not os.path.exists(text):
        return scaffolds.builtin(text)
    if os.path.exists(text) or os.path.splitext(text)[1] or os.sep in text:
        return io.read(text)
    raise ScaffoldError(f"{text!r} is neither a file nor a built-in scaffold name; see 'lkspace scaffold --help'")
