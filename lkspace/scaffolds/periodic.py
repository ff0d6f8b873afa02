"""Periodic scaffolds: Wigner–Seitz tilings and honeycombs, Voronoi scaffolds, supercells.

A periodic scaffold is the quotient of an infinite periodic polygon complex by its
lattice (see :mod:`lkspace.model.scaffold`).  Cells are computed with scipy's Voronoi (Qhull;
the built-in tilings and honeycombs are shipped precomputed, :func:`wigner_seitz`):

* 2D (``tiling:*``): the faces are the Voronoi cells (tiles) of the lattice points in the
  xy plane; every edge is shared by two tiles.
* 3D (``honeycomb:*``, Voronoi scaffolds): the faces are the walls between Voronoi cells;
  each cell is the convex hull (coplanar facets merged) of its Voronoi vertices.

Polygons that are lattice translates of each other are one face class, positions that
differ by a lattice vector one vertex class; each class keeps the representative whose
lattice coordinates lie in ``[0, 1)``, and every face corner carries the integer offset of
its actual position.

Lattice parameters of the built-ins (see :class:`~lkspace.model.lattice.Lattice`):
``tiling:square`` a = 1; ``tiling:hexagonal`` a = 1; ``honeycomb:cP`` a = 1 (cubes);
``honeycomb:hP`` a = c = 1 (hexagonal prisms); ``honeycomb:oF`` a, b, c = 1, 1.25, 1.5;
``honeycomb:cF`` a = 1 (rhombic dodecahedra); ``honeycomb:cI`` a = 1 (truncated octahedra).
"""

from __future__ import annotations

import itertools
import re
from collections.abc import Iterable

import numpy as np
from numpy.typing import ArrayLike

from ..errors import ScaffoldError, UsageError
from ..model.lattice import Lattice, lll_reduce
from ..model.scaffold import Scaffold
from .polyhedra import convex_polyhedron

DECIMALS = 6  # rounding of lattice coordinates when identifying translates

LATTICES = {
    "tiling:square": Lattice.square,
    "tiling:hexagonal": Lattice.hexagonal2d,
    "honeycomb:cP": Lattice.cubic,
    "honeycomb:hP": Lattice.hexagonal,
    "honeycomb:oF": Lattice.face_centred_orthorhombic,
    "honeycomb:cF": Lattice.face_centred_cubic,
    "honeycomb:cI": Lattice.body_centred_cubic,
}


def _translates(lattice: Lattice, points: np.ndarray, reach: int = 2) -> tuple[np.ndarray, np.ndarray]:
    """All ``points + m @ reduced`` for ``m`` in ``[-reach, reach]^dim``; and which are base.

    ``reduced`` is the LLL-reduced basis, so the translates surround the base points
    however skewed the given basis is.
    """
    _, unimodular = lll_reduce(lattice.basis)
    shifts = np.array(list(itertools.product(range(-reach, reach + 1), repeat=lattice.dim)))
    order = np.argsort(np.abs(shifts).sum(axis=1), kind="stable")  # the zero shift first
    shifts = shifts[order] @ unimodular  # in the given basis
    cloud = (points[None, :, :] + lattice.translate(shifts)[:, None, :]).reshape(-1, 3)
    return cloud, np.arange(len(points))


def _planar_frame(lattice: Lattice) -> np.ndarray:
    """(2, 3) orthonormal basis of the plane of a 2D lattice."""
    q, _ = np.linalg.qr(lattice.basis.T)
    return q.T


def voronoi_polygons(lattice: Lattice, generators: ArrayLike) -> list[np.ndarray]:
    """Polygons ``(m, 3)`` of the Voronoi complex of ``generators`` + lattice.

    2D lattices give the tiles of the base generators, 3D lattices the walls of their
    cells (each wall once per cell, so shared walls appear twice: deduplicated later).
    """
    from scipy.spatial import ConvexHull, Voronoi  # Qhull: loaded only for periodic scaffolds

    generators = np.atleast_2d(np.asarray(generators, dtype=np.float64))
    cloud, base = _translates(lattice, generators)
    polygons = []
    if lattice.dim == 2:
        frame = _planar_frame(lattice)
        origin = generators[0]
        vor = Voronoi((cloud - origin) @ frame.T)
        for i in base:
            region = vor.regions[vor.point_region[i]]
            if -1 in region or not region:
                raise ScaffoldError("voronoi: a cell of the base generators is unbounded")
            pts2 = vor.vertices[region]
            hull = ConvexHull(pts2)
            polygons.append(pts2[hull.vertices] @ frame + origin)
        return polygons
    vor = Voronoi(cloud)
    for i in base:
        region = vor.regions[vor.point_region[i]]
        if -1 in region or not region:
            raise ScaffoldError("voronoi: a cell of the base generators is unbounded")
        cell = convex_polyhedron(vor.vertices[region], decimals=DECIMALS)
        polygons += [cell.vertices[face] for face in cell.faces()]
    return polygons


def quotient_scaffold(lattice: Lattice, polygons: Iterable[np.ndarray], name: str) -> Scaffold:
    """Return the periodic scaffold of ``polygons`` (each ``(m, 3)``) modulo ``lattice``.

    Corners closer than ``10^-DECIMALS`` in lattice coordinates modulo the lattice are one
    vertex class (a periodic KD-tree, not rounded floats: a coordinate on a rounding
    boundary cannot split a class); a face is then an exact integer key, its corners'
    classes and offsets up to translation, and translates of a face are one face class.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    polys = [np.asarray(p, dtype=np.float64) for p in polygons]
    sizes = [len(p) for p in polys]
    frac = lattice.fractional(np.concatenate(polys))
    shifts = np.concatenate(
        [
            np.repeat(np.floor(np.round(f.mean(axis=0), DECIMALS - 1))[None], len(f), axis=0)
            for f in np.split(frac, np.cumsum(sizes)[:-1])
        ]
    )
    frac = frac - shifts  # each face near the cell [0, 1)
    wrapped = np.mod(frac, 1.0)
    pairs = cKDTree(np.where(wrapped >= 1.0, 0.0, wrapped), boxsize=1.0).query_pairs(
        10.0**-DECIMALS, output_type="ndarray"
    )
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(len(frac), len(frac)))
    _, cluster = connected_components(graph, directed=False)
    _, first, vertex_class = np.unique(cluster, return_index=True, return_inverse=True)
    order = np.argsort(first)  # classes numbered by first occurrence
    rank = np.empty(len(order), np.int64)
    rank[order] = np.arange(len(order))
    vertex_class = rank[vertex_class.reshape(-1)]
    first = first[order]
    base = np.floor(np.round(frac[first], DECIMALS - 1))  # the representative's cell
    offsets = np.rint(frac - (frac[first] - base)[vertex_class]).astype(np.int64)
    points = np.concatenate(polys) - lattice.translate(shifts)
    positions = points[first] - lattice.translate(base)
    face_keys = set()
    faces, face_offsets = [], []
    starts = np.r_[0, np.cumsum(sizes)]
    for f in range(len(polys)):
        corners = list(
            zip(vertex_class[starts[f] : starts[f + 1]].tolist(), offsets[starts[f] : starts[f + 1]].tolist())
        )
        low = min(corners)[1]
        key = tuple(sorted((v, tuple(o - m for o, m in zip(off, low))) for v, off in corners))
        if key in face_keys:
            continue
        face_keys.add(key)
        faces.append([v for v, _ in corners])
        face_offsets.append([off for _, off in corners])
    # number vertices deterministically: by position of the representative
    order = np.lexsort(np.round(positions, DECIMALS).T[::-1])
    renumber = np.empty(len(order), np.int64)
    renumber[order] = np.arange(len(order))
    faces = [renumber[f].tolist() for f in faces]
    return Scaffold.from_faces(positions[order], faces, lattice=lattice, offsets=face_offsets, name=name)


def wigner_seitz(name: str) -> Scaffold:
    """Return the built-in Wigner–Seitz tiling or honeycomb ``name`` (see the module docstring).

    The cell is read from :mod:`lkspace.scaffolds.wigner_seitz_cells`, which holds what
    :func:`wigner_seitz_from_voronoi` computes (the tests check that they agree): loading a
    built-in needs no Qhull.
    """
    if name not in LATTICES:
        raise ScaffoldError(f"unknown periodic scaffold {name!r}; known: {', '.join(LATTICES)}")
    from .wigner_seitz_cells import CELLS

    vertices, faces, offsets = CELLS[name]
    return Scaffold.from_faces(vertices, faces, lattice=LATTICES[name](), offsets=offsets, name=name)


def wigner_seitz_from_voronoi(name: str) -> Scaffold:
    """Compute the built-in Wigner–Seitz scaffold ``name`` with Qhull (the data of :func:`wigner_seitz`)."""
    lattice = LATTICES[name]()
    return quotient_scaffold(lattice, voronoi_polygons(lattice, np.zeros((1, 3))), name)


def voronoi_scaffold(lattice: Lattice, generators: ArrayLike, name: str = "voronoi") -> Scaffold:
    """Generalized Voronoi scaffold: ``generators (n, 3)`` in the fundamental domain.

    Examples
    --------
    >>> s = voronoi_scaffold(Lattice.cubic(), [[0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]])
    >>> s.n_faces, sorted(set(s.edge_degrees.tolist()))
    (12, [3, 4])
    """
    generators = np.atleast_2d(np.asarray(generators, dtype=np.float64))
    if generators.ndim != 2 or generators.shape[1] != 3 or len(generators) == 0:
        raise ScaffoldError(f"{name}: generator points must be an (n, 3) array, got shape {generators.shape}")
    frac = lattice.fractional(generators)
    keys = np.round(frac - np.floor(np.round(frac, DECIMALS)), DECIMALS - 1)
    if len(np.unique(keys, axis=0)) < len(keys):
        raise ScaffoldError(f"{name}: two generator points coincide modulo the lattice")
    if lattice.dim == 2 and np.any(np.abs(generators @ np.cross(*lattice.basis)) > 1e-9):
        raise ScaffoldError(f"{name}: generator points must lie in the plane of the 2D lattice")
    return quotient_scaffold(lattice, voronoi_polygons(lattice, generators), name)


VORONOI_EXAMPLES = {
    # the paper's figure: a cubic lattice with points at the cube's face centres
    "voronoi:cube-faces": (Lattice.cubic, [[0.5, 0.5, 0.0], [0.5, 0.0, 0.5], [0.0, 0.5, 0.5]]),
}


def voronoi_example(name: str) -> Scaffold:
    """Return the built-in generalized Voronoi scaffold (see ``VORONOI_EXAMPLES``)."""
    make_lattice, points = VORONOI_EXAMPLES[name]
    return voronoi_scaffold(make_lattice(), points, name)


_SUPERCELL = re.compile(r"^([0-9]{1,9})x([0-9]{1,9})(?:x([0-9]{1,9}))?$")

MAX_SUPERCELL_FACES = 200_000
"""Most faces a supercell ``NAME@AxBxC`` may have (cells times the faces of one cell)."""


def parse_supercell(text: str, dim: int, faces_per_cell: int = 1) -> tuple[int, ...]:
    """``"2x2x1"`` -> ``(2, 2, 1)``; the number of factors must match ``dim``.

    The supercell may hold at most :data:`MAX_SUPERCELL_FACES` faces, ``faces_per_cell``
    per cell; a larger one is a :class:`~lkspace.errors.UsageError` naming the bound.
    """
    m = _SUPERCELL.match(text)
    sizes = tuple(int(g) for g in m.groups() if g is not None) if m else ()
    if len(sizes) != dim or min(sizes, default=0) < 1:
        want = "AxB" if dim == 2 else "AxBxC"
        raise ScaffoldError(f"supercell {text[:40]!r}: expected {want} with positive integers")
    faces = int(np.prod(sizes, dtype=object)) * faces_per_cell
    if faces > MAX_SUPERCELL_FACES:
        raise UsageError(
            f"supercell {text!r}: {faces} faces ({faces_per_cell} per cell); a supercell may have at most "
            f"{MAX_SUPERCELL_FACES} faces"
        )
    return sizes


def supercell(scaffold: Scaffold, sizes: ArrayLike) -> Scaffold:
    """Return the ``A x B (x C)`` repeating domain of a periodic scaffold.

    Cell ``m = (i, j, k)`` with ``0 <= m < sizes`` gets index ``(i * B + j) * C + k``;
    vertex ``v`` of cell ``m`` becomes ``cell_index * n_vertices + v`` and face ``f`` becomes
    ``cell_index * n_faces + f``.  Edges are then numbered by the usual rule
    (:mod:`lkspace.model.scaffold`), so per-cell labels are given in that documented edge order.
    """
    if scaffold.lattice is None or scaffold.corner_offsets is None:
        raise ScaffoldError(f"{scaffold.name}: supercells need a periodic scaffold")
    sizes = np.asarray(sizes, dtype=np.int64)
    if sizes.shape != (scaffold.dim,):
        raise ScaffoldError(f"{scaffold.name}: supercell needs {scaffold.dim} sizes, got {sizes.tolist()}")
    cells = np.array(list(itertools.product(*(range(s) for s in sizes))), dtype=np.int64)
    n_cells = len(cells)
    vertices = (scaffold.vertices[None] + scaffold.lattice.translate(cells)[:, None]).reshape(-1, 3)
    absolute = cells[:, None, :] + scaffold.corner_offsets[None]  # (cells, corners, dim)
    cell_of = np.mod(absolute, sizes)
    super_offsets = np.floor_divide(absolute, sizes)
    strides = np.cumprod(np.r_[1, sizes[::-1][:-1]])[::-1]
    cell_index = cell_of @ strides
    corners = cell_index * scaffold.n_vertices + scaffold.corners[None]
    starts = np.concatenate([[0], np.cumsum(np.tile(scaffold.face_sizes, n_cells))]).astype(np.int64)
    return Scaffold(
        vertices,
        starts,
        corners.reshape(-1),
        lattice=scaffold.lattice.supercell(sizes),
        corner_offsets=super_offsets.reshape(-1, scaffold.dim),
        name=f"{scaffold.name}@{'x'.join(map(str, sizes.tolist()))}",
    )
