"""The lkspace scaffold file: JSON, versioned, holding everything the model holds.

Format version 1::

    {
      "format": "lkspace-scaffold", "version": 1,
      "name": "tetrahedron",                       # optional
      "vertices": [[x, y, z], ...],
      "faces": [[v0, v1, v2, ...], ...],           # 0-based vertex indices
      "lattice": [[...3 floats...], ...],          # optional: 2 or 3 basis vectors
      "offsets": [[[i, j, k], ...], ...],          # periodic: lattice offset per face corner
      "radial_orders": [                           # optional explicit radial orders
          {"edge": [a, b], "sides": [[face, k], ...]}, ...],   # periodic: [a, b, [delta]]
      "edges": [[a, b], ...],                      # optional, written for reference; checked
      "labels": [t_0, t_1, ...],                   # optional: twist label per edge, edge order
                                                   # ("twists" is read too: the older key)
      "nulls": [[face, k], ...]                    # optional: null edge-sides
    }

A generalized Voronoi scaffold can be given instead by its lattice and generator points:
``{"format": "lkspace-voronoi", "version": 1, "lattice": [...], "points": [[x, y, z], ...]}``.

A face-side is named ``[face, k]``: side ``k`` of the face runs from its ``k``-th vertex
to the next.  Unknown keys are an error (a typo must not be silently ignored).
"""

from __future__ import annotations

import json
import os
from typing import Any, NotRequired, TypedDict, cast

import numpy as np
from numpy.typing import ArrayLike

from ..errors import ScaffoldError
from ..model.lattice import Lattice
from ..model.scaffold import Scaffold
from ..model.validation import MAX_LABEL
from ..runtime.progress import task
from ..scaffolds.periodic import voronoi_scaffold
from ..words import noun
from .json_fields import array, integer, point, shown, text, vectors
from .json_values import JsonObject
from .text import parse_json, read_text


class RadialOrderJSON(TypedDict):
    """One entry of ``radial_orders``: the edge ``[a, b]`` (``[a, b, offset]`` when periodic) and its sides in order."""

    edge: list[Any]
    sides: list[list[int]]


class ScaffoldJSON(TypedDict):
    """The object of a scaffold file, as :func:`scaffold_to_dict` writes it (``docs/formats.md``)."""

    format: str
    version: int
    name: str
    vertices: list[list[float]]
    faces: list[list[int]]
    lattice: NotRequired[list[list[float]]]
    offsets: NotRequired[list[list[list[int]]]]
    radial_orders: NotRequired[list[RadialOrderJSON]]
    edges: list[list[Any]]
    labels: NotRequired[list[int]]
    nulls: NotRequired[list[list[int]]]


FORMAT = "lkspace-scaffold"
VORONOI_FORMAT = "lkspace-voronoi"
VERSION = 1
KEYS = {
    "format",
    "version",
    "name",
    "vertices",
    "faces",
    "lattice",
    "offsets",
    "radial_orders",
    "edges",
    "labels",
    "twists",
    "nulls",
    "comment",
}


def _side(faces: list[list[int]], value: Any, where: str, starts: np.ndarray) -> int:
    """Return the global side number of a face-side ``[face, k]``."""
    pair = array(value, where, 2)
    f = integer(pair[0], f"{where}[0] (face)", 0, len(faces) - 1)
    k = integer(pair[1], f"{where}[1] (side)", 0, len(faces[f]) - 1)
    return int(starts[f] + k)


def _faces(data: JsonObject, name: str, n_vertices: int) -> list[list[int]]:
    faces = array(data.get("faces"), f"{name}: faces")
    for i, face in enumerate(faces):
        for j, v in enumerate(array(face, f"{name}: faces[{i}]")):
            integer(v, f"{name}: faces[{i}][{j}] (vertex)", 0, n_vertices - 1)
    return faces


def _offsets(data: JsonObject, name: str, faces: list[list[int]], dim: int) -> list[list[list[int]]]:
    raw = array(data.get("offsets"), f"{name}: offsets", len(faces))
    for i, (face, offs) in enumerate(zip(faces, raw)):
        for j, o in enumerate(array(offs, f"{name}: offsets[{i}]", len(face))):
            for x in array(o, f"{name}: offsets[{i}][{j}]", dim):
                integer(x, f"{name}: offsets[{i}][{j}]")
    return raw


def _edge_key(value: Any, where: str, dim: int) -> tuple[int, int, tuple[int, ...]]:
    """Return the edge key ``(a, b, delta)`` of ``[a, b]`` or ``[a, b, [delta]]``, in either direction.

    ``delta`` is the lattice offset of the second vertex relative to the first, so
    ``[b, a, delta]`` names the same edge as ``[a, b, -delta]``.
    """
    edge = array(value, where)
    if len(edge) not in ((2, 3) if dim else (2,)):
        raise ScaffoldError(
            f"{where}: expected [a, b]" + (" or [a, b, [offset]]" if dim else "") + f", got {shown(edge)}"
        )
    a, b = integer(edge[0], f"{where}[0]", 0), integer(edge[1], f"{where}[1]", 0)
    delta = [integer(x, f"{where}[2]") for x in array(edge[2], f"{where}[2]", dim)] if len(edge) == 3 else [0] * dim
    flip = a > b or (a == b and next((x < 0 for x in delta if x), False))
    if flip:
        a, b, delta = b, a, [-x for x in delta]
    return a, b, tuple(delta)


def _radial_orders(data: JsonObject, name: str, faces: list[list[int]], dim: int) -> dict[tuple, tuple[int, ...]]:
    starts = np.concatenate([[0], np.cumsum([len(f) for f in faces])]).astype(np.int64)
    radial: dict[tuple, tuple[int, ...]] = {}
    for i, entry in enumerate(array(data["radial_orders"], f"{name}: radial_orders")):
        where = f"{name}: radial_orders[{i}]"
        if not isinstance(entry, dict) or set(entry) != {"edge", "sides"}:
            raise ScaffoldError(f"{where}: expected {{'edge': [a, b], 'sides': [[face, k], ...]}}")
        key = _edge_key(entry["edge"], f"{where}.edge", dim)
        if key in radial:
            raise ScaffoldError(f"{where}: edge {key[0]}-{key[1]} given twice")
        sides = array(entry["sides"], f"{where}.sides")
        radial[key] = tuple(_side(faces, s, f"{where}.sides[{j}]", starts) for j, s in enumerate(sides))
    return radial


def scaffold_from_dict(data: JsonObject, name: str = "<json>") -> Scaffold:
    """Build a scaffold (with its labels and nulls, if any) from the parsed JSON."""
    if not isinstance(data, dict):
        raise ScaffoldError(f"{name}: expected a JSON object, got {type(data).__name__}")
    if data.get("format") == VORONOI_FORMAT:
        return voronoi_from_dict(data, name)
    _known_keys(data, KEYS, name)
    if text(data.get("format", FORMAT), f"{name}: format") != FORMAT:
        raise ScaffoldError(f"{name}: format {shown(data.get('format'))} is not {FORMAT!r}")
    _version(data, name)
    label = text(data.get("name", name), f"{name}: name")
    with task(f"reading {name}", total=2) as step:  # shown only for big files (> 2 s)
        raw = array(data.get("vertices"), f"{name}: vertices")
        rows = [point(v, f"{name}: vertices[{i}]") for i, v in enumerate(raw)]
        if not rows:
            raise ScaffoldError(f"{name}: no vertices")
        step.advance()
        faces = _faces(data, name, len(rows))
        step.advance()
    lattice = Lattice(np.array(vectors(data["lattice"], f"{name}: lattice"))) if "lattice" in data else None
    dim = 0 if lattice is None else lattice.dim
    if lattice is None and "offsets" in data:
        raise ScaffoldError(f"{name}: offsets given without a lattice")
    offsets = _offsets(data, name, faces, dim) if lattice is not None else None
    radial = _radial_orders(data, name, faces, dim) if "radial_orders" in data else None
    try:
        scaffold = Scaffold.from_faces(rows, faces, lattice=lattice, offsets=offsets, radial_orders=radial, name=label)
    except ScaffoldError as exc:
        raise ScaffoldError(f"{name}: {exc}") from None
    if "edges" in data:
        expected = scaffold_to_dict(scaffold)["edges"]
        if json.dumps(data["edges"]) != json.dumps(expected):
            raise ScaffoldError(f"{name}: 'edges' does not match the faces' edges in edge order")
    if "labels" in data and "twists" in data:
        raise ScaffoldError(f"{name}: give the twist labels once, as 'labels' ('twists' is the older key)")
    labels = None
    for key in ("labels", "twists"):
        if key in data:
            labels = [
                integer(t, f"{name}: {key}[{i}]", -MAX_LABEL, MAX_LABEL)
                for i, t in enumerate(array(data[key], f"{name}: {key}", scaffold.n_edges))
            ]
    nulls = None
    if "nulls" in data:
        starts = scaffold.face_starts
        nulls = [
            _side(faces, s, f"{name}: nulls[{j}]", starts) for j, s in enumerate(array(data["nulls"], f"{name}: nulls"))
        ]
    if labels is not None or nulls is not None:
        scaffold = scaffold.with_labels(labels, nulls)
    return scaffold


def _version(data: JsonObject, name: str) -> None:
    version = data.get("version", VERSION)
    if isinstance(version, bool) or not isinstance(version, int) or version != VERSION:
        raise ScaffoldError(f"{name}: file version {shown(version)} is not supported (expected {VERSION})")


MAX_VORONOI_POINTS = 200
"""Most generator points of a Voronoi file: Qhull works on 125 lattice translates of each."""


def _known_keys(data: JsonObject, keys: set[str], name: str) -> None:
    """Refuse a key outside ``keys``: a misspelt key must not be silently ignored."""
    unknown = sorted(set(data) - keys)
    if unknown:
        raise ScaffoldError(
            f"{name}: unknown {noun(len(unknown), 'key')} {', '.join(shown(k) for k in unknown)}; "
            f"the keys are {', '.join(sorted(keys))}"
        )


def voronoi_from_dict(data: JsonObject, name: str) -> Scaffold:
    """Build a generalized Voronoi scaffold from its parsed JSON.

    The object is ``{"format": "lkspace-voronoi", "version": 1, "lattice": [[...], ...],
    "points": [[x, y, z], ...], "name": ...}``.
    """
    _known_keys(data, {"format", "version", "name", "lattice", "points", "comment"}, name)
    _version(data, name)
    lattice = Lattice(np.array(vectors(data.get("lattice"), f"{name}: lattice")))
    points = [point(p, f"{name}: points[{i}]") for i, p in enumerate(array(data.get("points"), f"{name}: points"))]
    if not 1 <= len(points) <= MAX_VORONOI_POINTS:
        raise ScaffoldError(f"{name}: points: give 1 to {MAX_VORONOI_POINTS} generator points, got {len(points)}")
    label = text(data.get("name", name), f"{name}: name")
    return voronoi_scaffold(lattice, np.array(points, dtype=float), label)


def scaffold_to_dict(
    scaffold: Scaffold, labels: ArrayLike | None = None, nulls: ArrayLike | None = None
) -> ScaffoldJSON:
    """Return the JSON object of ``scaffold``; ``labels``/``nulls`` default to the scaffold's own."""
    labels = scaffold.labels if labels is None else np.asarray(labels)
    nulls = scaffold.nulls if nulls is None else nulls
    starts = scaffold.face_starts

    def side_name(s: int) -> list[int]:
        f = int(np.searchsorted(starts, s, side="right") - 1)
        return [f, int(s - starts[f])]

    out: dict[str, Any] = {  # keys in the file's order (a ScaffoldJSON literal would put edges before lattice)
        "format": FORMAT,
        "version": VERSION,
        "name": scaffold.name,
        "vertices": scaffold.vertices.tolist(),
        "faces": scaffold.faces(),
    }
    if scaffold.lattice is not None and scaffold.corner_offsets is not None:  # periodic
        out["lattice"] = scaffold.lattice.basis.tolist()
        offs = scaffold.corner_offsets.tolist()
        out["offsets"] = [offs[s:e] for s, e in zip(starts[:-1], starts[1:])]
    if scaffold.radial_orders:
        out["radial_orders"] = [
            {"edge": [a, b, list(d)] if d else [a, b], "sides": [side_name(s) for s in sides]}
            for (a, b, d), sides in sorted(scaffold.radial_orders.items())
        ]
    out["edges"] = [
        [int(k[0]), int(k[1]), [int(x) for x in k[2:]]] if scaffold.dim else [int(k[0]), int(k[1])]
        for k in scaffold.edge_keys.tolist()
    ]
    if labels is not None:
        out["labels"] = [int(t) for t in np.broadcast_to(labels, (scaffold.n_edges,))]
    if nulls is not None:
        mask = np.asarray(nulls)
        sides = np.flatnonzero(mask) if mask.dtype == bool else mask
        if len(sides):
            out["nulls"] = [side_name(int(s)) for s in sides]
    return cast(ScaffoldJSON, out)


def read_scaffold_json(path: str | os.PathLike) -> Scaffold:
    """Read a scaffold file."""
    name = os.path.basename(str(path))
    return scaffold_from_dict(parse_json(read_text(path, "scaffold"), name), name)


def format_scaffold_json(scaffold: Scaffold, labels: ArrayLike | None = None, nulls: ArrayLike | None = None) -> str:
    """Return the scaffold file text (JSON) of ``scaffold``."""
    return json.dumps(scaffold_to_dict(scaffold, labels, nulls), indent=1) + "\n"
