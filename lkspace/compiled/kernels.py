"""Compiled kernels that cost nothing until they are needed, and the helpers they share.

A kernel is a plain Python function written in numba's nopython subset (numpy arrays,
scalars, loops).  :func:`kernel` wraps it in a :class:`Kernel`: calling the wrapper runs
the numba-compiled version, importing numba and compiling (or loading numba's on-disk
cache) on first use only, so commands that never reach a hot loop never pay numba's
import.  :meth:`Kernel.run` takes the size of the job and runs the plain Python function
when the job is too small for compilation to pay (a trace of a small scaffold), the
compiled one otherwise.

Kernels share loops through **helpers**: :func:`helper` registers a function and returns
it unchanged, so a kernel run as plain Python calls the plain helper.  When a kernel is
compiled, each helper its body names is swapped for the helper's own compiled version
(itself compiled the same way, so helpers may call helpers), which numba inlines
(``inline="always"``: no call overhead in inner loops).  A
kernel must name a helper imported into its module (``from .loops import join``), not as
``module.join``.  Numba's cache keys a kernel by its own file only; here the key also
holds the text of the files of every helper the kernel reaches, so editing a helper (or a
constant beside it) in another file recompiles the kernels that use it instead of
loading stale code.  The compiled code of every kernel also ships with lkspace
(:mod:`~lkspace.compiled.shipped`), so a fresh machine loads it instead of compiling.
"""

from __future__ import annotations

import types
from collections.abc import Callable
from typing import Any, Literal, TypeVar

SMALL_WORK = 4096
"""Jobs below this many elementary steps run as plain Python (about 10 ms at most)."""

F = TypeVar("F", bound=Callable[..., Any])

_helpers: dict[Callable[..., Any], Any] = {}
"""Every helper, mapped to its numba dispatcher once one was needed (``None`` before)."""


def helper(py_func: F) -> F:
    """Register ``py_func`` as a helper kernels may call (use as a decorator); return it unchanged."""
    _helpers[py_func] = None
    return py_func


def _is_helper(value: object) -> bool:
    return isinstance(value, types.FunctionType) and value in _helpers


def _helpers_named(py_func: Callable[..., Any]) -> dict[str, Callable[..., Any]]:
    """Return the helpers the body of ``py_func`` names, keyed by the name it uses."""
    names = py_func.__globals__
    return {n: names[n] for n in py_func.__code__.co_names if _is_helper(names.get(n))}


def _reached(py_func: Callable[..., Any]) -> list[Callable[..., Any]]:
    """Return every helper ``py_func`` reaches through calls."""
    seen: dict[str, Callable[..., Any]] = {}
    todo = list(_helpers_named(py_func).values())
    while todo:
        h = todo.pop()
        key = f"{h.__module__}.{h.__qualname__}"
        if key not in seen:
            seen[key] = h
            todo += _helpers_named(h).values()
    return list(seen.values())


def _source(func: Callable[..., Any]) -> bytes:
    """Return the text of the file defining ``func`` (its bytecode where the file is gone)."""
    try:
        with open(func.__code__.co_filename, "rb") as fh:
            return fh.read()
    except OSError:
        return func.__code__.co_code


def _compile(py_func: Callable[..., Any], nogil: bool = False) -> Any:
    """Return the numba dispatcher of ``py_func`` (cached, :mod:`~lkspace.compiled.shipped`), its helpers compiled in.

    ``nogil``: the compiled code runs without Python's lock (threads run it in parallel).
    """
    import hashlib

    from .shipped import cache_class, portable_codegen

    portable_codegen()
    import numba

    named = _helpers_named(py_func)
    inline: Literal["always", "never"] = "always" if py_func in _helpers else "never"  # no calls in inner loops
    namespace = dict(py_func.__globals__)
    for name, h in named.items():
        if _helpers[h] is None:
            _helpers[h] = _compile(h)
        namespace[name] = _helpers[h]
    func = types.FunctionType(py_func.__code__, namespace, py_func.__name__, py_func.__defaults__, py_func.__closure__)
    func.__qualname__ = py_func.__qualname__
    func.__doc__ = py_func.__doc__
    dispatcher = numba.njit(cache=True, inline=inline, nogil=nogil)(func)
    files = {h.__code__.co_filename: h for h in _reached(py_func)}
    flags = [b"nogil"] if nogil else []  # numba's cache key omits it: the flag is part of the key here
    digest = hashlib.sha256(b"\0".join([*(_source(files[f]) for f in sorted(files)), *flags])).hexdigest()
    dispatcher._cache = cache_class()(func, digest)  # type: ignore[attr-defined]
    return dispatcher


class Kernel:
    """A numba kernel compiled on first use; see the module docstring."""

    def __init__(self, py_func: Callable[..., Any], nogil: bool = False) -> None:
        self.py_func = py_func
        self.nogil = nogil
        self.__doc__ = py_func.__doc__
        self.__name__ = py_func.__name__
        self._compiled: Callable[..., Any] | None = None

    @property
    def compiled(self) -> Callable[..., Any]:
        """The numba dispatcher (``cache=True``: compiled once per machine)."""
        if self._compiled is None:
            self._compiled = _compile(self.py_func, self.nogil)
        return self._compiled

    def __call__(self, *args: Any) -> Any:
        """Run the compiled kernel on ``args`` (compiling it first if needed).

        A signal that came during the call is raised once the call returns, where numba
        boxes the result (it unpickles the result's types in Python); numba then reports a
        ``SystemError`` caused (through more of them) by the ``KeyboardInterrupt`` (or
        SIGTERM's ``Terminated``), which goes on up as itself.
        """
        try:
            return self.compiled(*args)
        except SystemError as exc:
            cause: BaseException | None = exc
            while isinstance(cause, SystemError):  # numba's, one per value it boxed
                cause = cause.__cause__
            if isinstance(cause, KeyboardInterrupt):
                raise cause from None
            raise

    def run(self, work: int, *args: Any) -> Any:
        """Run on ``args``: as plain Python when ``work < SMALL_WORK``, else compiled."""
        if work < SMALL_WORK and self._compiled is None:
            return self.py_func(*args)
        return self(*args)

    def __repr__(self) -> str:
        state = "compiled" if self._compiled is not None else "not compiled yet"
        return f"<kernel {self.__name__} ({state})>"


def kernel(py_func: Callable[..., Any]) -> Kernel:
    """Wrap ``py_func`` in a :class:`Kernel` (use as a decorator)."""
    return Kernel(py_func)


def threaded_kernel(py_func: Callable[..., Any]) -> Kernel:
    """Wrap ``py_func`` in a :class:`Kernel` whose compiled code releases Python's lock (use as a decorator).

    For kernels that threads run on parts of one job at once; such a kernel must not
    share writable arrays between the calls.
    """
    return Kernel(py_func, nogil=True)
