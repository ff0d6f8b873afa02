"""Compiled kernels that cost nothing until they are needed.

A kernel is a plain Python function written in numba's nopython subset (numpy arrays,
scalars, loops; no calls to other kernels).  :func:`kernel` wraps it in a
:class:`Kernel`: calling the wrapper runs the numba-compiled version, importing numba and
compiling (or loading numba's on-disk cache) on first use only, so commands that never
reach a hot loop never pay numba's import.  :meth:`Kernel.run` takes the size of the job
and runs the plain Python function when the job is too small for compilation to pay
(a trace of a small scaffold), the compiled one otherwise.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

SMALL_WORK = 4096
"""Jobs below this many elementary steps run as plain Python (about 10 ms at most)."""


class Kernel:
    """A numba kernel compiled on first use; see the module docstring."""

    def __init__(self, py_func: Callable[..., Any]) -> None:
        self.py_func = py_func
        self.__doc__ = py_func.__doc__
        self.__name__ = py_func.__name__
        self._compiled: Callable[..., Any] | None = None

    @property
    def compiled(self) -> Callable[..., Any]:
        """The numba dispatcher (``cache=True``: compiled once per machine)."""
        if self._compiled is None:
            import numba

            self._compiled = numba.njit(cache=True)(self.py_func)
        return self._compiled

    def __call__(self, *args: Any) -> Any:
        """Run the compiled kernel on ``args`` (compiling it first if needed)."""
        return self.compiled(*args)

    def run(self, work: int, *args: Any) -> Any:
        """Run on ``args``: as plain Python when ``work < SMALL_WORK``, else compiled."""
        if work < SMALL_WORK and self._compiled is None:
            return self.py_func(*args)
        return self.compiled(*args)

    def __repr__(self) -> str:
        state = "compiled" if self._compiled is not None else "not compiled yet"
        return f"<kernel {self.__name__} ({state})>"


def kernel(py_func: Callable[..., Any]) -> Kernel:
    """Wrap ``py_func`` in a :class:`Kernel` (use as a decorator)."""
    return Kernel(py_func)
