"""A Blender mesh as an lkspace scaffold, and its attributes as twist labels and null sides.

No ``bpy`` here: the add-on reads a mesh into plain arrays (:class:`MeshArrays`) and this
module does the rest, so it is tested without Blender.

Conventions
-----------
* **Vertices**: the scaffold keeps the mesh vertices that lie on a face, in Blender's
  order (loose vertices are left out), so its vertex ``i`` is Blender vertex
  ``vertex_of[i]``.
* **Faces and corners**: polygon ``p`` is scaffold face ``p``; its loops, in Blender's
  order starting at ``loop_start``, are its corners.  Scaffold corner ``c`` is Blender loop
  ``loop_of[c]``, and scaffold side ``c`` (corner ``c`` to the next corner) is the face
  side Blender calls that loop's edge.
* **Edges**: lkspace numbers edges by vertex pair (``lkspace info --edges``); Blender edge
  ``b`` is lkspace edge ``edge_of[b]`` when its vertex pair is a face side, else ``-1``
  (a loose edge).  ``blender_edge[e]`` goes the other way.
* **Attributes**: ``lk_twist`` is an ``INT`` attribute on the ``EDGE`` domain (the twist of
  each Blender edge), ``lk_null`` a ``BOOLEAN`` attribute on the ``CORNER`` domain (loop
  ``l`` null: the side starting at ``l`` is a null edge-side).  An ``lk_twist`` of another
  integer type (``INT8``) is read as well, a ``FLOAT`` one when every value is a whole number
  within ±(2^31 - 1); anything else (another domain or type, a fraction, a huge float) is
  refused by :func:`check_attribute` / :func:`whole_twists` with a message naming the problem.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..errors import LabelError, ScaffoldError
from ..model.scaffold import Scaffold

TWIST = "lk_twist"
"""Name of the edge attribute holding twist labels."""
NULL = "lk_null"
"""Name of the face-corner attribute marking null edge-sides."""

EXPECTED = {TWIST: ("EDGE", ("INT", "INT8", "FLOAT")), NULL: ("CORNER", ("BOOLEAN",))}
"""Attribute name -> (its domain, the data types read)."""
DOMAINS = {"POINT": "Vertex", "EDGE": "Edge", "FACE": "Face", "CORNER": "Face Corner"}
TYPES = {"INT": "Integer", "INT8": "8-Bit Integer", "FLOAT": "Float", "BOOLEAN": "Boolean", "STRING": "String"}
TYPES |= {"FLOAT_VECTOR": "Vector", "FLOAT_COLOR": "Color", "BYTE_COLOR": "Byte Color", "FLOAT2": "2D Vector"}
TYPES |= {"INT32_2D": "2D Integer Vector", "QUATERNION": "Quaternion", "FLOAT4X4": "4x4 Matrix"}
"""Blender's names (as its Attributes panel shows them) of attribute domains and data types."""
MAX_TWIST = 2**31 - 1
"""Largest twist an ``lk_twist`` attribute holds (Blender's integers are 32-bit)."""


def check_attribute(name: str, domain: str, data_type: str) -> None:
    """Refuse (:class:`~lkspace.errors.LabelError`) attribute ``name`` (:data:`TWIST` or :data:`NULL`) of the wrong domain or type."""
    want_domain, want_types = EXPECTED[name]
    if domain == want_domain and data_type in want_types:
        return
    have = f"{TYPES.get(data_type, data_type)} attribute on the {DOMAINS.get(domain, domain)} domain"
    want = f"{TYPES[want_types[0]]} attribute on the {DOMAINS[want_domain]} domain"
    article = "an" if have[0] in "AEIOU8" else "a"
    raise LabelError(
        f"{name} is {article} {have}; lkspace reads it as an {want} (Object Data > Attributes: "
        f"remove {name}, or re-create it as {TYPES[want_types[0]]} on {DOMAINS[want_domain]})"
    )


def whole_twists(values: ArrayLike) -> np.ndarray:
    """Return the twists of a ``FLOAT`` ``lk_twist`` as int64 if every one is a whole number within ±:data:`MAX_TWIST`.

    Raises :class:`~lkspace.errors.LabelError` naming the first edge that is not (1.5, 2**40, nan).
    """
    v = np.asarray(values, np.float64)
    bad = np.flatnonzero(~np.isfinite(v) | (np.abs(v) > MAX_TWIST) | (v != np.round(v)))
    if len(bad):
        e = int(bad[0])
        raise LabelError(
            f"{TWIST}: edge {e} holds {v[e]:.10g}, not a whole twist within ±{MAX_TWIST:,} "
            f"(twists are integers: make {TWIST} an Integer attribute on the Edge domain)"
        )
    return v.astype(np.int64)


@dataclass(frozen=True)
class MeshArrays:
    """The parts of a Blender mesh lkspace reads.

    Attributes
    ----------
    vertices : (n_vertices, 3) float64
        Vertex positions (object space).
    edges : (n_edges, 2) int64
        Vertex pair of every Blender edge.
    loop_starts, loop_totals : (n_polygons,) int64
        First loop and loop count of every polygon.
    loop_vertices : (n_loops,) int64
        Vertex of every loop (face corner).
    """

    vertices: np.ndarray
    edges: np.ndarray
    loop_starts: np.ndarray
    loop_totals: np.ndarray
    loop_vertices: np.ndarray


@dataclass(frozen=True, eq=False)
class MeshDesign:
    """A scaffold made from a mesh and the maps between the two numberings.

    Attributes
    ----------
    scaffold : Scaffold
    vertex_of : (n_scaffold_vertices,) int64
        Blender vertex of each scaffold vertex.
    loop_of : (n_corners,) int64
        Blender loop of each scaffold corner (and side).
    edge_of : (n_blender_edges,) int64
        lkspace edge of each Blender edge, ``-1`` for a loose edge.
    blender_edge : (n_lkspace_edges,) int64
        Blender edge of each lkspace edge.
    """

    scaffold: Scaffold
    vertex_of: np.ndarray
    loop_of: np.ndarray
    edge_of: np.ndarray
    blender_edge: np.ndarray

    def labels(self, edge_twists: ArrayLike) -> np.ndarray:
        """(n_lkspace_edges,) int64 labels from ``edge_twists (n_blender_edges,)``, the ``lk_twist`` values."""
        return np.asarray(edge_twists, np.int64)[self.blender_edge]

    def edge_twists(self, labels: ArrayLike, previous: ArrayLike) -> np.ndarray:
        """``previous (n_blender_edges,)`` twists with the face edges set to ``labels`` (lkspace order)."""
        out = np.array(previous, np.int64)
        out[self.blender_edge] = np.asarray(labels, np.int64)
        return out

    def nulls(self, loop_nulls: ArrayLike) -> np.ndarray:
        """(n_corners,) bool null sides from ``loop_nulls (n_loops,)``, the ``lk_null`` values."""
        return np.asarray(loop_nulls, bool)[self.loop_of]


def mesh_design(mesh: MeshArrays, name: str = "mesh") -> MeshDesign:
    """Build the scaffold of ``mesh`` and the maps between Blender's and lkspace's numbering.

    Raises :class:`~lkspace.errors.ScaffoldError` for a mesh without faces and for one whose
    Blender edges do not cover every face side (Blender always has them; a mesh from another
    tool may not).

    Examples
    --------
    >>> square = MeshArrays(
    ...     vertices=np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [5, 5, 5]], float),
    ...     edges=np.array([[2, 3], [0, 1], [1, 2], [3, 0], [3, 4]]),
    ...     loop_starts=np.array([0]), loop_totals=np.array([4]), loop_vertices=np.array([0, 1, 2, 3]))
    >>> d = mesh_design(square, "square")
    >>> d.scaffold.edge_vertices.tolist()
    [[0, 1], [0, 3], [1, 2], [2, 3]]
    >>> d.edge_of.tolist(), d.blender_edge.tolist()
    ([3, 0, 2, 1, -1], [1, 3, 2, 0])
    """
    starts = np.asarray(mesh.loop_starts, np.int64)
    totals = np.asarray(mesh.loop_totals, np.int64)
    if len(starts) == 0:
        raise ScaffoldError(f"{name}: the mesh has no faces; lkspace needs polygons whose edges carry the twists")
    loop_of = np.concatenate([np.arange(s, s + n) for s, n in zip(starts.tolist(), totals.tolist())])
    loop_vertices = np.asarray(mesh.loop_vertices, np.int64)[loop_of]
    vertex_of, corners = np.unique(loop_vertices, return_inverse=True)
    vertices = np.asarray(mesh.vertices, np.float64)[vertex_of]
    face_starts = np.concatenate([[0], np.cumsum(totals)])
    scaffold = Scaffold(vertices, face_starts, corners.reshape(-1), name=name)
    edges = np.sort(np.asarray(mesh.edges, np.int64).reshape(-1, 2), axis=1)
    n = int(np.asarray(mesh.vertices).shape[0])
    blender_keys = edges[:, 0] * n + edges[:, 1]
    pairs = vertex_of[scaffold.edge_vertices]  # lkspace edges in Blender vertex numbers, lower first
    lk_keys = pairs[:, 0] * n + pairs[:, 1]
    order = np.argsort(blender_keys, kind="stable")
    found = np.searchsorted(blender_keys[order], lk_keys)
    found = np.minimum(found, len(order) - 1)
    blender_edge = order[found]
    missing = np.flatnonzero(blender_keys[blender_edge] != lk_keys)
    if len(missing):
        a, b = pairs[missing[0]].tolist()
        raise ScaffoldError(f"{name}: the face side from vertex {a} to vertex {b} has no mesh edge")
    edge_of = np.full(len(edges), -1, np.int64)
    edge_of[blender_edge] = np.arange(len(blender_edge))
    return MeshDesign(scaffold, vertex_of, loop_of, edge_of, blender_edge)
