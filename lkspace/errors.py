"""Exceptions raised by lkspace.

The tree::

    LkspaceError                      base of everything lkspace raises on purpose
    ├── ScaffoldError(ValueError)     a scaffold that cannot be built or read
    │   └── RadialOrderError          two face-sides of an edge (K >= 3) at the same angle
    ├── LabelError(ValueError)        twist labels, label sets, null edge-sides
    ├── CatalogError(ValueError)      a catalog that cannot be read or written
    ├── GeometryError(ValueError)     realized strands that would touch, unusable parameters
    ├── DiagramError(ValueError)      a projection that is not generic
    ├── ExportError(ValueError)       an output path or format that cannot be written
    └── MissingDependencyError(ImportError)  an optional extra is not installed

    SolveVerificationError(RuntimeError)  a solver answer failed the tracer check: a bug

Messages say what, where and what arrived, e.g.
``"tetra.obj line 7: face vertex index 9 out of range 1..4"``.
The command line turns any ``LkspaceError`` into one stderr line and exit code 2.
"""

from __future__ import annotations

import importlib
from types import ModuleType


class LkspaceError(Exception):
    """Base class of every error lkspace raises on purpose."""


class ScaffoldError(LkspaceError, ValueError):
    """A scaffold (mesh, file, built-in name) is malformed or unusable."""


class RadialOrderError(ScaffoldError):
    """The radial order of the face-sides around an edge is ambiguous."""


class LabelError(LkspaceError, ValueError):
    """Twist labels, a label set or null edge-sides are malformed."""


class CatalogError(LkspaceError, ValueError):
    """A catalog file is malformed or does not match its scaffold."""


class GeometryError(LkspaceError, ValueError):
    """The realized strands are not an embedding (or parameters are unusable)."""


class DiagramError(LkspaceError, ValueError):
    """A projection that is not generic (a crossing too close to another one)."""


class ExportError(LkspaceError, ValueError):
    """An output path or format that cannot be written."""


class SolveVerificationError(RuntimeError):
    """A solver answer failed the tracer check: a bug in lkspace, never bad input."""


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
