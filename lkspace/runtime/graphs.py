"""igraph, imported without matplotlib: lkspace never draws with igraph (:func:`igraph_module`)."""

from __future__ import annotations

import sys
import threading
from importlib.machinery import ModuleSpec
from types import ModuleType
from typing import Any

_IMPORTING = threading.Lock()


class _NoMatplotlibInThisThread:
    """A finder that refuses ``matplotlib`` to one thread (other threads import it as usual)."""

    def __init__(self) -> None:
        self.thread = threading.get_ident()

    def find_spec(self, name: str, path: Any = None, target: Any = None) -> ModuleSpec | None:
        """Refuse ``matplotlib`` in the importing thread; leave every other name to the next finders."""
        if name == "matplotlib" and threading.get_ident() == self.thread:
            raise ModuleNotFoundError("matplotlib is left out of igraph's import", name=name)
        return None


def igraph_module() -> ModuleType:
    """Return the igraph module, imported the first time with matplotlib kept out unless already loaded.

    igraph's drawing package imports ``matplotlib.pyplot`` whenever matplotlib is
    installed: 0.39 s of igraph's 0.43 s import in a fresh process.  While igraph
    imports, matplotlib is refused to the importing thread, so igraph puts stand-ins in
    its place, which only its drawing functions use; matplotlib imports as usual
    afterwards, and in other threads meanwhile.
    """
    module = sys.modules.get("igraph")
    if module is not None:
        return module
    with _IMPORTING:
        refuse = None if "matplotlib" in sys.modules else _NoMatplotlibInThisThread()
        if refuse is not None:
            sys.meta_path.insert(0, refuse)
        try:
            import igraph
        finally:
            if refuse is not None:
                sys.meta_path.remove(refuse)
    return igraph
