"""Built-in scaffolds by name (SPEC §4).

=========================  ==========================================================
name                       scaffold
=========================  ==========================================================
tetrahedron                regular tetrahedron (4 triangles, 6 edges)
cube                       cube [-1, 1]^3 (6 squares, 12 edges)
octahedron                 regular octahedron (8 triangles, 12 edges)
dodecahedron               regular dodecahedron (12 pentagons, 30 edges)
icosahedron                regular icosahedron (20 triangles, 30 edges)
truncated-octahedron       truncated octahedron (6 squares + 8 hexagons, 36 edges)
dihedron:N                 two-sided regular N-gon (two faces on one N-cycle), N >= 3
book:K                     K quads sharing one edge at equal angles, K >= 1
figure-eight               square: two triangles in front, a quad behind (paper; 4_1)
whitehead                  square fanned into four triangles, no back (paper; L5a1)
=========================  ==========================================================

``figure-eight`` and ``whitehead`` carry their paper designs as default twists
(see :mod:`lkspace.scaffolds.paper`).
"""

from __future__ import annotations

from typing import Callable

from ..errors import ScaffoldError
from ..mesh import Scaffold
from . import paper, polyhedra, special

SOLIDS: dict[str, Callable[[], Scaffold]] = {
    "tetrahedron": polyhedra.tetrahedron,
    "cube": polyhedra.cube,
    "octahedron": polyhedra.octahedron,
    "dodecahedron": polyhedra.dodecahedron,
    "icosahedron": polyhedra.icosahedron,
    "truncated-octahedron": polyhedra.truncated_octahedron,
    "figure-eight": paper.figure_eight,
    "whitehead": paper.whitehead,
}

FAMILIES: dict[str, Callable[[int], Scaffold]] = {
    "dihedron": special.dihedron,
    "book": special.book,
}

DEFAULT = "tetrahedron"


def builtin_names() -> list[str]:
    """Every built-in name, families written with their parameter (``book:K``)."""
    return list(SOLIDS) + [f"{f}:N" if f == "dihedron" else f"{f}:K" for f in FAMILIES]


def is_builtin_name(name: str) -> bool:
    """Whether ``name`` looks like a built-in name rather than a path."""
    head = name.split(":", 1)[0].split("@", 1)[0]
    return head in SOLIDS or head in FAMILIES or name.startswith(("tiling:", "honeycomb:"))


def builtin(name: str) -> Scaffold:
    """The built-in scaffold called ``name``.

    Examples
    --------
    >>> builtin("book:3").edge_degrees.max()
    np.int64(3)
    """
    if name in SOLIDS:
        return SOLIDS[name]()
    head, _, arg = name.partition(":")
    if head in FAMILIES:
        try:
            n = int(arg)
        except ValueError:
            raise ScaffoldError(f"built-in {name!r}: expected {head}:N with an integer N") from None
        return FAMILIES[head](n)
    raise ScaffoldError(f"unknown scaffold name {name!r}; built-in names: {', '.join(builtin_names())}")
