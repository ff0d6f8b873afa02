"""Nucleotides on B-DNA double helices along the edges, joined by unpaired nucleotides at the vertices.

Lengths are in nm here and in oxDNA units (``UNIT_NM``) in the result.  Every edge ``(a, b)``
carries one double helix on its own line: base pair ``j`` (``0 .. n-1`` from end ``a``) sits
``RISE_NM`` after the last, and the strand in slot 0 at end ``a`` sits at the angle
``theta_a + (j + 1/2) pi t / n`` about the axis ``a -> b`` (the slot-1 strand opposite it,
``+ pi``): ``t`` half turns over ``n`` base pairs, counter-clockwise (right-handed) for
``t > 0``.  ``theta_a`` puts the two strands nearest their own faces at end ``a``, so after
``t`` half turns the slot-0 strand arrives on the side of slot ``t mod 2``: the twist rule.

Nucleotides follow oxDNA's frame (its standard duplex generator): the centre of mass sits
``CM_RADIUS`` from the axis, ``a1`` points from it to the axis (the backbone site is at
``-0.4 a1``, radius 1 unit), paired nucleotides face each other at one height, and ``a3``
points along the axis toward the 5' neighbour (3' -> 5').

A helix starts ``gap`` from each end vertex: enough for helices meeting at the vertex at
angle ``alpha`` not to touch (``CLEAR_NM / sin(alpha / 2)``).  The **scale** (nm per mesh
unit) is the smallest that fits every edge's helix and gaps; longer edges leave slack, which
the corner linkers take up.  A linker is a straight run of unpaired nucleotides, at most
``LINK_STEP_NM`` apart, from the last nucleotide of one helix to the first of the next.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import GeometryError, TooLargeError
from ..model.scaffold import Scaffold
from .model import SIGN, Passes

UNIT_NM = 0.8518
"""oxDNA length unit in nm."""
RISE_NM = 0.332
"""Rise per base pair of B-DNA, nm."""
CM_RADIUS = 0.6
"""Distance of a paired nucleotide's centre of mass from the helix axis, oxDNA units."""
BACKBONE = 0.4
"""Distance of the backbone site behind the centre of mass, ``r - 0.4 a1`` (oxDNA units)."""
CLEAR_NM = 1.4
"""Half the least distance between the axes' ends of two helices at a vertex, nm."""
COINCIDE = 0.1
"""Two faces of an edge whose directions from it differ by less (a chord of the unit circle) lie on one side."""
NORMAL_SHARE = 0.35
"""There, each strand's side is moved toward its face's front by this share of the unit direction."""
LINK_STEP_NM = 0.6
"""Largest step between consecutive unpaired nucleotides of a corner linker, nm."""
MAX_NUCLEOTIDES = 1_000_000
"""Most nucleotides :func:`place` builds (about 0.5 kB each while placed): a scale far past the
smallest that fits would stretch the linkers between helices without bound."""


@dataclass(frozen=True)
class Nucleotides:
    """Every nucleotide of the design, strand after strand, each strand 5' -> 3'.

    Attributes
    ----------
    position, a1, a3 : (n, 3) float64
        Centre of mass (oxDNA units) and the unit vectors of oxDNA's frame.
    strand_starts : (n_strands + 1,) int64
    pair : (n,) int64
        Index of the paired nucleotide, -1 for an unpaired (linker) one.
    edge, index : (n,) int64
        Edge of a paired nucleotide and its base-pair number from end ``a`` (-1 on linkers).
    slot : (n,) int64
        Slot at end ``a`` of the pass a paired nucleotide is on (-1 on linkers).
    scale : float
        nm per mesh unit.
    """

    position: np.ndarray
    a1: np.ndarray
    a3: np.ndarray
    strand_starts: np.ndarray
    pair: np.ndarray
    edge: np.ndarray
    index: np.ndarray
    slot: np.ndarray
    scale: float


def edge_frames(scaffold: Scaffold) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Per edge: axis ``d``, perpendicular unit ``e1``, ``e2 = d x e1`` (each (n_edges, 3)) and length (n_edges,)."""
    p = scaffold.vertices
    ab = scaffold.edge_vertices
    vec = p[ab[:, 1]] - p[ab[:, 0]]
    length = np.linalg.norm(vec, axis=1)
    d = vec / length[:, None]
    helper = np.where(np.abs(d[:, :1]) < 0.9, [[1.0, 0, 0]], [[0, 1.0, 0]])
    e1 = helper - np.sum(helper * d, axis=1)[:, None] * d
    e1 /= np.linalg.norm(e1, axis=1)[:, None]
    return d, e1, np.cross(d, e1), length


def start_angles(scaffold: Scaffold, d: np.ndarray, e1: np.ndarray, e2: np.ndarray) -> np.ndarray:
    """(n_edges,) ``theta_a``: the slot-0 strand's angle at end ``a``, its faces' directions balanced."""
    r = scaffold.radial
    sides = r.edge_sides.reshape(-1, 2)  # every edge has degree 2 here
    centroid = scaffold.face_centroids[scaffold.corner_face[sides]]  # (n_edges, 2, 3)
    rel = centroid - scaffold.vertices[scaffold.edge_vertices[:, 0]][:, None, :]
    x, y = np.einsum("eij,ej->ei", rel, e1), np.einsum("eij,ej->ei", rel, e2)
    norm = np.hypot(x, y)
    x, y = x / norm, y / norm
    # faces on one side of the edge (a two-sided polygon): each strand moves to its face's front, as realize does
    normal = face_normals(scaffold)[scaffold.corner_face[sides]]
    close = np.hypot(x[:, 0] - x[:, 1], y[:, 0] - y[:, 1]) < COINCIDE
    h = np.where(close, NORMAL_SHARE, 0.0)[:, None]
    x = x + h * np.einsum("eij,ej->ei", normal, e1)
    y = y + h * np.einsum("eij,ej->ei", normal, e2)
    phi = np.arctan2(y, x)
    return np.asarray(np.angle(np.exp(1j * phi[:, 0]) + np.exp(1j * (phi[:, 1] - np.pi))))


def vertex_gaps(scaffold: Scaffold, d: np.ndarray) -> np.ndarray:
    """(n_vertices,) distance in nm from a vertex to the helices' ends, from the smallest angle between its edges."""
    ab = scaffold.edge_vertices
    gaps = np.full(scaffold.n_vertices, CLEAR_NM)
    for v in np.unique(ab):
        out = np.concatenate([d[ab[:, 0] == v], -d[ab[:, 1] == v]])
        cos = np.clip(out @ out.T, -1, 1)
        np.fill_diagonal(cos, -1)
        alpha = np.arccos(cos.max())
        gaps[v] = CLEAR_NM / max(np.sin(alpha / 2), 0.2)
    return gaps


def fit_scale(
    scaffold: Scaffold, bp: np.ndarray, gaps: np.ndarray, length: np.ndarray, nm_per_unit: float | None
) -> float:
    """Return the nm per mesh unit: the smallest that fits every helix and its gaps, or ``nm_per_unit`` checked."""
    ab = scaffold.edge_vertices
    need = (bp - 1) * RISE_NM + gaps[ab[:, 0]] + gaps[ab[:, 1]]
    if nm_per_unit is None:
        return float(np.max(need / length))
    scale = nm_per_unit
    per_nm = scaffold.n_corners * float(np.max(length)) / LINK_STEP_NM  # linker nucleotides per nm of scale, at most
    most = (MAX_NUCLEOTIDES - 2 * int(bp.sum())) / per_nm
    if scale > most:
        raise TooLargeError(
            f"{scaffold.name}: at `nm_per_unit` {scale:g} nm the linkers between its helices could need more than "
            f"the {MAX_NUCLEOTIDES:,} nucleotides lkspace builds; use a scale of at most {max(most, 0):.4g}",
            parameter="nm_per_unit",
        )
    short = np.flatnonzero(need > scale * length * (1 + 1e-9))
    if len(short):
        e = int(short[np.argmax(need[short] / length[short])])
        raise GeometryError(
            f"{scaffold.name}: at `nm_per_unit` {scale:g} nm, edge {e} ({scaffold.edge_name(e)}) is {scale * length[e]:.3g} nm, "
            f"but its {int(bp[e])} base pairs and the vertex gaps need {need[e]:.3g} nm; "
            f"use a scale of at least {float(np.max(need / length)):.4g}",
            usage=True,
            parameter="nm_per_unit",
        )
    return scale


def check_size(scaffold: Scaffold, bp: np.ndarray, length: np.ndarray, scale: float | None) -> None:
    """Refuse a design of more than :data:`MAX_NUCLEOTIDES` before any is placed: helices, then linkers at ``scale``.

    The linkers' count is bounded by the triangle inequality: the linker at a corner spans at
    most the slack its two edges leave at that vertex (``scale * length - (bp - 1) * RISE_NM``
    in all, over both ends of an edge) and the helices' radii, one nucleotide per
    ``LINK_STEP_NM`` and one more.  At the default scale the shortest edge for its base pairs
    sets the scale, so long edges beside it leave long linkers.
    """
    helices = 2.0 * float(bp.sum(dtype=np.float64))
    name, most = scaffold.name, MAX_NUCLEOTIDES
    if helices > most:
        raise TooLargeError(
            f"{name}: its helices alone need {_count(helices)} nucleotides, past the {most:,} lkspace builds; "
            "use smaller twists (each half turn is about 5 base pairs) or a smaller mesh",
            parameter="labels",
        )
    if scale is None:
        return
    linkers = linker_bound(scaffold, bp, length, scale)
    if helices + linkers > most:
        raise TooLargeError(
            f"{name}: at {scale:.4g} nm per mesh unit its linkers could need {linkers:,.0f} nucleotides beside "
            f"{helices:,.0f} in its helices, past the {most:,} lkspace builds; make its edges more even in length "
            "for their twists (the shortest for its base pairs sets the scale) or use a smaller mesh",
            parameter="nm_per_unit",
        )


def linker_bound(scaffold: Scaffold, bp: np.ndarray, length: np.ndarray, scale: float) -> float:
    """Return at most how many unpaired nucleotides the corner linkers take at ``scale`` (:func:`check_size`)."""
    slack = np.maximum(scale * length - (bp - 1) * RISE_NM, 0.0)
    per_corner = 2 * UNIT_NM * (CM_RADIUS + BACKBONE) / LINK_STEP_NM + 1
    return 2 * float(slack.sum()) / LINK_STEP_NM + scaffold.n_corners * per_corner


def _count(n: float) -> str:
    """``n`` in words for a message: with commas up to 10**15 (exact there), past it in powers of ten."""
    return f"{n:,.0f}" if n < 1e15 else f"{n:.3g}"


def place(
    scaffold: Scaffold, labels: np.ndarray, bp: np.ndarray, passes: Passes, nm_per_unit: float | None
) -> Nucleotides:
    """Place every nucleotide of the oriented ``passes`` (see the module docstring)."""
    d, e1, e2, length = edge_frames(scaffold)
    theta_a = start_angles(scaffold, d, e1, e2)
    gaps = vertex_gaps(scaffold, d)
    check_size(scaffold, bp, length, None)
    s = fit_scale(scaffold, bp, gaps, length, nm_per_unit)
    check_size(scaffold, bp, length, s)
    ab = scaffold.edge_vertices
    pts = scaffold.vertices * s
    t = SIGN * np.asarray(labels, np.float64)
    start = gaps[ab[:, 0]] + 0.5 * (s * length - (bp - 1) * RISE_NM - gaps[ab[:, 0]] - gaps[ab[:, 1]])
    normals = face_normals(scaffold)
    cols: dict[str, list] = {k: [] for k in ("pos", "a1", "a3", "edge", "index", "slot")}
    starts = [0]
    for k in range(len(passes.starts) - 1):
        first = len(cols["pos"])
        for i in range(passes.starts[k], passes.starts[k + 1]):
            e, side, from_a = int(passes.edge[i]), int(passes.slot[i]), bool(passes.from_a[i])
            n = int(bp[e])
            j = np.arange(n) if from_a else np.arange(n)[::-1]
            theta = theta_a[e] + (j + 0.5) * np.pi * t[e] / n + np.pi * side
            radial = np.cos(theta)[:, None] * e1[e] + np.sin(theta)[:, None] * e2[e]
            axis = pts[ab[e, 0]] + (start[e] + j * RISE_NM)[:, None] * d[e]
            pos = axis / UNIT_NM + CM_RADIUS * radial
            if len(cols["pos"]) > first:
                ends = (cols["pos"][-1], cols["a1"][-1], pos[0], -radial[0])
                link(cols, ends, normals[scaffold.corner_face[passes.corner[i]]])
            cols["pos"].extend(pos)
            cols["a1"].extend(-radial)
            cols["a3"].extend(np.repeat((-d[e] if from_a else d[e])[None], n, axis=0))
            cols["edge"].extend([e] * n)
            cols["index"].extend(j.tolist())
            cols["slot"].extend([side] * n)
        c = passes.corner[passes.starts[k]]
        link(
            cols,
            (cols["pos"][-1], cols["a1"][-1], cols["pos"][first], cols["a1"][first]),
            normals[scaffold.corner_face[c]],
        )
        starts.append(len(cols["pos"]))
    edge = np.asarray(cols["edge"], np.int64)
    index = np.asarray(cols["index"], np.int64)
    slot = np.asarray(cols["slot"], np.int64)
    return Nucleotides(
        np.asarray(cols["pos"]),
        np.asarray(cols["a1"]),
        np.asarray(cols["a3"]),
        np.asarray(starts, np.int64),
        pairs(edge, index, slot, bp),
        edge,
        index,
        slot,
        s,
    )


def link(
    cols: dict[str, list], ends: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray], normal: np.ndarray
) -> None:
    """Append the unpaired nucleotides of a straight linker between two nucleotides.

    ``ends = (p, a1_p, q, a1_q)``: centres of mass (oxDNA units) and ``a1`` of the nucleotide
    before and after; the linker's backbone sites lie evenly on the segment between theirs,
    at most ``LINK_STEP_NM`` apart, and its ``a1`` is perpendicular to the segment, in the face.
    """
    p, a1_p, q, a1_q = ends
    bb_p = p - BACKBONE * a1_p
    bb_q = q - BACKBONE * a1_q
    gap = float(np.linalg.norm(bb_q - bb_p))
    m = max(1, int(np.ceil(gap * UNIT_NM / LINK_STEP_NM)) - 1)
    tangent = (bb_q - bb_p) / gap
    a1 = np.cross(tangent, normal)
    a1 /= np.linalg.norm(a1)
    for i in range(1, m + 1):
        cols["pos"].append(bb_p + (bb_q - bb_p) * i / (m + 1) + BACKBONE * a1)
        cols["a1"].append(a1)
        cols["a3"].append(-tangent)
        cols["edge"].append(-1)
        cols["index"].append(-1)
        cols["slot"].append(-1)


def face_normals(scaffold: Scaffold) -> np.ndarray:
    """(n_faces, 3) unit normals (Newell's method over each face's corners)."""
    p = scaffold.corner_positions
    q = p[scaffold.corner_next]
    cross = np.cross(p, q)
    n = np.zeros((scaffold.n_faces, 3))
    np.add.at(n, scaffold.corner_face, cross)
    return n / np.linalg.norm(n, axis=1)[:, None]


def pairs(edge: np.ndarray, index: np.ndarray, slot: np.ndarray, bp: np.ndarray) -> np.ndarray:
    """(n,) partner of every nucleotide: same edge and base-pair number, the other slot (-1 on linkers)."""
    offsets = np.concatenate([[0], np.cumsum(bp)])
    key = np.where(edge >= 0, 2 * (offsets[np.maximum(edge, 0)] + index) + slot, -1)
    where = np.full(2 * int(offsets[-1]), -1, np.int64)
    paired = np.flatnonzero(edge >= 0)
    where[key[paired]] = paired
    out = np.full(len(edge), -1, np.int64)
    out[paired] = where[key[paired] ^ 1]
    return out
