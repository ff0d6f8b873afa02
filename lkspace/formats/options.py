"""What each export format takes: one frozen record per format, checked when it is built.

- :class:`MeshOptions` (``.obj``, ``.ply``): ``tubes``, the tube, ``units`` (a comment), ``sides``
- :class:`GlbOptions` (``.glb``): the tube, ``sides``
- :class:`PrintOptions` (``.stl``, ``.3mf``): ``thickness``, ``clearance``, ``units``, ``scale``,
  ``sides``, ``pieces``
- :class:`PictureOptions` (``.png``, ``.svg``): ``look``, ``diagram``, ``show_mesh``, ``title``, the tube

"The tube" (:class:`TubeOptions`) is ``radius`` in scaffold units, or ``thickness`` (a
diameter in output units) with ``scale`` (output units per scaffold unit), and an optional
``clearance`` (output units) proved between the tubes before they are written.  A record
given for a format that does not take it is refused by :func:`lkspace.formats.registry.export`
in one line naming the record that format takes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, TypeAlias

from ..errors import ExportError
from ..geometry.fabrication import Units, check_options
from .render import Look, check_title

if TYPE_CHECKING:
    from ..geometry.fabrication import Printable

TUBE_SIDES = 12
"""Vertices around a tube's circle (the mesh formats' default ``sides``)."""
PRINT_SIDES = 16
"""Vertices around a printed tube's circle (``.stl``, ``.3mf``)."""
MAX_SIDES = 256
"""Most vertices around a tube's circle (``sides``)."""


def check_sides(sides: int) -> None:
    """Refuse a ``sides`` that is not an integer in 3..:data:`MAX_SIDES`."""
    if isinstance(sides, bool) or not isinstance(sides, int) or not 3 <= sides <= MAX_SIDES:
        raise ExportError(f"sides: must be an integer in 3..{MAX_SIDES}, got {sides!r}", parameter="sides")


@dataclass(frozen=True)
class TubeOptions:
    """The tubes of a format that draws them: how thick, and the gap proved between them.

    Parameters
    ----------
    radius : float, optional
        Tube radius in scaffold units (default: the realization's).
    thickness : float, optional
        Tube diameter in output units: ``radius = thickness / 2 / scale`` when ``radius``
        is not given.
    scale : float
        Output units per scaffold unit (for ``thickness`` and ``clearance``).
    clearance : float, optional
        Least surface gap between distinct pieces, in output units, proved on the tubes
        (:func:`lkspace.geometry.fabrication.printable`) before anything is written.
    """

    radius: float | None = None
    thickness: float | None = None
    scale: float = 1.0
    clearance: float | None = None

    def __post_init__(self) -> None:
        if self.radius is not None and not (math.isfinite(self.radius) and self.radius > 0):
            raise ExportError(
                f"radius: the tube radius must be a finite number > 0, got {self.radius}", parameter="radius"
            )
        check_options(self.thickness, self.clearance, self._units(), self.scale)

    def _units(self) -> str:
        """Return the units checked with the tube (only the mesh formats take ``units``)."""
        return "mm"

    @property
    def tube_radius(self) -> float | None:
        """The tube radius in scaffold units: ``radius``, else from ``thickness``, else ``None`` (the realization's)."""
        if self.radius is None and self.thickness is not None:
            return self.thickness / 2 / self.scale
        return self.radius

    @property
    def given(self) -> str:
        """The parameter that sets the tube (``radius`` or ``thickness``), for messages."""
        return "radius" if self.radius is not None else "thickness"


@dataclass(frozen=True)
class MeshOptions(TubeOptions):
    """``.obj`` and ``.ply``: polylines, or with ``tubes=True`` tube meshes.

    Parameters
    ----------
    tubes : bool
        Tube meshes instead of polylines; ``clearance`` is checked on tubes only.
    units : {"um", "mm", "cm", "m", "in", "ft"}, optional
        What one unit is, written as a comment (none by default).
    sides : int
        Vertices around a tube.
    """

    tubes: bool = False
    units: Units | None = None
    sides: int = TUBE_SIDES

    def __post_init__(self) -> None:
        super().__post_init__()
        check_sides(self.sides)
        if self.clearance is not None and not self.tubes:
            raise ExportError(
                "clearance: polylines have no tubes to keep apart; give tubes=True", parameter="clearance"
            )

    def _units(self) -> str:
        return self.units or "mm"


@dataclass(frozen=True)
class GlbOptions(TubeOptions):
    """``.glb``: tube meshes, ``sides`` vertices around."""

    sides: int = TUBE_SIDES

    def __post_init__(self) -> None:
        super().__post_init__()
        check_sides(self.sides)


@dataclass(frozen=True)
class PictureOptions(TubeOptions):
    """``.png`` and ``.svg``: a 3D render of the tubes, or a 2D knot diagram.

    Parameters
    ----------
    look : Look
        View, size, background and colours (:func:`lkspace.formats.render.look_of`).
    diagram : bool
        Draw the 2D knot/link diagram instead of the 3D render.
    show_mesh : bool
        Draw the scaffold faintly behind the tubes.
    title : str, optional
        A title above the picture.
    """

    look: Look = Look()
    diagram: bool = False
    show_mesh: bool = True
    title: str | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        check_title(self.title)


@dataclass(frozen=True)
class PrintOptions:
    """``.stl`` and ``.3mf``: printable pieces (:func:`lkspace.geometry.fabrication.printable`).

    Parameters
    ----------
    thickness, clearance : float, optional
        Tube diameter (default: the realization's tube) and the least surface gap between
        distinct pieces (default 0), in output units.
    units : {"um", "mm", "cm", "m", "in", "ft"}
        What one output unit is: the 3MF ``unit``, the STL header.
    scale : float
        Output units per scaffold unit.
    sides : int
        Vertices around a tube.
    pieces : Printable, optional
        Pieces already made by :func:`~lkspace.geometry.fabrication.printable` with these
        options (the command line reports them); made and checked on export otherwise.
    """

    thickness: float | None = None
    clearance: float | None = None
    units: Units = "mm"
    scale: float = 1.0
    sides: int = PRINT_SIDES
    pieces: Printable | None = field(default=None, compare=False)

    def __post_init__(self) -> None:
        check_options(self.thickness, self.clearance, self.units, self.scale)
        check_sides(self.sides)


FormatOptions: TypeAlias = MeshOptions | GlbOptions | PrintOptions | PictureOptions
"""The record of any format."""
