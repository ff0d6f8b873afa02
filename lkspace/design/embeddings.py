"""The many surfaces of one graph: face sets, radial orders and labels, up to automorphism.

Without trusted coordinates a scaffold is combinatorial: faces as vertex cycles.  An edge
lying on ``K >= 3`` faces then has no radial order of its own: any of the ``(K-1)!`` cyclic
orders of its faces may be chosen, and different choices give different strands.  A
**structure** on a face set is a choice, per edge, of a cyclic order of its faces and a
value: the residue ``t mod K`` (what the strands depend on) or, for designs, a label from a
set.  Graph automorphisms that keep the face set act on structures:

* automorphism ``g`` maps edge ``e = (a, b)`` to ``g(e)`` and the faces in its order to
  their images; when ``g(a) > g(b)`` the edge is seen from its other end, so the cyclic
  order is reversed (slots run counter-clockwise about the axis from the lower vertex);
* the value is kept: the twist rule reads the same from either end of an edge.

A mirror image (every order reversed, labels negated) is a different structure here.
:func:`count_structures` counts the orbits exactly by Burnside (``|Fix(g)|`` is a product
over the cycles of ``g`` on the edges: the states of the cycle's first edge fixed by
``g^L``); :func:`list_structures` lists canonical ones for small spaces; and
:func:`graph_surfaces` does both for every cover of a graph (:mod:`~lkspace.design.graph_faces`).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..errors import ScaffoldError, TooLargeError
from ..model.scaffold import Scaffold
from .graph_faces import (
    MAX_CYCLES,
    CycleSpace,
    canonical_cycle,
    check_graph,
    cover_orbits,
    cycle_space,
    graph_automorphisms,
)

MAX_LISTED = 1 << 20
"""Most structures :func:`list_structures` walks."""


@dataclass(frozen=True, eq=False)
class FaceStructure:
    """The edges of a face set with the faces on each and their possible cyclic orders.

    Attributes
    ----------
    space : CycleSpace
    faces : tuple of int
        Cycle indices of the faces (face ``k`` is cycle ``faces[k]``).
    edges : (n_edges,) int64
        Graph edges lying on at least one face, in graph edge order.
    orders : list of list of tuple of int
        Per edge, its cyclic orders: face positions starting at the smallest.
    group : (n_g,) int64
        Automorphisms (indices into ``space.automorphisms``) keeping the face set.
    """

    space: CycleSpace
    faces: tuple[int, ...]
    edges: np.ndarray
    orders: list[list[tuple[int, ...]]]
    group: np.ndarray

    @classmethod
    def of(cls, space: CycleSpace, faces: Sequence[int]) -> FaceStructure:
        """Build from a face set of ``space``."""
        on_edge: dict[int, list[int]] = {}
        for k, f in enumerate(faces):
            for e in space.cycle_edges[f]:
                on_edge.setdefault(e, []).append(k)
        edges = np.array(sorted(on_edge), np.int64)
        orders = [[(on_edge[e][0], *p) for p in itertools.permutations(on_edge[e][1:])] for e in edges.tolist()]
        return cls(space, tuple(faces), edges, orders, space.stabilizer(faces))

    def degree(self, i: int) -> int:
        """Faces on the ``i``-th edge of :attr:`edges`."""
        return len(self.orders[i][0])

    def move(self, g: int) -> tuple[np.ndarray, list[list[int]]]:
        """Return the action of automorphism ``g``: edge images (positions in :attr:`edges`) and order images per edge."""
        p = self.space.automorphisms[g]
        face_image = {k: self.faces.index(int(self.space.cycle_perms[g, f])) for k, f in enumerate(self.faces)}
        where = {int(e): i for i, e in enumerate(self.edges)}
        edge_image = np.empty(len(self.edges), np.int64)
        order_image = []
        for i, e in enumerate(self.edges.tolist()):
            a, b = self.space.edges[e]
            j = where[self.space.edges.index((min(p[a], p[b]), max(p[a], p[b])))]
            edge_image[i] = j
            index = {o: n for n, o in enumerate(self.orders[j])}
            row = []
            for o in self.orders[i]:
                moved = [face_image[k] for k in o]
                if p[a] > p[b]:
                    moved = moved[::-1]
                row.append(index[_rotate_to_min(moved)])
            order_image.append(row)
        return edge_image, order_image


def _rotate_to_min(seq: list[int]) -> tuple[int, ...]:
    i = seq.index(min(seq))
    return tuple(seq[i:] + seq[:i])


def n_values(structure: FaceStructure, i: int, label_set: Sequence[int] | None) -> int:
    """Values an edge may carry: its ``K`` residues, or the labels of ``label_set``."""
    return structure.degree(i) if label_set is None else len(label_set)


def count_structures(structure: FaceStructure, label_set: Sequence[int] | None = None) -> int:
    """Structures (radial orders and residues, or labels) on the face set up to its automorphisms (exact)."""
    total = 0
    moves = [structure.move(int(g)) for g in structure.group]
    for edge_image, order_image in moves:
        fixed = 1
        seen = np.zeros(len(edge_image), bool)
        for start in range(len(edge_image)):
            if seen[start]:
                continue
            cycle = [start]
            seen[start] = True
            while edge_image[cycle[-1]] != start:
                cycle.append(int(edge_image[cycle[-1]]))
                seen[cycle[-1]] = True
            kept = 0
            for o in range(len(structure.orders[start])):
                x = o
                for i in cycle:  # follow the order around the cycle back to the first edge
                    x = order_image[i][x]
                kept += x == o
            fixed *= kept * n_values(structure, start, label_set)
        total += fixed
    return total // len(moves)


def list_structures(
    structure: FaceStructure, label_set: Sequence[int] | None = None
) -> list[tuple[tuple[int, ...], tuple[int, ...], int]]:
    """Canonical structures: ``(order index per edge, value per edge, orbit size)``, smallest first.

    A structure is canonical when no automorphism of the face set maps it to a smaller one
    (orders, then values, lexicographically).  Values are residues ``0..K-1`` or labels.
    """
    values = [
        list(range(structure.degree(i))) if label_set is None else list(label_set) for i in range(len(structure.edges))
    ]
    size = math.prod(len(o) * len(v) for o, v in zip(structure.orders, values, strict=True))
    if size > MAX_LISTED:
        raise TooLargeError(f"{size:,} structures to walk (limit {MAX_LISTED:,}); count them instead")
    moves = [structure.move(int(g)) for g in structure.group]
    out = []
    for orders in itertools.product(*[range(len(o)) for o in structure.orders]):
        for vals in itertools.product(*values):
            key = (orders, vals)
            images = []
            for edge_image, order_image in moves:
                o2 = [0] * len(orders)
                v2 = [0] * len(orders)
                for i, j in enumerate(edge_image.tolist()):
                    o2[j] = order_image[i][orders[i]]
                    v2[j] = vals[i]
                images.append((tuple(o2), tuple(v2)))
            if min(images) == key:
                out.append((orders, vals, len(moves) // images.count(key)))
    return out


def scaffold_structure(scaffold: Scaffold) -> FaceStructure:
    """Return the :class:`FaceStructure` of a finite scaffold's faces, coordinates ignored.

    Raises :class:`~lkspace.errors.ScaffoldError` for two faces on one vertex cycle or a
    face that is not a simple cycle (graph cycles cannot tell them apart).
    """
    if scaffold.periodic:
        raise ScaffoldError(f"{scaffold.name}: embeddings of periodic scaffolds are not supported")
    check_graph(scaffold.n_vertices, [(0, 0)] * scaffold.n_edges)  # before the faces are listed
    if scaffold.n_faces > MAX_CYCLES:
        raise TooLargeError(
            f"{scaffold.name}: {scaffold.n_faces:,} faces; face structures are counted on at most {MAX_CYCLES:,}"
        )
    cycles = [canonical_cycle(f) for f in scaffold.faces()]
    if len(set(cycles)) != len(cycles) or any(len(set(c)) != len(c) for c in cycles):
        raise ScaffoldError(f"{scaffold.name}: faces must be distinct simple cycles to count embeddings")
    edges = [tuple(e) for e in scaffold.edge_vertices.tolist()]
    ordered = sorted(set(cycles), key=lambda c: (len(c), c))
    space = CycleSpace(scaffold.n_vertices, edges, ordered, graph_automorphisms(scaffold.n_vertices, edges))
    return FaceStructure.of(space, sorted(ordered.index(c) for c in cycles))


@dataclass(frozen=True)
class Surface:
    """One cover of a graph up to automorphism, and the structures on it.

    Attributes
    ----------
    faces : list of tuple of int
        The faces as vertex cycles.
    covers : int
        Covers in its orbit (face sets of the graph equal to it up to automorphism).
    symmetry : int
        Order of its automorphism group (graph automorphisms keeping the face set).
    radial_orders : int
        Product over edges of ``(K-1)!``: radial orders of the face set.
    structures : int
        Radial orders and residues up to automorphism: distinct strand structures.
    designs : int or None
        Radial orders and labels from ``label_set`` up to automorphism.
    """

    faces: list[tuple[int, ...]]
    covers: int
    symmetry: int
    radial_orders: int
    structures: int
    designs: int | None


def graph_surfaces(
    graph: tuple[int, Sequence[tuple[int, int]]],
    max_length: int,
    per_edge: int = 2,
    label_set: Sequence[int] | None = None,
) -> list[Surface]:
    """Every way to choose cycles of ``graph`` as faces, each edge on ``per_edge`` faces, up to automorphism.

    Parameters
    ----------
    graph : (n_vertices, edges)
        E.g. :func:`~lkspace.design.graph_faces.named_graph` ``("K4")``.
    max_length : int
        Longest cycle that may become a face.
    per_edge : int
        Faces on every edge (2: surfaces; 3 or more: non-manifold scaffolds with radial orders).
    label_set : sequence of int, optional
        Also count designs with these labels.

    Examples
    --------
    >>> from lkspace.design.graph_faces import named_graph
    >>> [(len(s.faces), s.symmetry, s.structures) for s in graph_surfaces(named_graph("K4"), 4)]
    [(4, 24, 11), (3, 24, 11)]
    """
    space = cycle_space(*graph, max_length)
    out = []
    for faces, n_covers in cover_orbits(space, per_edge):
        st = FaceStructure.of(space, faces)
        out.append(
            Surface(
                faces=[space.cycles[f] for f in faces],
                covers=n_covers,
                symmetry=len(st.group),
                radial_orders=math.prod(len(o) for o in st.orders),
                structures=count_structures(st),
                designs=None if label_set is None else count_structures(st, label_set),
            )
        )
    return out


def own_surface(scaffold: Scaffold, label_set: Sequence[int] | None = None) -> Surface:
    """Return the :class:`Surface` of a finite scaffold's own faces (every radial order, coordinates ignored).

    Examples
    --------
    >>> from lkspace import load
    >>> s = own_surface(load("book:3"))
    >>> s.symmetry, s.radial_orders, s.structures
    (12, 2, 3)
    """
    st = scaffold_structure(scaffold)
    return Surface(
        faces=[st.space.cycles[f] for f in st.faces],
        covers=1,
        symmetry=len(st.group),
        radial_orders=math.prod(len(o) for o in st.orders),
        structures=count_structures(st),
        designs=None if label_set is None else count_structures(st, label_set),
    )
