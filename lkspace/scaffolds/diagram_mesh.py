"""A link diagram (PD code) made into a twist design: its checkerboard mesh with twist labels.

Colour the regions of a connected diagram on the sphere like a checkerboard.  The regions
of one colour become the **faces** of a mesh M, those of the other colour its **vertices**,
and every crossing an **edge**: the edge joins the two vertex-coloured regions at the
crossing and separates the two face-coloured ones.  Each face's strand runs around the
inside of its region, and at an edge with twist ±1 the two strands along it exchange
sides: the strands of (M, labels) are the medial link of M, which is the diagram again.
Conventions of the PD code (KnotTheory, SnapPy, KnotInfo): ``X[a, b, c, d]`` lists the four
edge labels at a crossing counter-clockwise, ``a`` and ``c`` on the under-strand.

* **Twist sign.**  Turn the over-strand counter-clockwise: if it sweeps the face-coloured
  corners (between positions 1-2 and 3-0), the label is +1, else -1 (:data:`SIGN`).  A
  right-handed half twist of two strands makes this crossing; the mirror image negates
  every label.
* **Twist regions.**  A vertex-coloured bigon is a vertex of M with two edges in series
  between the same two faces: the two crossings are one twist region, and the edges are
  merged into one whose label is the sum (``i -> i + t1 -> i + t1 + t2``).
* **Simple faces.**  A mesh face is a cycle of at least three distinct vertices and two
  edges never share both ends (SPEC §1).  A face-coloured bigon (two edges between the
  same two vertices) is made a triangle by splitting one of its edges in two, labels
  ``t, 0``: two edges in series add up, so the strands are unchanged.
* **Nugatory crossings** (a region meeting itself at a crossing) are smoothed first, the
  way that keeps the diagram connected: the link type does not change.
* **Composite diagrams** (a face meeting a vertex twice: a circle through that face and
  vertex cuts the diagram in two points): the vertex splits in two, joined by a new edge
  with label 0.  A label 0 is no crossing (the black regions at its ends are one), so the
  strands do not change, and the face meets each half once.

:func:`diagram_mesh` returns faces and labels; :mod:`lkspace.scaffolds.sphere_layout`
places the vertices.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from ..errors import ScaffoldError

SIGN = -1
"""Label of a crossing whose counter-clockwise turn of the over-strand sweeps the face-coloured corners."""


@dataclass(frozen=True)
class DiagramMesh:
    """The checkerboard mesh of a diagram with its labels.

    ``faces``: vertex cycles (lists of vertex indices, each of length >= 3);
    ``edges``: ``(n_edges, 2)`` vertex pairs as a list of tuples, in no special order;
    ``labels``: the twist of each of ``edges``; ``n_vertices``; ``crossings``: crossings of
    the diagram the mesh was made from (after nugatory crossings were smoothed).
    """

    n_vertices: int
    faces: list[list[int]]
    edges: list[tuple[int, int]]
    labels: list[int]
    crossings: int


def check_pd(pd: Sequence[Sequence[int]], where: str = "PD code") -> list[tuple[int, int, int, int]]:
    """Return the PD code as tuples after checking it is one: four labels a crossing, each label twice."""
    out: list[tuple[int, int, int, int]] = []
    seen: dict[int, int] = {}
    for i, x in enumerate(pd):
        if not isinstance(x, (list, tuple)) or len(x) != 4 or not all(isinstance(v, int) for v in x):
            raise ScaffoldError(f"{where}: crossing {i + 1} is {x!r}; a crossing is four integer edge labels")
        out.append((int(x[0]), int(x[1]), int(x[2]), int(x[3])))
        for v in x:
            seen[int(v)] = seen.get(int(v), 0) + 1
    odd = sorted(v for v, n in seen.items() if n != 2)
    if odd:
        raise ScaffoldError(
            f"{where}: edge label {odd[0]} occurs {seen[odd[0]]} {'time' if seen[odd[0]] == 1 else 'times'}; "
            "in a link diagram every label occurs twice"
        )
    return out


def _faces(pd: list[tuple[int, int, int, int]]) -> tuple[list[int], list[int], int]:
    """Darts ``4 c + p`` (leave crossing c at position p): the other end of each, and the face of each.

    Faces are the orbits of ``sigma . alpha`` (alpha: the other end of the edge; sigma: the
    next position counter-clockwise).  Returns ``(alpha, face_of, n_faces)``.
    """
    ends: dict[int, list[int]] = {}
    for c, x in enumerate(pd):
        for p, label in enumerate(x):
            ends.setdefault(label, []).append(4 * c + p)
    alpha = [0] * (4 * len(pd))
    for a, b in ends.values():
        alpha[a], alpha[b] = b, a
    face_of = [-1] * len(alpha)
    n_faces = 0
    for start in range(len(alpha)):
        d = start
        while face_of[d] < 0:
            face_of[d] = n_faces
            o = alpha[d]
            d = o - o % 4 + (o + 1) % 4
        if face_of[start] == n_faces:
            n_faces += 1
    return alpha, face_of, n_faces


def _corner_face(face_of: list[int], c: int, k: int) -> int:
    """Return the region in corner k of crossing c (between positions k and k + 1)."""
    return face_of[4 * c + (k + 1) % 4]


def smooth_nugatory(pd: list[tuple[int, int, int, int]]) -> tuple[list[tuple[int, int, int, int]], int]:
    """Smooth nugatory crossings (a region in two opposite corners) until none is left.

    Returns the PD code left and the number of closed loops freed (a kink of an unknot
    leaves its component with no crossing at all).
    """
    pd = list(pd)
    freed = 0
    while pd:
        _, face_of, _ = _faces(pd)
        found = next(
            (
                (c, k)
                for c in range(len(pd))
                for k in (0, 1)
                if _corner_face(face_of, c, k) == _corner_face(face_of, c, k + 2)
            ),
            None,
        )
        if found is None:
            break
        c, k = found
        x = pd.pop(c)
        # the region in corners k and k + 2 is cut; corners k + 1 and k + 3 merge: join (k, k+1) and (k+2, k+3)
        for p, q in ((k, k + 1), (k + 2, k + 3)):
            keep, gone = x[p % 4], x[q % 4]
            if keep == gone:
                freed += 1
                continue
            pd = [tuple(keep if v == gone else v for v in y) for y in pd]  # type: ignore[misc]
            x = tuple(keep if v == gone else v for v in x)  # type: ignore[assignment]
    return pd, freed


class _Mesh:
    """A plane mesh under edit: faces as lists of edge ids with the vertex each edge leads to."""

    def __init__(self) -> None:
        self.ends: list[list[int]] = []  # edge -> [u, v]
        self.labels: list[int] = []
        self.faces: list[list[tuple[int, int]]] = []  # face -> [(edge, vertex reached), ...]
        self.n_vertices = 0

    def vertices_of(self, face: list[tuple[int, int]]) -> list[int]:
        return [v for _, v in face]

    def split_edge(self, e: int) -> None:
        """Split edge e = (u, v) at a new vertex w: (u, w) keeps the label, (w, v) gets 0."""
        u, v = self.ends[e]
        w = self.n_vertices
        self.n_vertices += 1
        f = len(self.ends)
        self.ends[e] = [u, w]
        self.ends.append([w, v])
        self.labels.append(0)
        for face in self.faces:
            for i, (edge, reached) in enumerate(face):
                if edge != e:
                    continue
                if reached == v:  # u -> w -> v
                    face[i : i + 1] = [(e, w), (f, v)]
                else:  # v -> w -> u
                    face[i : i + 1] = [(f, w), (e, u)]
                break


def _build(pd: list[tuple[int, int, int, int]], colour: int) -> _Mesh:
    """Return the checkerboard mesh whose faces are the regions of ``colour`` (0 or 1)."""
    alpha, face_of, n_regions = _faces(pd)
    colours = _checkerboard(alpha, face_of, n_regions)
    mesh = _Mesh()
    vertex_of: dict[int, int] = {}
    for r in range(n_regions):
        if colours[r] != colour:
            vertex_of[r] = len(vertex_of)
    mesh.n_vertices = len(vertex_of)
    for c in range(len(pd)):
        face_corners = [k for k in range(4) if colours[_corner_face(face_of, c, k)] == colour]
        v1, v2 = (vertex_of[_corner_face(face_of, c, k)] for k in range(4) if k not in face_corners)
        mesh.ends.append([v1, v2])
        mesh.labels.append(SIGN if face_corners == [1, 3] else -SIGN)
    done: set[int] = set()
    for start in range(len(alpha)):
        r = face_of[start]
        if colours[r] != colour or r in done:
            continue
        done.add(r)
        d, face = start, []
        while True:  # edge crossing(d) of M leads to the vertex-coloured region across d's diagram edge
            face.append((d // 4, vertex_of[face_of[alpha[d]]]))
            o = alpha[d]
            d = o - o % 4 + (o + 1) % 4
            if d == start:
                break
        mesh.faces.append(face)
    return mesh


def _checkerboard(alpha: list[int], face_of: list[int], n_regions: int) -> list[int]:
    """Colour regions 0/1 so the two sides of every edge differ (a connected diagram only)."""
    colours = [-1] * n_regions
    colours[0] = 0
    stack = [0]
    neighbours: list[set[int]] = [set() for _ in range(n_regions)]
    for d, o in enumerate(alpha):
        neighbours[face_of[d]].add(face_of[o])
    while stack:
        r = stack.pop()
        for s in neighbours[r]:
            if colours[s] < 0:
                colours[s] = 1 - colours[r]
                stack.append(s)
    return colours


def _merge_series(mesh: _Mesh) -> None:
    """Merge the two edges at every vertex of degree 2 into one edge (their labels add up)."""
    kept: set[int] = set()  # degree 2 between one vertex twice: merging would make a loop
    while True:
        incident: dict[int, list[int]] = {}
        for e, (u, v) in enumerate(mesh.ends):
            if u >= 0:
                incident.setdefault(u, []).append(e)
                incident.setdefault(v, []).append(e)
        found = next(((w, es) for w, es in incident.items() if len(es) == 2 and w not in kept), None)
        if found is None:
            return
        w, (e1, e2) = found
        u = mesh.ends[e1][0] if mesh.ends[e1][1] == w else mesh.ends[e1][1]
        v = mesh.ends[e2][0] if mesh.ends[e2][1] == w else mesh.ends[e2][1]
        if u == v:
            kept.add(w)
            continue
        mesh.ends[e1] = [u, v]
        mesh.ends[e2] = [-1, -1]
        mesh.labels[e1] += mesh.labels[e2]
        for face in mesh.faces:
            for i in range(len(face)):
                here, after = face[i], face[(i + 1) % len(face)]
                if here[1] == w:  # (e1, w), (e2, v) -> (e1, v); (e2, w), (e1, u) -> (e1, u)
                    face[i] = (e1, after[1])
                    del face[(i + 1) % len(face)]
                    break


def _rotation(mesh: _Mesh, w: int) -> list[tuple[int, int, int]]:
    """Corners at vertex w in rotation order: ``(face, edge in, edge out)``."""
    corners = {}
    for f, face in enumerate(mesh.faces):
        for i, (e_in, v) in enumerate(face):
            if v == w:
                corners[e_in] = (f, e_in, face[(i + 1) % len(face)][0])
    # the corner after (f, e_in, e_out) is the one entering w through e_out
    first = next(iter(corners.values()))
    order, corner = [], first
    while True:
        order.append(corner)
        corner = corners[corner[2]]
        if corner == first:
            return order


def _split_composite(mesh: _Mesh, f: int, w: int) -> None:
    """Face f meets vertex w twice: split w in two, joined by a new edge with label 0.

    An edge with label 0 is no crossing: the two black regions at its ends are one, so the
    strands are unchanged.  The split runs from a corner of another face between f's two
    corners to one on the other side, so f meets each half of w once.
    """
    order = _rotation(mesh, w)
    at = [i for i, corner in enumerate(order) if corner[0] == f]
    i, j = at[0], at[1]
    one, two = order[i + 1 : j], order[j + 1 :] + order[:i]
    c1, c2 = next((c for c in one if c[0] != f), None), next((c for c in two if c[0] != f), None)
    if c1 is None or c2 is None:
        raise ScaffoldError("the diagram has a nugatory crossing left (a region meets itself at a crossing)")
    k1, k2 = order.index(c1), order.index(c2)
    arc = [order[(k1 + s) % len(order)] for s in range(1, (k2 - k1) % len(order) + 1)]
    arc_edges = {c[1] for c in arc}  # edges e_out(c1) .. e_in(c2) stay at w (x1), the others move to x2
    x1, x2 = w, mesh.n_vertices
    mesh.n_vertices += 1
    for e, ends in enumerate(mesh.ends):
        if e not in arc_edges:
            mesh.ends[e] = [x2 if v == w else v for v in ends]
    for face in mesh.faces:
        for i2, (e, v) in enumerate(face):
            if v == w and e not in arc_edges:
                face[i2] = (e, x2)
    new = len(mesh.ends)
    mesh.ends.append([x1, x2])
    mesh.labels.append(0)
    for corner, reached in ((c1, x1), (c2, x2)):  # c1's face enters at x2 and leaves at x1; c2's the other way
        face = mesh.faces[corner[0]]
        k = next(k for k, entry in enumerate(face) if entry[0] == corner[1])
        face.insert(k + 1, (new, reached))


def _repair(mesh: _Mesh) -> None:
    """Split edges and vertices until every face is a cycle of >= 3 distinct vertices and edges are simple."""
    while True:
        bad = next(
            (
                (f, v)
                for f, face in enumerate(mesh.faces)
                for v in {x for _, x in face}
                if sum(x == v for _, x in face) > 1
            ),
            None,
        )
        if bad is None:
            break
        _split_composite(mesh, *bad)
    while True:
        pairs: dict[tuple[int, int], int] = {}
        twin = None
        for e, (u, v) in enumerate(mesh.ends):
            if u < 0:
                continue
            key = (min(u, v), max(u, v))
            if key in pairs:
                twin = e
                break
            pairs[key] = e
        if twin is None:
            return
        mesh.split_edge(twin)


def _finish(mesh: _Mesh, crossings: int) -> DiagramMesh:
    used = sorted({v for ends in mesh.ends for v in ends if v >= 0})
    new = {v: i for i, v in enumerate(used)}
    faces = [[new[v] for _, v in face] for face in mesh.faces]
    edges = [(new[u], new[v]) for u, v in mesh.ends if u >= 0]
    labels = [t for (u, _), t in zip(mesh.ends, mesh.labels) if u >= 0]
    return DiagramMesh(len(used), faces, edges, labels, crossings)


def diagram_mesh(pd: Sequence[Sequence[int]], where: str = "PD code", colouring: str = "fewer") -> DiagramMesh:
    """Return the checkerboard mesh of a connected link diagram, with twist labels (module docstring).

    ``colouring``: ``"fewer"`` keeps the colouring whose mesh has fewer edges (ties: fewer
    vertices, then the first colour), ``"more"`` the other one.  Raises :class:`~lkspace.errors.ScaffoldError` for a code
    that is no link diagram, a split diagram or a diagram with no crossing left.

    Examples
    --------
    >>> m = diagram_mesh([[1, 5, 2, 4], [3, 1, 4, 6], [5, 3, 6, 2]])  # KnotInfo's 3_1
    >>> m.n_vertices, len(m.faces), sum(abs(t) for t in m.labels)  # one twist region of 3 half twists
    (3, 2, 3)
    """
    code, freed = smooth_nugatory(check_pd(pd, where))
    if not code:
        raise ScaffoldError(
            f"{where}: the diagram has no crossing left after smoothing its kinks (an unknot or unlink)"
        )
    alpha, face_of, n_regions = _faces(code)
    components = link_components(code)
    if n_regions != len(code) + 2 or freed:
        raise ScaffoldError(
            f"{where}: not a connected diagram on the sphere ({len(code)} crossings, {n_regions} regions, "
            f"{components + freed} components); split links are made one piece at a time"
        )
    made = []
    for colour in (0, 1):
        mesh = _build(code, colour)
        _merge_series(mesh)
        _repair(mesh)
        made.append(_finish(mesh, len(code)))
    made.sort(key=lambda m: (len(m.edges), m.n_vertices))
    return made[0] if colouring == "fewer" else made[1]


def link_components(pd: list[tuple[int, int, int, int]]) -> int:
    """Count the link components of a PD code (strands continue straight through each crossing)."""
    parent: dict[int, int] = {}

    def find(x: int) -> int:
        while parent.setdefault(x, x) != x:
            x = parent[x]
        return x

    for x in pd:
        for p, q in ((0, 2), (1, 3)):
            parent[find(x[p])] = find(x[q])
    return len({find(v) for x in pd for v in x})
