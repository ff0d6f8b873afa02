"""Articulated scaffolds from the paper: a cube net, a cube with a lid, hinged cubes.

* ``cube-net``: the six squares of a cube unfolded flat into a cross (a disk: every
  fold edge has degree 2, the outline is boundary).
* ``cube-lid``: an open box whose top face is swung open by 90 degrees about one top
  edge (the lid hinge has degree 2; the box rim is boundary).
* ``cubes:piano``: two cubes sharing one edge (a piano hinge of degree 4).
* ``cubes:vertex``: two cubes sharing one vertex (faces meet only there).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ..model.scaffold import Scaffold
from .polyhedra import cube


def _merge(parts: list[tuple[np.ndarray, list[list[int]]]], name: str) -> Scaffold:
    """Union of (vertices, faces) parts, merging coincident vertices (exactly, after rounding)."""
    points = np.concatenate([p for p, _ in parts])
    keys = np.round(points, 9)
    unique, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    order = np.argsort(first)  # keep first-appearance order
    renumber = np.empty(len(order), np.int64)
    renumber[order] = np.arange(len(order))
    faces, base = [], 0
    for p, fs in parts:
        faces += [renumber[inverse.reshape(-1)[base + np.asarray(f)]].tolist() for f in fs]
        base += len(p)
    return Scaffold.from_faces(points[first[order]], faces, name=name)


def _unit_cube(shift: ArrayLike) -> tuple[np.ndarray, list[list[int]]]:
    c = cube()
    return (c.vertices + 1) / 2 + np.asarray(shift, dtype=float), c.faces()


def cube_net() -> Scaffold:
    """Build six unit squares in a cross: a column of four plus two arms."""
    cells = [(0, 0), (0, 1), (0, 2), (0, 3), (-1, 1), (1, 1)]
    parts = []
    for x, y in cells:
        square = np.array([[x, y, 0], [x + 1, y, 0], [x + 1, y + 1, 0], [x, y + 1, 0]], dtype=float)
        parts.append((square, [[0, 1, 2, 3]]))
    return _merge(parts, "cube-net")


def cube_lid() -> Scaffold:
    """Build a unit open box (no top) with its lid opened 90 degrees about the top edge y = 1."""
    box = [
        (np.array(q, dtype=float), [[0, 1, 2, 3]])
        for q in (
            [[0, 0, 0], [0, 1, 0], [1, 1, 0], [1, 0, 0]],  # bottom
            [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1]],  # front
            [[0, 1, 0], [0, 1, 1], [1, 1, 1], [1, 1, 0]],  # back
            [[0, 0, 0], [0, 0, 1], [0, 1, 1], [0, 1, 0]],  # left
            [[1, 0, 0], [1, 1, 0], [1, 1, 1], [1, 0, 1]],  # right
            [[0, 1, 1], [0, 1, 2], [1, 1, 2], [1, 1, 1]],  # lid, standing up from the back edge
        )
    ]
    return _merge(box, "cube-lid")


def piano_hinged_cubes() -> Scaffold:
    """Build two unit cubes sharing the edge x = y = 1 (degree 4)."""
    return _merge([_unit_cube((0, 0, 0)), _unit_cube((1, 1, 0))], "cubes:piano")


def vertex_hinged_cubes() -> Scaffold:
    """Build two unit cubes sharing the vertex (1, 1, 1)."""
    return _merge([_unit_cube((0, 0, 0)), _unit_cube((1, 1, 1))], "cubes:vertex")


HINGED = {
    "cube-net": cube_net,
    "cube-lid": cube_lid,
    "cubes:piano": piano_hinged_cubes,
    "cubes:vertex": vertex_hinged_cubes,
}
