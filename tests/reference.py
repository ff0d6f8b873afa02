"""A slow, independent reference implementation of the strand model (tests only).

Written straight from the model's rules (docs/model.md) with Python dicts and ``math``: it shares no code with
``lkspace`` beyond reading the scaffold's raw arrays.
"""

from __future__ import annotations

import math
from collections import defaultdict


def _sub(p, q):
    return [p[i] - q[i] for i in range(3)]


def _dot(p, q):
    return sum(p[i] * q[i] for i in range(3))


def _cross(p, q):
    return [p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]]


def reference_trace(vertices, faces, twists, nulls=()):
    """Trace a finite scaffold.

    ``vertices``: list of [x, y, z]; ``faces``: list of vertex lists; ``twists``: dict
    ``(a, b) -> t`` with ``a < b``; ``nulls``: set of ``(face, k)`` sides.
    Returns a list of strands, each ``(closed, faces_in_order)``.
    """
    # edges and their sides
    edge_sides = defaultdict(list)  # (a, b) -> [(face, k)]
    for f, face in enumerate(faces):
        for k in range(len(face)):
            u, w = face[k], face[(k + 1) % len(face)]
            edge_sides[(min(u, w), max(u, w))].append((f, k))
    # radial order: angle of centroid offset about the axis a->b
    slots = {}
    for (a, b), sides in edge_sides.items():
        pa, pb = vertices[a], vertices[b]
        d = _sub(pb, pa)
        n = math.sqrt(_dot(d, d))
        d = [x / n for x in d]
        ref = [1.0, 0.0, 0.0] if abs(d[0]) < 0.9 else [0.0, 1.0, 0.0]
        u1 = _cross(ref, d)
        nu = math.sqrt(_dot(u1, u1))
        u1 = [x / nu for x in u1]
        u2 = _cross(d, u1)

        def angle(side, pa=pa, u1=u1, u2=u2):
            face = faces[side[0]]
            c = [sum(vertices[v][i] for v in face) / len(face) for i in range(3)]
            r = _sub(c, pa)
            return math.atan2(_dot(r, u2), _dot(r, u1))

        slots[(a, b)] = sorted(sides, key=angle)

    # port = (face, k, which) with which = "start" (at vertex face[k]) or "end"
    def vertex_of(port):
        f, k, which = port
        face = faces[f]
        return face[k] if which == "start" else face[(k + 1) % len(face)]

    corner = {}
    for f, face in enumerate(faces):
        m = len(face)
        for k in range(m):
            corner[(f, k, "end")] = (f, (k + 1) % m, "start")
            corner[(f, (k + 1) % m, "start")] = (f, k, "end")
    edge = {}
    for (a, b), order in slots.items():
        K = len(order)
        t = twists[(a, b)]
        for i, (f, k) in enumerate(order):
            g, j = order[(i + t) % K]
            pa = (f, k, "start") if vertex_of((f, k, "start")) == a else (f, k, "end")
            pb = (g, j, "start") if vertex_of((g, j, "start")) == b else (g, j, "end")
            if (f, k) in nulls:
                continue
            edge[pa] = pb
            edge[pb] = pa
    strands = []
    seen = set()
    starts = [p for p in corner if p not in edge] + list(corner)
    for p0 in starts:
        if p0 in seen:
            continue
        seq = []
        p = p0
        closed = None
        while True:
            q = corner[p]
            seen.update((p, q))
            seq.append(p[0])
            if q not in edge:
                closed = False
                break
            p = edge[q]
            if p == p0:
                closed = True
                break
        strands.append((closed, seq))
    return strands
