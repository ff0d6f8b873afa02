"""The public API's boundary: a path or a built-in name becomes a :class:`Scaffold` here, once.

The computing layers take a :class:`Scaffold` (or a design space, or a realization) and
never read files.  The public functions of :mod:`lkspace` whose first argument is a
scaffold (:data:`SCAFFOLD_FIRST`) are those functions wrapped by :func:`loading`: a ``str``
or ``os.PathLike`` first argument is loaded with :func:`lkspace.load`, anything else is
passed through unchanged.  ``lkspace.__getattr__`` wraps a function when it is first used,
so ``import lkspace`` imports no implementation module.

Examples
--------
>>> import lkspace
>>> lkspace.trace("cube", 1)
Trace(cube: 4 components, holds together, lengths [6, 6, 6, 6])
>>> from lkspace.strands.tracing import trace
>>> lkspace.trace.__wrapped__ is trace
True
"""

from __future__ import annotations

import functools
import inspect
import os
import re
from collections.abc import Callable
from typing import Any, Concatenate, ParamSpec, TypeVar, cast

P = ParamSpec("P")
R = TypeVar("R")
T = TypeVar("T")

SCAFFOLD_FIRST: dict[str, str | None] = {
    "trace": None,
    "designs": None,
    "symmetric_designs": None,
    "count_designs": None,
    "write_catalog": "path",
    "solve": None,
    "realize": None,
    "export": "path",
    "identify": None,
}
"""Public functions that take a scaffold first -> the parameter naming the file they write (or ``None``).

A function that writes a file refuses to write over the scaffold file it was given
(:func:`~lkspace.io.paths.not_an_input`), checked before the scaffold is read.
"""


def loading(
    func: Callable[Concatenate[T, P], R], writes: str | None = None
) -> Callable[Concatenate[T | str | os.PathLike[str], P], R]:
    """Return ``func`` taking a path or a built-in name as its first argument as well.

    The wrapper keeps ``func``'s name and docstring (``__wrapped__`` is ``func``); its
    ``__signature__`` shows the first parameter as a ``ScaffoldSource``.  ``writes`` names
    the parameter holding the file ``func`` writes, which must not be the scaffold file.
    """
    signature = inspect.signature(func)
    first = next(iter(signature.parameters))

    @functools.wraps(func)
    def public(*args: Any, **kwargs: Any) -> R:
        if args:
            args = (as_scaffold(args[0], signature, writes, args, kwargs), *args[1:])
        elif first in kwargs:
            kwargs[first] = as_scaffold(kwargs[first], signature, writes, args, kwargs)
        return func(*args, **kwargs)

    setattr(public, "__signature__", source_signature(signature))  # noqa: B010 (mypy: no such attribute)
    return cast(Callable[Concatenate[T | str | os.PathLike[str], P], R], public)


def as_scaffold(
    value: Any, signature: inspect.Signature, writes: str | None, args: tuple[Any, ...], kwargs: dict[str, Any]
) -> Any:
    """Return ``value`` loaded if it is a ``str`` or ``os.PathLike``, else ``value`` itself.

    With ``writes``, the output argument of the call ``(args, kwargs)`` is checked first
    not to be the file ``value`` names.
    """
    if not isinstance(value, (str, os.PathLike)):
        return value
    from .io.sources import load

    if writes is not None:
        from .io.paths import not_an_input

        try:
            output = signature.bind_partial(*args, **kwargs).arguments.get(writes)
        except TypeError:  # a wrong call: the function itself says what is wrong
            output = None
        if isinstance(output, (str, os.PathLike)):
            not_an_input(os.fspath(output), (os.fspath(value),))
    return load(value)


def source_signature(signature: inspect.Signature) -> inspect.Signature:
    """``signature`` with ``Scaffold`` in its first parameter's annotation read as ``ScaffoldSource``."""
    params = list(signature.parameters.values())
    annotation = params[0].annotation
    text = annotation if isinstance(annotation, str) else getattr(annotation, "__name__", str(annotation))
    params[0] = params[0].replace(annotation=re.sub(r"\bScaffold\b", "ScaffoldSource", text))
    return signature.replace(parameters=params)
