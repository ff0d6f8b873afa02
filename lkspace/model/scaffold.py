"""The :class:`Scaffold` value type and the conventions of the model.

Conventions (explained for users in ``docs/model.md``)
------------------------------------------------------
* **Vertices** are numbered from 0 in file order; positions ``(n_vertices, 3) float64``.
* **Faces** are vertex cycles of length >= 3, stored compressed: ``face_starts
  (n_faces + 1,) int64`` and ``corners (n_corners,) int64`` (the vertex of every face
  corner, faces one after the other).  Corner ``c`` of a face is followed by
  ``corner_next[c]``; **side** ``c`` is the face side from corner ``c`` to
  ``corner_next[c]``, so sides and corners share one numbering.
* **Periodic** scaffolds carry a :class:`~lkspace.model.lattice.Lattice` and an integer
  lattice offset ``corner_offsets (n_corners, dim) int64`` per face corner: the
  corner sits at ``vertices[v] + offset @ basis``.
* **Edges** are the distinct unordered vertex pairs occurring as sides.  For a side
  from ``(u, o_u)`` to ``(w, o_w)`` let ``delta = o_w - o_u``; its edge key is
  ``(u, w, delta)`` if ``u < w`` or (``u == w`` and ``delta`` is lexicographically
  positive), else ``(w, u, -delta)``.  Edges are numbered in lexicographic order of
  ``(a, b, -delta)`` — vertex pair first, then larger offsets first, so that the cubic
  honeycomb's three edge classes come out x, y, z — and for finite scaffolds simply in
  lexicographic order of ``(a, b)`` with ``a < b``.
  The edge's end ``a`` is vertex ``a`` at offset 0 and end ``b`` is vertex ``b`` at
  offset ``delta``; each side lies on its edge translated by ``side_translation``.
* **Axis** of edge ``(a, b)``: the unit vector from end ``a`` to end ``b``.
* **Radial order** and **twist rule**: see :mod:`lkspace.model.radial` and
  :mod:`lkspace.strands.ports`.
"""

from __future__ import annotations

import hashlib
from collections.abc import Sequence
from dataclasses import dataclass, replace
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, DTypeLike

from ..errors import ScaffoldError
from ..words import plural
from .lattice import Lattice
from .radial import RadialOrder, radial_order
from .validation import MAX_COORDINATE, validate_labels, validate_nulls

if TYPE_CHECKING:
    import networkx as nx


def unique_rows(keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Lexicographically sorted unique rows of ``keys (n, m) int64`` and the inverse map.

    Rows are packed into one int64 by mixed radix when their ranges allow (a plain 1-D
    sort, much faster than ``np.unique(axis=0)``); otherwise rows are lexsorted.
    """
    keys = np.asarray(keys, dtype=np.int64)
    if len(keys) == 0:
        return keys.copy(), np.zeros(0, np.int64)
    lo = keys.min(axis=0)
    spans = keys.max(axis=0) - lo + 1
    if np.sum(np.log2(spans.astype(np.float64))) < 62:
        packed = np.zeros(len(keys), np.int64)
        for j in range(keys.shape[1]):
            packed = packed * spans[j] + (keys[:, j] - lo[j])
        _, first, inverse = np.unique(packed, return_index=True, return_inverse=True)
        return keys[first], inverse.reshape(-1)
    order = np.lexsort(keys.T[::-1])
    sorted_keys = keys[order]
    new = np.r_[True, np.any(sorted_keys[1:] != sorted_keys[:-1], axis=1)]
    inverse = np.empty(len(keys), np.int64)
    inverse[order] = np.cumsum(new) - 1
    return sorted_keys[new], inverse


def _frozen(array: ArrayLike, dtype: DTypeLike) -> np.ndarray:
    out = np.array(array, dtype=dtype)
    out.setflags(write=False)
    return out


@dataclass(frozen=True, eq=False, repr=False)
class Scaffold:
    """A polygon mesh, finite or periodic, possibly non-manifold.

    Parameters
    ----------
    vertices : (n_vertices, 3) float64
    face_starts : (n_faces + 1,) int64
        Face ``f`` owns corners ``face_starts[f]:face_starts[f + 1]``.
    corners : (n_corners,) int64
        Vertex of each face corner.
    lattice : Lattice or None
        Present for periodic scaffolds.
    corner_offsets : (n_corners, dim) int64 or None
        Lattice offset of each face corner (periodic scaffolds only).
    radial_orders : dict or None
        Explicit radial order: edge key ``(a, b, delta_tuple)`` -> tuple of sides in
        slot order.  Overrides the geometric order on those edges.
    labels : (n_edges,) int64 or None
        Default twist labels carried with the scaffold (a labelled design).
    nulls : (n_corners,) bool or None
        Default null edge-sides (side ``c`` is null when ``nulls[c]``).
    name : str
        For messages and catalog metadata.
    """

    vertices: np.ndarray
    face_starts: np.ndarray
    corners: np.ndarray
    lattice: Lattice | None = None
    corner_offsets: np.ndarray | None = None
    radial_orders: dict | None = None
    labels: np.ndarray | None = None
    nulls: np.ndarray | None = None
    name: str = "scaffold"

    def __post_init__(self) -> None:
        set_ = lambda k, v: object.__setattr__(self, k, v)  # noqa: E731
        vertices = np.asarray(self.vertices, dtype=np.float64)
        if vertices.ndim != 2 or vertices.shape[1] != 3 or len(vertices) == 0:
            raise ScaffoldError(f"{self.name}: vertices must be a non-empty (n, 3) array, got shape {vertices.shape}")
        bad = np.flatnonzero(~np.all(np.abs(vertices) <= MAX_COORDINATE, axis=1))  # NaN fails too
        if len(bad):
            raise ScaffoldError(
                f"{self.name}: vertex {bad[0]} coordinate {vertices[bad[0]].tolist()} is not a finite number "
                f"within +-{MAX_COORDINATE:g}"
            )
        set_("vertices", _frozen(vertices, np.float64))
        starts = _frozen(self.face_starts, np.int64)
        corners = _frozen(self.corners, np.int64)
        set_("face_starts", starts)
        set_("corners", corners)
        if starts.ndim != 1 or len(starts) < 2 or starts[0] != 0 or starts[-1] != len(corners):
            raise ScaffoldError(f"{self.name}: the scaffold needs at least one face")
        sizes = np.diff(starts)
        small = np.flatnonzero(sizes < 3)
        if len(small):
            raise ScaffoldError(f"{self.name}: face {small[0]} has {sizes[small[0]]} vertices; a face needs at least 3")
        out = np.flatnonzero((corners < 0) | (corners >= len(vertices)))
        if len(out):
            f = int(np.searchsorted(starts, out[0], side="right") - 1)
            raise ScaffoldError(
                f"{self.name}: face {f}: vertex index {corners[out[0]]} out of range 0..{len(vertices) - 1}"
            )
        if self.lattice is not None:
            if not isinstance(self.lattice, Lattice):
                set_("lattice", Lattice(self.lattice))
            offsets = (
                np.zeros((len(corners), self.lattice.dim), np.int64)
                if self.corner_offsets is None
                else self.corner_offsets
            )
            offsets = np.asarray(offsets)
            if offsets.shape != (len(corners), self.lattice.dim) or not np.issubdtype(offsets.dtype, np.integer):
                raise ScaffoldError(
                    f"{self.name}: corner offsets must be integers of shape ({len(corners)}, {self.lattice.dim}), got {offsets.shape}"
                )
            set_("corner_offsets", _frozen(offsets, np.int64))
        elif self.corner_offsets is not None:
            raise ScaffoldError(f"{self.name}: corner offsets given without a lattice")
        self._check_faces()
        if self.labels is not None:
            set_("labels", _frozen(validate_labels(self, self.labels), np.int64))
        if self.nulls is not None:
            set_("nulls", _frozen(validate_nulls(self, self.nulls), bool))

    def _check_faces(self) -> None:
        """Reject repeated corners and zero-length sides."""
        keys = self.corner_keys
        order = np.lexsort(keys.T[::-1])
        sorted_keys = keys[order]
        same = np.all(sorted_keys[1:] == sorted_keys[:-1], axis=1)
        dup = np.flatnonzero(same & (self.corner_face[order[1:]] == self.corner_face[order[:-1]]))
        if len(dup):
            c = order[dup[0] + 1]
            f = self.corner_face[c]
            raise ScaffoldError(f"{self.name}: face {f} visits vertex {self.corners[c]} twice")
        pos = self.corner_positions
        lengths = np.linalg.norm(pos[self.corner_next] - pos, axis=1)
        scale = max(1.0, float(np.abs(pos).max()))
        short = np.flatnonzero(lengths <= 1e-12 * scale)
        if len(short):
            c = short[0]
            raise ScaffoldError(
                f"{self.name}: face {self.corner_face[c]}: zero-length edge between vertices "
                f"{self.corners[c]} and {self.corners[self.corner_next[c]]}"
            )

    def __repr__(self) -> str:
        cell = f", periodic in {self.dim}D" if self.periodic else ""
        counts = f"{plural(self.n_vertices, 'vertex', 'vertices')}, {plural(self.n_edges, 'edge')}"
        return f"Scaffold({self.name}: {counts}, {plural(self.n_faces, 'face')}{cell})"

    # ---- counts -------------------------------------------------------------
    @property
    def n_vertices(self) -> int:
        """Number of vertices."""
        return int(len(self.vertices))

    @property
    def n_faces(self) -> int:
        """Number of faces."""
        return int(len(self.face_starts) - 1)

    @property
    def n_corners(self) -> int:
        """Number of face corners, which is also the number of face-sides."""
        return int(len(self.corners))

    @property
    def n_edges(self) -> int:
        """Number of edges (edge classes of a periodic scaffold)."""
        return int(len(self.edge_vertices))

    @property
    def periodic(self) -> bool:
        """Whether the scaffold has a lattice (then ``lattice`` and ``corner_offsets`` are set)."""
        return self.lattice is not None

    @property
    def dim(self) -> int:
        """Lattice dimension (0 for a finite scaffold)."""
        return 0 if self.lattice is None else self.lattice.dim

    # ---- corner incidence ---------------------------------------------------
    @cached_property
    def face_sizes(self) -> np.ndarray:
        """(n_faces,) int64: number of corners (and sides) of each face."""
        return _frozen(np.diff(self.face_starts), np.int64)

    @cached_property
    def corner_face(self) -> np.ndarray:
        """(n_corners,) int64: face of each corner."""
        return _frozen(np.repeat(np.arange(self.n_faces), self.face_sizes), np.int64)

    @cached_property
    def corner_next(self) -> np.ndarray:
        """(n_corners,) int64: next corner of the same face (cyclically)."""
        nxt = np.arange(1, self.n_corners + 1, dtype=np.int64)
        nxt[self.face_starts[1:] - 1] = self.face_starts[:-1]
        return _frozen(nxt, np.int64)

    @cached_property
    def corner_prev(self) -> np.ndarray:
        """(n_corners,) int64: previous corner of the same face (cyclically)."""
        prev = np.empty(self.n_corners, np.int64)
        prev[self.corner_next] = np.arange(self.n_corners)
        return _frozen(prev, np.int64)

    @cached_property
    def corner_keys(self) -> np.ndarray:
        """(n_corners, 1 + dim) int64: vertex and lattice offset of each corner."""
        if self.corner_offsets is None:
            return _frozen(self.corners[:, None], np.int64)
        return _frozen(np.column_stack([self.corners, self.corner_offsets]), np.int64)

    @cached_property
    def corner_positions(self) -> np.ndarray:
        """(n_corners, 3) float64: corner positions, unwrapped by their offsets."""
        pos = self.vertices[self.corners]
        if self.lattice is not None and self.corner_offsets is not None:
            pos = pos + self.lattice.translate(self.corner_offsets)
        return _frozen(pos, np.float64)

    @cached_property
    def face_centroids(self) -> np.ndarray:
        """(n_faces, 3) float64: mean of each face's (unwrapped) corner positions."""
        sums = np.add.reduceat(self.corner_positions, self.face_starts[:-1], axis=0)
        return _frozen(sums / self.face_sizes[:, None], np.float64)

    # ---- edges ----------------------------------------------------------------
    @cached_property
    def _edge_table(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        u = self.corner_keys
        w = self.corner_keys[self.corner_next]
        delta = w[:, 1:] - u[:, 1:]
        forward = u[:, 0] < w[:, 0]
        same = u[:, 0] == w[:, 0]
        if self.dim:
            nz = delta != 0
            first = np.argmax(nz, axis=1)
            lex_pos = delta[np.arange(len(delta)), first] > 0
            forward |= same & lex_pos
        a = np.where(forward, u[:, 0], w[:, 0])
        b = np.where(forward, w[:, 0], u[:, 0])
        d = np.where(forward[:, None], delta, -delta)
        sort_keys, side_edge = unique_rows(np.column_stack([a, b, -d]))
        edge_keys = np.column_stack([sort_keys[:, :2], -sort_keys[:, 2:]])
        translation = np.where(forward[:, None], u[:, 1:], w[:, 1:])
        return edge_keys, side_edge.reshape(-1), forward, translation

    @cached_property
    def edge_keys(self) -> np.ndarray:
        """(n_edges, 2 + dim) int64: ``(a, b, delta...)`` per edge, in edge order."""
        return _frozen(self._edge_table[0], np.int64)

    @cached_property
    def edge_vertices(self) -> np.ndarray:
        """(n_edges, 2) int64: vertices ``(a, b)`` of each edge, ``a <= b``."""
        return _frozen(self.edge_keys[:, :2], np.int64)

    @cached_property
    def edge_deltas(self) -> np.ndarray:
        """(n_edges, dim) int64: lattice offset of end ``b`` (empty for finite scaffolds)."""
        return _frozen(self.edge_keys[:, 2:], np.int64)

    @cached_property
    def side_edge(self) -> np.ndarray:
        """(n_corners,) int64: edge of each side."""
        return _frozen(self._edge_table[1], np.int64)

    @cached_property
    def side_forward(self) -> np.ndarray:
        """(n_corners,) bool: side runs from the edge's end ``a`` to end ``b``."""
        return _frozen(self._edge_table[2], bool)

    @cached_property
    def side_translation(self) -> np.ndarray:
        """(n_corners, dim) int64: lattice translation carrying the edge onto the side."""
        return _frozen(self._edge_table[3], np.int64)

    @cached_property
    def edge_degrees(self) -> np.ndarray:
        """(n_edges,) int64: number K of face-sides on each edge."""
        return _frozen(np.bincount(self.side_edge, minlength=self.n_edges), np.int64)

    @cached_property
    def edge_points(self) -> np.ndarray:
        """(n_edges, 2, 3) float64: positions of ends ``a`` and ``b``."""
        pa = self.vertices[self.edge_vertices[:, 0]]
        pb = self.vertices[self.edge_vertices[:, 1]]
        if self.lattice is not None:
            pb = pb + self.lattice.translate(self.edge_deltas)
        return _frozen(np.stack([pa, pb], axis=1), np.float64)

    @cached_property
    def radial(self) -> RadialOrder:
        """The :class:`~lkspace.model.radial.RadialOrder` of every edge."""
        return radial_order(self)

    def dual_graph(self) -> nx.MultiGraph:
        """Return the dual graph as a networkx multigraph.

        A node per face, an edge per scaffold edge of degree 2 joining its two faces
        (attribute ``edge``: the edge index).

        Odd labels on a spanning tree of this graph and even labels elsewhere make a
        single strand on a scaffold whose edges all have degree <= 2.

        Examples
        --------
        >>> import lkspace
        >>> g = lkspace.load("cube").dual_graph()
        >>> g.number_of_nodes(), g.number_of_edges()
        (6, 12)
        """
        import networkx as nx

        graph = nx.MultiGraph()
        graph.add_nodes_from(range(self.n_faces), size=0)
        for f, size in enumerate(self.face_sizes.tolist()):
            graph.nodes[f]["size"] = size
        sides = self.radial.edge_sides
        starts = self.radial.edge_starts
        for e in np.flatnonzero(self.edge_degrees == 2).tolist():
            f, g = self.corner_face[sides[starts[e]]], self.corner_face[sides[starts[e] + 1]]
            graph.add_edge(int(f), int(g), key=e, edge=e)
        return graph

    def edge_name(self, e: int | np.integer) -> str:
        """Human name of edge ``e``: ``"3-7"`` or, periodic, ``"3-7[0,1,0]"``."""
        a, b = self.edge_vertices[e]
        if self.dim:
            return f"{a}-{b}[{','.join(str(x) for x in self.edge_deltas[e])}]"
        return f"{a}-{b}"

    def with_labels(self, labels: ArrayLike | None = None, nulls: ArrayLike | None = None) -> Scaffold:
        """Return a copy carrying default twist ``labels`` and ``nulls`` (validated again)."""
        new_labels, new_nulls = (None if x is None else np.asarray(x) for x in (labels, nulls))
        return replace(self, labels=new_labels, nulls=new_nulls)

    @classmethod
    def from_faces(cls, vertices: ArrayLike, faces: Sequence[Sequence[int]], **kwargs: Any) -> Scaffold:
        """Build from a list of faces, each a sequence of vertex indices.

        Examples
        --------
        >>> s = Scaffold.from_faces([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
        >>> s.n_edges, s.edge_degrees.tolist()
        (3, [1, 1, 1])
        """
        sizes = [len(f) for f in faces]
        starts = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
        corners = np.concatenate([np.asarray(f, dtype=np.int64) for f in faces]) if faces else np.zeros(0, np.int64)
        offsets = kwargs.pop("offsets", None)
        if offsets is not None:
            offsets = np.concatenate(
                [np.asarray(o, dtype=np.int64).reshape(len(f), -1) for o, f in zip(offsets, faces)]
            )
        return cls(
            np.asarray(vertices, dtype=np.float64).reshape(-1, 3), starts, corners, corner_offsets=offsets, **kwargs
        )

    def faces(self) -> list[list[int]]:
        """Faces as lists of vertex indices."""
        return [self.corners[s:e].tolist() for s, e in zip(self.face_starts[:-1], self.face_starts[1:])]

    def content_hash(self) -> str:
        """SHA-256 of the exact combinatorics and positions (hex, 16 chars)."""
        h = hashlib.sha256()
        for arr in (self.vertices, self.face_starts, self.corners):
            h.update(np.ascontiguousarray(arr).tobytes())
        if self.lattice is not None:
            h.update(self.lattice.basis.tobytes())
            h.update(np.ascontiguousarray(self.corner_offsets).tobytes())
        if self.radial_orders:
            h.update(repr(sorted(self.radial_orders.items())).encode())
        return h.hexdigest()[:16]
