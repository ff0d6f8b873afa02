"""Symmetries of a finite scaffold: isometries of its sites lifted to incidence automorphisms.

:mod:`lkspace.symmetry.pointset` finds the isometries of the vertex positions (sites).
Each one is **lifted** to a vertex permutation ``sigma``: with one vertex per site it is
the site permutation itself; with coincident vertices (an OBJ with one vertex copy per
face) each face goes to the face on the image sites and its corners follow.  A lift is
kept only when it is an automorphism of the incidence structure: ``sigma`` is a
bijection, every edge goes to an edge and every face (as its set of edges) to a face.
Checks use integer keys and sorting: O(size log size) per motion, no dense matrices.

When coincident vertices make the lift ambiguous (two faces on the same sites, a face
through one site twice), the exact but slower automorphism search of
:mod:`lkspace.symmetry.motions` is used if the incidence structure is small enough,
otherwise only the identity is kept, with a :class:`~lkspace.errors.LkspaceWarning`.
"""

from __future__ import annotations

import contextlib
import math
import warnings
from collections.abc import Iterator
from dataclasses import dataclass, replace

import numpy as np

from ..errors import LkspaceWarning, TooLargeError
from ..model.counts import count_text
from ..model.scaffold import Scaffold
from ..runtime.progress import task
from .pointset import Sites, SiteSearch, find_sites, standard_position
from .slots import RadialCheck
from .tolerance import FLOOR, mesh_unit

MAX_GROUP_ENTRIES = 50_000_000
"""Most entries the group's tables (order x (vertices + edges)) may hold, about 400 MB.

Past it, :class:`~lkspace.errors.TooLargeError` (e.g. a two-sided 5,000-gon: 20,000 motions
on 5,000 vertices); use ``--symmetry none``."""


@dataclass(frozen=True, eq=False)
class Lift:
    """A symmetry as the search holds it: a rigid motion lifted to the incidence structure.

    Attributes
    ----------
    sigma : (n_vertices,) int64
        Image vertex of each vertex.
    q : (3, 3) float64
        Orthogonal part of the motion.
    edge_perm : (n_edges,) int64
        Image edge of each edge.
    sites : (n_sites,) int64 or None
        Image site of each site (:mod:`~lkspace.symmetry.pointset`); ``None`` outside the site search.
    """

    sigma: np.ndarray
    q: np.ndarray
    edge_perm: np.ndarray
    sites: np.ndarray | None = None


_RELEASED = np.empty(0, np.int64)
"""What :func:`stack` leaves in place of a vertex permutation it has copied."""

_MIX = np.uint64(0x9E3779B97F4A7C15)


def mix(values: np.ndarray) -> np.ndarray:
    """(n,) uint64: a fixed pseudo-random 64-bit code of each int64 value (splitmix64 finalizer)."""
    z = values.astype(np.uint64) * _MIX
    z ^= z >> np.uint64(31)
    z *= np.uint64(0xBF58476D1CE4E5B9)
    z ^= z >> np.uint64(29)
    return z


def segment_hashes(values: np.ndarray, starts: np.ndarray) -> np.ndarray:
    """(n_segments,) uint64: an order-free hash of each segment ``values[starts[i]:starts[i+1]]``."""
    with np.errstate(over="ignore"):
        return np.add.reduceat(mix(values), starts[:-1]).astype(np.uint64)


def gather(starts: np.ndarray, order: np.ndarray) -> np.ndarray:
    """Return the indices of the segments ``starts[i]:starts[i+1]`` for ``i`` in ``order``, concatenated."""
    sizes = np.diff(starts)[order]
    begin = np.repeat(starts[:-1][order], sizes)
    offset = np.arange(int(sizes.sum())) - np.repeat(np.cumsum(sizes) - sizes, sizes)
    return begin + offset


class Structure:
    """The incidence structure of a finite scaffold, keyed for fast automorphism checks."""

    def __init__(self, scaffold: Scaffold) -> None:
        self.scaffold = scaffold
        self.n_vertices = scaffold.n_vertices
        ev = scaffold.edge_vertices
        self.edge_codes = ev[:, 0] * self.n_vertices + ev[:, 1]
        self.edge_order = np.argsort(self.edge_codes)
        self.sorted_codes = self.edge_codes[self.edge_order]
        self.starts = scaffold.face_starts
        self.sizes = np.diff(self.starts)
        self.face_of_side = np.repeat(np.arange(scaffold.n_faces), self.sizes)
        self.faces = self.sorted_faces(segment_hashes(scaffold.side_edge, self.starts), scaffold.side_edge)
        self.radial = RadialCheck(scaffold, segment_hashes(scaffold.side_edge, self.starts))

    def sorted_faces(self, hashes: np.ndarray, side_edges: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Faces (``hashes`` of their edges) as edge multisets in a canonical order: ``((2, n_faces), sorted edges)``."""
        order = np.lexsort((hashes, self.sizes))
        sorted_sides = side_edges[np.lexsort((side_edges, self.face_of_side))]
        edges = sorted_sides[gather(self.starts, order)]
        return np.stack([self.sizes[order], hashes[order].view(np.int64)]), edges

    def edge_permutation(self, sigma: np.ndarray) -> np.ndarray | None:
        """(n_edges,) int64 image edge of each edge under ``sigma``, or ``None`` if one is no edge."""
        ev = self.scaffold.edge_vertices
        a, b = sigma[ev[:, 0]], sigma[ev[:, 1]]
        codes = np.minimum(a, b) * self.n_vertices + np.maximum(a, b)
        at = np.minimum(np.searchsorted(self.sorted_codes, codes), len(codes) - 1)
        if not np.array_equal(self.sorted_codes[at], codes):
            return None
        perm = self.edge_order[at]
        if np.any(np.bincount(perm, minlength=len(perm)) != 1):
            return None
        return perm.astype(np.int64)

    def automorphism(self, sigma: np.ndarray, proper: bool) -> np.ndarray | None:
        """Edge permutation of ``sigma`` if it keeps edges, faces and radial orders (:mod:`.slots`), else ``None``.

        ``proper``: the motion is a rotation (it decides which way radial orders must turn).
        """
        if np.any(np.bincount(sigma, minlength=self.n_vertices) != 1):
            return None
        perm = self.edge_permutation(sigma)
        if perm is None:
            return None
        image_sides = perm[self.scaffold.side_edge]
        hashes = segment_hashes(image_sides, self.starts)
        keys, edges = self.sorted_faces(hashes, image_sides)
        if not (np.array_equal(keys, self.faces[0]) and np.array_equal(edges, self.faces[1])):
            return None
        return perm if self.radial.keeps(sigma, perm, hashes, proper) else None

    def keeps_radial(self, sigma: np.ndarray, perm: np.ndarray, proper: bool) -> bool:
        """Whether the automorphism ``(sigma, perm)`` keeps the radial order of every edge (:mod:`.slots`)."""
        return self.radial.keeps(sigma, perm, segment_hashes(perm[self.scaffold.side_edge], self.starts), proper)


class Lifter:
    """Lift site permutations to vertex permutations (one vertex per site, or by faces)."""

    def __init__(self, scaffold: Scaffold, sites: Sites) -> None:
        self.sites = sites
        self.of_vertex = sites.of_vertex
        self.simple = sites.n_sites == scaffold.n_vertices
        self.vertex_at = np.empty(sites.n_sites, np.int64)
        self.vertex_at[self.of_vertex] = np.arange(scaffold.n_vertices)
        starts, corners = scaffold.face_starts, scaffold.corners
        self.starts = starts
        self.corners = corners
        self.face_of_corner = scaffold.corner_face
        corner_sites = self.of_vertex[corners]
        self.face_sites_hash = segment_hashes(corner_sites, starts)
        self.by_site = np.lexsort((corner_sites, self.face_of_corner))
        sorted_sites = corner_sites[self.by_site]
        same_face = self.face_of_corner[self.by_site][1:] == self.face_of_corner[self.by_site][:-1]
        repeated_site = bool(np.any(same_face & (sorted_sites[1:] == sorted_sites[:-1])))
        hashes = np.sort(self.face_sites_hash)
        repeated_face = bool(np.any(hashes[1:] == hashes[:-1]))
        in_face = np.zeros(scaffold.n_vertices, bool)
        in_face[corners] = True
        loose = np.bincount(self.of_vertex[~in_face], minlength=sites.n_sites)
        self.ambiguous = not self.simple and (repeated_site or repeated_face or bool(np.any(loose > 1)))
        self.face_order = np.argsort(self.face_sites_hash)

    def lift(self, pi: np.ndarray) -> np.ndarray | None:
        """Vertex permutation over the site permutation ``pi``, or ``None`` if faces do not match up."""
        if self.simple:
            return self.vertex_at[pi[self.of_vertex]]
        image_sites = pi[self.of_vertex[self.corners]]
        image_hash = segment_hashes(image_sites, self.starts)
        order = np.argsort(image_hash)
        if not np.array_equal(image_hash[order], self.face_sites_hash[self.face_order]):
            return None
        target = np.empty(len(order), np.int64)
        target[order] = self.face_order  # face f goes to face target[f]
        sizes = np.diff(self.starts)
        if not np.array_equal(sizes[target], sizes):
            return None
        src = np.lexsort((image_sites, self.face_of_corner))  # corners of f by image site
        # corners of target faces, laid out in the order of the source faces
        tgt_face_corners = np.repeat(self.starts[:-1][target], sizes) + (
            np.arange(len(self.corners)) - np.repeat(self.starts[:-1], sizes)
        )
        tgt_sites = self.of_vertex[self.corners[tgt_face_corners]]
        dst = tgt_face_corners[np.lexsort((tgt_sites, self.face_of_corner))]
        if not np.array_equal(image_sites[src], self.of_vertex[self.corners[dst]]):
            return None
        sigma = np.full(len(self.of_vertex), -1, np.int64)
        sigma[self.corners[src]] = self.corners[dst]
        if not np.array_equal(sigma[self.corners[src]], self.corners[dst]):
            return None  # a vertex shared by faces would go two ways
        loose = np.flatnonzero(sigma < 0)
        sigma[loose] = self.vertex_at[pi[self.of_vertex[loose]]]
        return sigma


def vertex_invariants(scaffold: Scaffold) -> list[np.ndarray]:
    """Per-vertex values every symmetry keeps: degree, number of corners, summed edge-degree."""
    ev = scaffold.edge_vertices.reshape(-1)
    n = scaffold.n_vertices
    degree = np.bincount(ev, minlength=n).astype(np.float64)
    corners = np.bincount(scaffold.corners, minlength=n).astype(np.float64)
    sides = np.bincount(ev, weights=np.repeat(scaffold.edge_degrees, 2), minlength=n)
    return [degree, corners, sides]


Tables = tuple[np.ndarray, np.ndarray, np.ndarray]
"""Group tables: ``sigmas (m, n_vertices) int64``, ``Qs (m, 3, 3) float64``, ``edge_perms (m, n_edges) int64``."""


def stack(lifts: list[Lift]) -> Tables:
    """Stack lifted motions into :data:`Tables`, one table at a time.

    Each lift's arrays are released once copied (``lifts`` is emptied), so the peak is
    the lifts plus one table, not the lifts plus all tables.
    """
    m = len(lifts)
    qs = np.array([row.q for row in lifts], np.float64).reshape(m, 3, 3)
    sigmas = np.empty((m, len(lifts[0].sigma)), np.int64)
    for i, row in enumerate(lifts):
        sigmas[i] = row.sigma
        lifts[i] = replace(row, sigma=_RELEASED, sites=None)
    perms = np.empty((m, len(lifts[0].edge_perm)), np.int64)
    for i, row in enumerate(lifts):
        perms[i] = row.edge_perm
    lifts.clear()
    return sigmas, qs, perms


class Elements:
    """The group found so far, closed under composition: each new generator is multiplied in.

    Products of symmetries are symmetries, so only generators are verified (a few full
    matches, about log2 of the order); the rest of the group costs one composition
    (``O(vertices + edges)``) per element.
    """

    def __init__(self, search: SiteSearch, n_vertices: int, n_edges: int, name: str) -> None:
        self.search = search
        self.size = n_vertices + n_edges
        self.name = name
        identity = np.arange(search.sites.n_sites, dtype=np.int64)
        self.rows = [
            Lift(np.arange(n_vertices, dtype=np.int64), np.eye(3), np.arange(n_edges, dtype=np.int64), identity)
        ]
        self.keys = {search.key(identity, True)}
        self.generators: list[Lift] = []
        self.same = bool(np.array_equal(search.sites.of_vertex, np.arange(n_vertices)))

    def tables(self) -> Tables:
        """Return the elements as arrays ``(sigmas, Qs, edge_perms)``, built row by row (no second copy of the rows)."""
        return stack(self.rows)

    def add_generator(self, row: Lift) -> None:
        """Add a motion (with its ``sites``) and every product it makes with the elements found."""
        if self.same:
            row = replace(row, sites=row.sigma)
        self.generators = self.generators + [row]
        frontier = list(self.rows)
        while frontier:
            new = []
            for h in frontier:
                for g in self.generators:
                    h_sites, g_sites = _sites(h), _sites(g)
                    pi_ab = h_sites[g_sites[[self.search.a, self.search.b_or_a]]]
                    key = self.search.key_of(pi_ab, bool(np.linalg.det(h.q) * np.linalg.det(g.q) > 0))
                    if key in self.keys:
                        continue
                    self.keys.add(key)
                    sigma = h.sigma[g.sigma]
                    pi = sigma if self.same else h_sites[g_sites]  # one vertex per site, numbered alike: pi is sigma
                    self.rows.append(Lift(sigma, h.q @ g.q, h.edge_perm[g.edge_perm], pi))
                    new.append(self.rows[-1])
                    if len(self.rows) * self.size > MAX_GROUP_ENTRIES:
                        raise TooLargeError(
                            f"{self.name}: the symmetry group has more than {len(self.rows) - 1} elements on "
                            f"{self.size} vertices and edges: its tables would pass {MAX_GROUP_ENTRIES} "
                            "entries; use `symmetry='none'`",
                        )
            frontier = new


def _sites(lift: Lift) -> np.ndarray:
    """Return the site permutation of a lift of the site search (each of its lifts has one)."""
    if lift.sites is None:
        raise ValueError("a motion without its site permutation")  # a bug in lkspace
    return lift.sites


def finite_lifts(scaffold: Scaffold, tolerance: float) -> Tables:
    """Return ``(sigma, Q, edge_perm)`` for every symmetry of a finite scaffold, the identity first.

    ``tolerance`` (mesh units, :mod:`lkspace.symmetry.tolerance`): how far a motion may
    move a vertex from the vertex it is matched with.  Raises
    :class:`~lkspace.errors.TooLargeError` when the group's tables would pass
    :data:`MAX_GROUP_ENTRIES` or the candidates :data:`~lkspace.symmetry.pointset.MAX_FRAME_CANDIDATES`.
    """
    x = standard_position(scaffold.vertices)
    sites = find_sites(x, vertex_invariants(scaffold), max(tolerance / mesh_unit(scaffold), FLOOR))
    structure = Structure(scaffold)
    lifter = Lifter(scaffold, sites)
    if lifter.ambiguous:
        return stack(list(ambiguous_lifts(scaffold, structure, scaffold.n_vertices + scaffold.n_edges, tolerance)))
    search = SiteSearch(sites)
    found = Elements(search, scaffold.n_vertices, scaffold.n_edges, scaffold.name)
    with task("symmetry search (motions)", total=None) as step:
        for keys, qs in search.batches():
            if keys is not None:
                fresh = ~np.isin(keys, np.fromiter(found.keys, np.int64, len(found.keys)))
                keys, qs = keys[fresh], qs[fresh]
                ok = search.probe(qs)
                keys, qs = keys[ok], qs[ok]
            for i, q in enumerate(qs):
                if keys is not None and int(keys[i]) in found.keys:
                    continue
                verified = search.verify(q)
                if verified is None:
                    continue
                q, pi = verified
                if search.key(pi, bool(np.linalg.det(q) > 0)) in found.keys:
                    continue
                sigma = lifter.lift(pi)
                perm = None if sigma is None else structure.automorphism(sigma, bool(np.linalg.det(q) > 0))
                if sigma is not None and perm is not None:
                    found.add_generator(Lift(sigma, q, perm, pi))
                    step.note(f"{len(found.rows)} motions found")
    return found.tables()


def ambiguous_lifts(scaffold: Scaffold, structure: Structure, size: int, tolerance: float) -> Iterator[Lift]:
    """Lifts when coincident vertices leave faces ambiguous: the exact igraph search if small, else the identity."""
    from .motions import MAX_AUTOMORPHISMS, automorphism_count, candidate_vertex_perms, finite_motions

    identity = np.arange(scaffold.n_vertices, dtype=np.int64)
    unused = scaffold.n_vertices - len(np.unique(scaffold.corners))
    count = None  # unknown: past MAX_AUTOMORPHISMS
    if math.factorial(min(unused, 20)) <= MAX_AUTOMORPHISMS:  # vertices in no face are interchangeable
        with contextlib.suppress(ValueError):  # igraph's count past 4,300 digits is text Python will not read
            count = automorphism_count(scaffold)
    if count is not None and count <= MAX_AUTOMORPHISMS and count * (size + scaffold.n_faces) <= MAX_GROUP_ENTRIES:
        seen = set()
        for sigma, q, _, _ in finite_motions(scaffold, candidate_vertex_perms(scaffold), tolerance):
            perm = structure.edge_permutation(sigma)
            proper = bool(np.linalg.det(q) > 0)
            key = (sigma.tobytes(), proper)
            if perm is not None and key not in seen and structure.keeps_radial(sigma, perm, proper):
                seen.add(key)
                yield Lift(sigma, q, perm)
        return
    warnings.warn(
        f"{scaffold.name}: coincident vertices and faces leave the symmetry search ambiguous "
        f"({f'more than {MAX_AUTOMORPHISMS}' if count is None else count_text(count)} incidence automorphisms); "
        "using the identity only (weld the mesh to find its symmetries)",
        LkspaceWarning,
        stacklevel=2,
    )
    yield Lift(identity, np.eye(3), np.arange(scaffold.n_edges, dtype=np.int64))
