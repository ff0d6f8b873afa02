"""Built-in scaffolds by name (listed for users in ``lkspace scaffold --help`` and ``docs/cli.md``).

=========================  ==========================================================
name                       scaffold
=========================  ==========================================================
tetrahedron                regular tetrahedron (4 triangles, 6 edges)
cube                       cube [-1, 1]^3 (6 squares, 12 edges)
octahedron                 regular octahedron (8 triangles, 12 edges)
dodecahedron               regular dodecahedron (12 pentagons, 30 edges)
icosahedron                regular icosahedron (20 triangles, 30 edges)
truncated-tetrahedron      truncated tetrahedron (4 triangles + 4 hexagons, 18 edges)
cuboctahedron              cuboctahedron (8 triangles + 6 squares, 24 edges)
truncated-octahedron       truncated octahedron (6 squares + 8 hexagons, 36 edges)
prism:N                    uniform N-gonal prism (N + 2 faces, 3N edges), N >= 3
antiprism:N                uniform N-gonal antiprism (2N + 2 faces, 4N edges), N >= 3
dihedron:N                 two-sided regular N-gon (two faces on one N-cycle), N >= 3
book:K                     K quads sharing one edge at equal angles, K >= 1
kaleidocycle:K             a ring of K tetrahedra hinged edge to edge, K even >= 4
tiling:square              square tiling (periodic, 1 face, 2 edge classes)
tiling:hexagonal           hexagonal tiling (periodic, 1 face, 3 edge classes)
honeycomb:cP               cubic honeycomb (3 faces, edge classes x, y, z)
honeycomb:hP               hexagonal-prism honeycomb
honeycomb:oF               face-centred orthorhombic Wigner–Seitz honeycomb
honeycomb:cF               rhombic-dodecahedral honeycomb (face-centred cubic)
honeycomb:cI               truncated-octahedral honeycomb (body-centred cubic)
cube-net                   the cube unfolded flat into a cross of six squares
cube-lid                   open box with its lid swung open about one top edge
cubes:piano                two cubes sharing an edge (piano hinge, degree 4)
cubes:vertex               two cubes sharing a vertex
figure-eight               square: two triangles in front, a quad behind (paper; 4_1)
whitehead                  square fanned into four triangles, no back (paper; L5a1)
laves                      the Laves graph (srs net), periodic: its 10-rings as faces
                           (the paper's figure; every edge of degree 10)
voronoi:cube-faces         Voronoi scaffold of a cubic lattice with points at the
                           cube's face centres (the paper's figure; 12 triangles)
NAME@AxBxC                 the A x B x C supercell of a periodic NAME (AxB in 2D)
knot:NAME, link:NAME       a table type made from its diagram, with its labels
                           (``knot:8_17``, ``knot:m3_1``, ``link:L6a4``; every prime
                           knot of KnotInfo to 12 crossings, link of LinkInfo to 11;
                           see :mod:`lkspace.scaffolds.constructed`)
=========================  ==========================================================

Bounds, checked before building: ``N, K <= MAX_FAMILY_PARAMETER`` (1000); a supercell
holds at most :data:`~lkspace.scaffolds.periodic.MAX_SUPERCELL_FACES` faces.

Periodic cells and lattice parameters: :mod:`lkspace.scaffolds.periodic`.
``figure-eight`` and ``whitehead`` carry their paper designs as default labels
(see :mod:`lkspace.scaffolds.paper`).
"""

from __future__ import annotations

import re
from collections.abc import Callable

from ..errors import ScaffoldError, UsageError
from ..model.scaffold import Scaffold
from . import constructed, hinged, kaleidocycle, laves, paper, periodic, polyhedra, prisms, special

SOLIDS: dict[str, Callable[[], Scaffold]] = {
    "tetrahedron": polyhedra.tetrahedron,
    "cube": polyhedra.cube,
    "octahedron": polyhedra.octahedron,
    "dodecahedron": polyhedra.dodecahedron,
    "icosahedron": polyhedra.icosahedron,
    "truncated-tetrahedron": polyhedra.truncated_tetrahedron,
    "cuboctahedron": polyhedra.cuboctahedron,
    "truncated-octahedron": polyhedra.truncated_octahedron,
    "figure-eight": paper.figure_eight,
    "whitehead": paper.whitehead,
    "laves": laves.laves,
}

SOLIDS.update(hinged.HINGED)

FAMILIES: dict[str, Callable[[int], Scaffold]] = {
    "dihedron": special.dihedron,
    "prism": prisms.prism,
    "antiprism": prisms.antiprism,
    "book": special.book,
    "kaleidocycle": kaleidocycle.kaleidocycle,
}

DEFAULT = "tetrahedron"

MAX_FAMILY_PARAMETER = 1000
"""Largest N of ``dihedron:N``, ``prism:N``, ``antiprism:N`` and K of ``book:K`` (checked before anything is built)."""


def builtin_names() -> list[str]:
    """Every built-in name, families written with their parameter (``book:K``)."""
    return (
        list(SOLIDS)
        + [f"{f}:K" if f in ("book", "kaleidocycle") else f"{f}:N" for f in FAMILIES]
        + list(periodic.LATTICES)
        + list(periodic.VORONOI_EXAMPLES)
        + ["knot:NAME", "link:NAME"]
    )


def is_builtin_name(name: str) -> bool:
    """Whether ``name`` looks like a built-in name rather than a path."""
    head = name.split(":", 1)[0].split("@", 1)[0]
    return (
        name in SOLIDS
        or head in SOLIDS
        or head in FAMILIES
        or name.startswith(("tiling:", "honeycomb:", "voronoi:"))
        or constructed.is_table_design(name)
    )


def builtin(name: str) -> Scaffold:
    """Return the built-in scaffold called ``name``.

    Examples
    --------
    >>> builtin("book:3").edge_degrees.max()
    np.int64(3)
    """
    if constructed.is_table_design(name):
        return constructed.table_design(name)
    if "@" in name:
        base_name, _, sizes = name.partition("@")
        base = builtin(base_name)
        if not base.periodic:
            raise ScaffoldError(f"{name!r}: supercells need a periodic scaffold, {base_name!r} is finite")
        return periodic.supercell(base, periodic.parse_supercell(sizes, base.dim, base.n_faces))
    if name in periodic.LATTICES:
        return periodic.wigner_seitz(name)
    if name in periodic.VORONOI_EXAMPLES:
        return periodic.voronoi_example(name)
    if name in SOLIDS:
        return SOLIDS[name]()
    head, _, arg = name.partition(":")
    if head in FAMILIES:
        if not re.fullmatch(r"-?[0-9]{1,12}", arg):
            raise ScaffoldError(f"built-in {name[:40]!r}: expected {head}:N with an integer N")
        n = int(arg)
        if n > MAX_FAMILY_PARAMETER:
            letter = "K" if head in ("book", "kaleidocycle") else "N"
            raise UsageError(f"built-in {name!r}: {head}:{letter} is limited to {letter} <= {MAX_FAMILY_PARAMETER}")
        return FAMILIES[head](n)
    raise ScaffoldError(f"unknown scaffold name {name[:60]!r}; built-in names: {', '.join(builtin_names())}")
