"""Scaffolds made from a link diagram, and the built-in names ``knot:NAME`` / ``link:NAME``.

:func:`design_scaffold` turns a PD code into a scaffold carrying its twist labels: the
checkerboard mesh of :mod:`~lkspace.scaffolds.diagram_mesh` placed by
:mod:`~lkspace.scaffolds.plane_layout`.  Three placements exist (:data:`LAYOUTS`): ``sphere``
(the plane drawing lifted onto the unit sphere), ``flat`` (the drawing in the plane,
the outer face behind the others, like the paper's figure-eight mesh) and ``round`` (the
sphere's positions evened out by a spherical Tutte iteration).  The realized
strands follow the faces only where the faces are well shaped, so the command that makes
a scaffold (``lkspace construct``) checks the result's knot type and takes the first
placement that gives the diagram's own type.

The diagrams of every prime knot of KnotInfo to 12 crossings and every prime link of
LinkInfo to 11 ship in ``lkspace/data/diagrams.json.gz``, with the placement checked for
each (where no placement of the tables' diagram passes, another minimal diagram of the
type: the tables' moved by Reidemeister moves; ``experiments/construct_tables.py`` writes the file and the report in
``results/construct/``).  ``knot:8_17`` and ``link:L6a4`` name those designs; ``m`` in
front of the table name (``knot:m3_1``) is the mirror image (every label negated).
"""

from __future__ import annotations

import gzip
import json
import os
from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..errors import ScaffoldError
from ..model.scaffold import Scaffold
from .diagram_mesh import diagram_mesh
from .plane_layout import plane_layout, round_layout, sphere_layout

LAYOUTS = {"sphere": sphere_layout, "flat": plane_layout, "round": round_layout}
"""Placements of a diagram's mesh.  A layout is spelled ``sphere``, ``flat`` or ``round``, with the outer face
after a colon where it is not the largest face (``sphere:3``), and ``/more`` at the end for the
mesh of the other colouring (the one with more edges: ``flat:2/more``)."""


def layouts(pd: Sequence[Sequence[int]]) -> list[str]:
    """Every layout of the diagram ``pd``, in the order they are tried: fewer edges, largest face outside first."""
    out = []
    for colouring in ("fewer", "more"):
        n_faces = len(diagram_mesh(pd, colouring=colouring).faces)
        tail = "" if colouring == "fewer" else "/more"
        out += [f"{k}{tail}" for k in LAYOUTS] + [f"{k}:{f}{tail}" for f in range(n_faces) for k in LAYOUTS]
    return out


PREFIXES = ("knot:", "link:")
TABLE_FILE = os.path.join(os.path.dirname(os.path.dirname(__file__)), "data", "diagrams.json.gz")


def design_scaffold(pd: Sequence[Sequence[int]], name: str, layout: str = "sphere", where: str = "PD code") -> Scaffold:
    """Return the scaffold of the diagram ``pd`` with its twist labels (module docstring).

    Examples
    --------
    >>> s = design_scaffold([[1, 5, 2, 4], [3, 1, 4, 6], [5, 3, 6, 2]], "3_1")  # KnotInfo's 3_1
    >>> s.n_faces, int(abs(s.labels).sum())
    (2, 3)
    """
    placement, _, colouring = layout.partition("/")
    mesh = diagram_mesh(pd, where, "more" if colouring == "more" else "fewer")
    kind, _, outer = placement.partition(":")
    if (
        kind not in LAYOUTS
        or colouring not in ("", "more")
        or not (outer == "" or (outer.isdigit() and int(outer) < len(mesh.faces)))
    ):
        raise ScaffoldError(
            f"{where}: layout {layout!r}: expected sphere or flat, then :F (a face F) and /more, both optional"
        )
    positions = LAYOUTS[kind](mesh.n_vertices, mesh.faces, int(outer) if outer else None)
    scaffold = Scaffold.from_faces(positions, mesh.faces, name=name)
    by_pair = {(min(u, v), max(u, v)): t for (u, v), t in zip(mesh.edges, mesh.labels)}
    labels = np.array([by_pair[int(a), int(b)] for a, b in scaffold.edge_vertices], np.int64)
    return scaffold.with_labels(labels)


@dataclass(frozen=True)
class TableDiagram:
    """One type of the shipped table: its diagram and the placement checked for it.

    ``pd``: the tables' PD code; ``components``; ``crossings``: the crossing number;
    ``amphichiral``: KnotInfo's symmetry type says so (``None`` for links); ``layout``: the
    first placement that named right (``None``: not checked).
    """

    pd: tuple[tuple[int, ...], ...]
    components: int
    crossings: int
    amphichiral: bool | None
    layout: str | None

    @classmethod
    def from_json(cls, data: object, where: str) -> TableDiagram:
        """Read one entry of the file (the object :meth:`to_json` writes)."""
        if not isinstance(data, dict):
            raise ScaffoldError(f"{where}: not a table entry (a JSON object); reinstall lkspace")
        try:
            return cls(
                tuple(tuple(int(v) for v in x) for x in data["pd"]),
                int(data["components"]),
                int(data["crossings"]),
                None if data.get("amphichiral") is None else bool(data["amphichiral"]),
                None if data.get("layout") is None else str(data["layout"]),
            )
        except (KeyError, TypeError, ValueError) as exc:
            raise ScaffoldError(f"{where}: not a table entry ({exc!r}); reinstall lkspace") from exc

    def to_json(self) -> dict[str, object]:
        """Return ``{pd, components, crossings, amphichiral, layout}``."""
        return {
            "pd": [list(x) for x in self.pd],
            "components": self.components,
            "crossings": self.crossings,
            "amphichiral": self.amphichiral,
            "layout": self.layout,
        }


@lru_cache(maxsize=1)
def table() -> dict[str, TableDiagram]:
    """Name -> :class:`TableDiagram`, read once from the shipped file."""
    try:
        with gzip.open(TABLE_FILE, "rt", encoding="utf-8") as fh:
            data = json.load(fh)
    except (OSError, ValueError) as exc:
        raise ScaffoldError(f"the table of diagrams {TABLE_FILE} cannot be read ({exc}); reinstall lkspace") from exc
    return {name: TableDiagram.from_json(entry, f"{TABLE_FILE}: {name}") for name, entry in data.items()}


def is_table_design(name: str) -> bool:
    """Whether ``name`` is spelled as a built-in table design (``knot:...`` or ``link:...``)."""
    return name.startswith(PREFIXES)


def table_design(name: str) -> Scaffold:
    """Return the built-in scaffold ``knot:NAME`` / ``link:NAME`` with its labels (module docstring)."""
    kind, _, typed = name.partition(":")
    mirror = typed.startswith("m") and typed[1:] in table()
    base = typed[1:] if mirror else typed
    entry = table().get(base)
    if entry is None or (entry.components == 1) != (kind == "knot"):
        other = "link" if kind == "knot" else "knot"
        hint = f"; it is a {other}: write {other}:{typed}" if entry is not None else ""
        raise ScaffoldError(
            f"unknown built-in {name[:60]!r}{hint}; {kind}: takes a table name as KnotInfo/LinkInfo spell it "
            f"({'3_1, 8_17, 11a_1, 12n_242' if kind == 'knot' else 'L2a1, L6a4, L11n459'}), "
            "with m in front for the mirror image; `lkspace construct` takes every other spelling"
        )
    scaffold = design_scaffold(entry.pd, name, entry.layout or "sphere", where=name)
    assert scaffold.labels is not None
    return scaffold.with_labels(-scaffold.labels if mirror else scaffold.labels)
