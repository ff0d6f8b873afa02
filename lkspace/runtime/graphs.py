"""igraph, imported without matplotlib: lkspace never draws with igraph (:func:`igraph_module`)."""

from __future__ import annotations

import sys
import threading
from types import ModuleType

_IMPORTING = threading.Lock()


def igraph_module() -> ModuleType:
    """Return the igraph module, imported the first time with matplotlib kept out unless already loaded.

    igraph's drawing package imports ``matplotlib.pyplot`` whenever matplotlib is
    installed: 0.39 s of igraph's 0.43 s import in a fresh process.  With matplotlib
    marked missing during the import, igraph puts stand-ins in its place, which only its
    drawing functions use; matplotlib itself imports as usual afterwards.
    """
    module = sys.modules.get("igraph")
    if module is not None:
        return module
    with _IMPORTING:
        hidden = "matplotlib" not in sys.modules
        if hidden:
            sys.modules["matplotlib"] = None  # type: ignore[assignment]  # an import of it raises ImportError
        try:
            import igraph
        finally:
            if hidden and "matplotlib" in sys.modules and sys.modules["matplotlib"] is None:
                del sys.modules["matplotlib"]
    return igraph
