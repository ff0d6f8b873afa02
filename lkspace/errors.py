"""Exceptions raised by lkspace.

The tree::

    LkspaceError                      base of everything lkspace raises on purpose
    ├── UsageError(ValueError)        an option or argument that cannot be used (exit 2)
    │   └── TooLargeError             work past a documented bound (says how to go ahead or what to make smaller)
    ├── ScaffoldError(ValueError)     a scaffold that cannot be built or read
    │   └── RadialOrderError          two face-sides of an edge (K >= 3) at the same angle
    ├── LabelError(ValueError)        twist labels, label sets, null edge-sides
    ├── CatalogError(ValueError)      a catalog that cannot be read or written
    │   └── CatalogLockedError        another run is writing the same catalog
    ├── GeometryError(ValueError)     realized strands that would touch, unusable parameters
    ├── DiagramError(ValueError)      a projection that is not generic
    ├── ExportError(ValueError)       an output path or format that cannot be written (exit 2)
    └── MissingDependencyError(ImportError)  an optional extra is not installed

    SolveVerificationError(RuntimeError)  a solver answer failed the tracer check: a bug
    LkspaceWarning(UserWarning)       something suspicious but usable (e.g. faces that share no edge)

Messages say what, where and what arrived, e.g.
``"tetra.obj line 7: face vertex index 9 out of range 1..4"``.  The library speaks of its
own parameters, never of command-line flags: an error about one argument passes
``parameter="max_designs"`` and its message starts with that name
(``"max_designs: must be at least 1, got 0"``); the command line, which knows the flag
of each parameter (:mod:`lkspace.cli.flags`), shows the flag instead (``"--max-designs: ..."``).
A parameter named further on in a message is put in backquotes, alone or with a value
(``"use a smaller `thickness`"``, ``"use `symmetry='none'`"``), which the command line
shows as its flag too (``"use a smaller --thickness"``, ``"use --symmetry none"``).
The command line turns any ``LkspaceError`` into one stderr line (and, under ``--json``,
an ``{"error": {...}}`` object on stdout) with the error's :attr:`~LkspaceError.exit_code`:
1 for bad data (files, scaffolds, catalogs), 2 for bad usage (options and arguments).
"""

from __future__ import annotations

import importlib
from types import ModuleType


class LkspaceError(Exception):
    """Base class of every error lkspace raises on purpose.

    ``exit_code`` is the command line's exit status for it: 1 (bad data) unless the class
    or the ``usage=True`` keyword says the error is in how lkspace was called (2).
    ``parameter`` names the argument at fault (as the Python API calls it); the message
    then starts with that name, which the command line replaces by the flag.
    """

    exit_code = 1

    def __init__(self, *args: object, usage: bool | None = None, parameter: str | None = None) -> None:
        super().__init__(*args)
        if usage is not None:
            self.exit_code = 2 if usage else 1
        self.parameter = parameter


class UsageError(LkspaceError, ValueError):
    """An option or argument value that cannot be used (exit status 2)."""

    exit_code = 2


class TooLargeError(UsageError):
    """Work past a documented bound: the message gives the estimate and how to go ahead."""


class ScaffoldError(LkspaceError, ValueError):
    """A scaffold (mesh, file, built-in name) is malformed or unusable."""


class RadialOrderError(ScaffoldError):
    """The radial order of the face-sides around an edge is ambiguous."""


class LabelError(LkspaceError, ValueError):
    """Twist labels, a label set or null edge-sides are malformed."""


class CatalogError(LkspaceError, ValueError):
    """A catalog file is malformed or does not match its scaffold."""


class CatalogLockedError(CatalogError):
    """Another run holds the lock of the catalog being written."""


class GeometryError(LkspaceError, ValueError):
    """The realized strands are not an embedding (or parameters are unusable)."""


class DiagramError(LkspaceError, ValueError):
    """A projection that is not generic (a crossing too close to another one)."""


class ExportError(LkspaceError, ValueError):
    """An output path or format that cannot be written (a usage error: exit status 2)."""

    exit_code = 2


class SolveVerificationError(RuntimeError):
    """A solver answer failed the tracer check: a bug in lkspace, never bad input."""


class LkspaceWarning(UserWarning):
    """Something suspicious in the input that lkspace can still work with."""


class MissingDependencyError(LkspaceError, ImportError):
    """An optional dependency is missing; the message names the extra to install."""

    def __init__(self, package: str, extra: str, purpose: str) -> None:
        super().__init__(f"{purpose} needs the optional package {package!r}: pip install 'lkspace[{extra}]'")
        self.package = package
        self.extra = extra


def require(module: str, extra: str, purpose: str) -> ModuleType:
    """Import and return ``module`` or raise :class:`MissingDependencyError`."""
    try:
        return importlib.import_module(module)
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise MissingDependencyError(module, extra, purpose) from exc
