"""Radial slots under a symmetry: the sides around an edge must keep their cyclic order.

A twist shifts the ``K`` sides of an edge along their radial order
(:mod:`lkspace.model.radial`), so a symmetry must carry the radial order of every edge
with ``K >= 3`` onto that of its image edge: as the same cyclic order, or reversed when
the motion is a rotation that turns the edge end for end, or a reflection that does not
(seen from the image edge's own direction the turn is then clockwise).  A motion
accepted within a tolerance could in principle break this where sides are nearly at one
angle; :class:`RadialCheck` checks it exactly, with integers.

Edges whose sides are not told apart by their faces (a face on the edge twice, or two
faces on the same edges) are skipped: there the face map itself is not unique.
"""

from __future__ import annotations

import numpy as np

from ..model.scaffold import Scaffold


class RadialCheck:
    """Check that an edge permutation keeps the radial order of every edge with ``K >= 3``."""

    def __init__(self, scaffold: Scaffold, face_hashes: np.ndarray) -> None:
        """Prepare the checked edges; ``face_hashes (n_faces,) uint64`` tell faces apart by their edges."""
        self.scaffold = scaffold
        k = scaffold.edge_degrees
        self.n_edges = scaffold.n_edges
        self.active = bool(np.any(k >= 3))
        if not self.active:
            return
        radial = scaffold.radial
        starts = radial.edge_starts
        face, edge = scaffold.corner_face, scaffold.side_edge
        codes = face * self.n_edges + edge
        order = np.argsort(codes, kind="stable")
        sorted_codes = codes[order]
        repeated = np.zeros(len(codes), bool)
        twice = sorted_codes[1:] == sorted_codes[:-1]
        repeated[order[1:][twice]] = True
        repeated[order[:-1][twice]] = True
        hashes = np.sort(face_hashes)
        same = np.zeros(scaffold.n_faces, bool)
        dup = np.flatnonzero(hashes[1:] == hashes[:-1])
        same[np.isin(face_hashes, hashes[dup])] = True
        bad = np.bincount(edge[repeated | same[face]], minlength=self.n_edges) > 0
        self.edges = np.flatnonzero((k >= 3) & ~bad)
        sizes = k[self.edges]
        seg = np.repeat(starts[self.edges], sizes) + (
            np.arange(int(sizes.sum())) - np.repeat(np.cumsum(sizes) - sizes, sizes)
        )
        self.sides = radial.edge_sides[seg]  # sides of the checked edges, each edge's in slot order
        first = np.cumsum(sizes) - sizes
        self.successor = np.arange(len(self.sides)) + 1
        self.successor[np.cumsum(sizes) - 1] = first
        self.modulus = np.repeat(sizes, sizes)
        self.codes, self.order = sorted_codes, order
        self.slot = radial.side_slot
        self.sorted_hashes, self.hash_order = hashes, np.argsort(face_hashes, kind="stable")

    def keeps(self, sigma: np.ndarray, edge_perm: np.ndarray, image_hash: np.ndarray, proper: bool) -> bool:
        """Whether the automorphism ``(sigma, edge_perm)`` (``proper``: a rotation) keeps every checked radial order.

        ``image_hash (n_faces,) uint64``: the hash of each face's image edges (as ``face_hashes``).
        """
        if not self.active or not len(self.edges):
            return True
        sc = self.scaffold
        sides = self.sides
        faces = sc.corner_face[sides]
        at = np.minimum(np.searchsorted(self.sorted_hashes, image_hash[faces]), len(self.sorted_hashes) - 1)
        if not np.array_equal(self.sorted_hashes[at], image_hash[faces]):
            return False
        image_faces = self.hash_order[at]
        image_codes = image_faces * self.n_edges + edge_perm[sc.side_edge[sides]]
        where = np.minimum(np.searchsorted(self.codes, image_codes), len(self.codes) - 1)
        if not np.array_equal(self.codes[where], image_codes):
            return False
        slots = self.slot[self.order[where]]
        steps = (slots[self.successor] - slots) % self.modulus
        ev = sc.edge_vertices
        edges = sc.side_edge[sides]
        kept = sigma[ev[edges, 0]] == ev[edge_perm[edges], 0]
        expected = np.where(kept == proper, 1, self.modulus - 1)
        return bool(np.array_equal(steps, expected))
