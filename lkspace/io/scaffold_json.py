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
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..errors import ScaffoldError
from ..model.lattice import Lattice
from ..model.scaffold import Scaffold
from ..scaffolds.periodic import voronoi_scaffold

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


def _int(value: Any, where: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise ScaffoldError(f"{where}: expected an integer, got {value!r}")
    return value


def _list(value: Any, where: str, length: int | None = None) -> list[Any]:
    if not isinstance(value, list):
        raise ScaffoldError(f"{where}: expected a list, got {type(value).__name__}")
    if length is not None and len(value) != length:
        raise ScaffoldError(f"{where}: expected {length} entries, got {len(value)}")
    return value


def _side(scaffold_faces: list[Any], value: Any, where: str, starts: np.ndarray) -> int:
    pair = _list(value, where, 2)
    f, k = _int(pair[0], where), _int(pair[1], where)
    if not 0 <= f < len(scaffold_faces):
        raise ScaffoldError(f"{where}: face {f} out of range 0..{len(scaffold_faces) - 1}")
    if not 0 <= k < len(scaffold_faces[f]):
        raise ScaffoldError(f"{where}: face {f} has no side {k} (it has {len(scaffold_faces[f])})")
    return int(starts[f] + k)


def scaffold_from_dict(data: dict[str, Any], name: str = "<json>") -> Scaffold:
    """Build a scaffold (with its labels and nulls, if any) from the parsed JSON."""
    if not isinstance(data, dict):
        raise ScaffoldError(f"{name}: expected a JSON object")
    if data.get("format") == VORONOI_FORMAT:
        return voronoi_from_dict(data, name)
    unknown = set(data) - KEYS
    if unknown:
        raise ScaffoldError(f"{name}: unknown key(s) {sorted(unknown)}")
    if data.get("format", FORMAT) != FORMAT:
        raise ScaffoldError(f"{name}: format {data.get('format')!r} is not {FORMAT!r}")
    version = data.get("version", VERSION)
    if version != VERSION:
        raise ScaffoldError(f"{name}: scaffold file version {version!r} is not supported (expected {VERSION})")
    vertices = _list(data.get("vertices"), f"{name}: vertices")
    rows = []
    for i, v in enumerate(vertices):
        v = _list(v, f"{name}: vertices[{i}]", 3)
        if not all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in v):
            raise ScaffoldError(f"{name}: vertices[{i}]: coordinates must be numbers, got {v}")
        if not all(np.isfinite(v)):
            raise ScaffoldError(f"{name}: vertices[{i}]: non-finite coordinate {v}")
        rows.append(v)
    faces = _list(data.get("faces"), f"{name}: faces")
    for i, face in enumerate(faces):
        _list(face, f"{name}: faces[{i}]")
        for j, v in enumerate(face):
            _int(v, f"{name}: faces[{i}][{j}]")
    lattice = None
    offsets = None
    if "lattice" in data:
        lattice = Lattice(np.array(_list(data["lattice"], f"{name}: lattice"), dtype=float))
        raw = _list(data.get("offsets"), f"{name}: offsets", len(faces))
        offsets = []
        for i, (face, offs) in enumerate(zip(faces, raw)):
            _list(offs, f"{name}: offsets[{i}]", len(face))
            for j, o in enumerate(offs):
                for x in _list(o, f"{name}: offsets[{i}][{j}]", lattice.dim):
                    _int(x, f"{name}: offsets[{i}][{j}]")
            offsets.append(offs)
    elif "offsets" in data:
        raise ScaffoldError(f"{name}: offsets given without a lattice")
    starts = np.concatenate([[0], np.cumsum([len(f) for f in faces])]).astype(int)
    radial = None
    if "radial_orders" in data:
        radial = {}
        for i, entry in enumerate(_list(data["radial_orders"], f"{name}: radial_orders")):
            where = f"{name}: radial_orders[{i}]"
            if not isinstance(entry, dict) or set(entry) != {"edge", "sides"}:
                raise ScaffoldError(f"{where}: expected {{'edge': [a, b], 'sides': [[face, k], ...]}}")
            edge = _list(entry["edge"], f"{where}.edge")
            delta = tuple(edge[2]) if len(edge) == 3 else ()
            key = (min(edge[0], edge[1]), max(edge[0], edge[1]), delta)
            radial[key] = tuple(
                _side(faces, s, f"{where}.sides[{j}]", starts)
                for j, s in enumerate(_list(entry["sides"], f"{where}.sides"))
            )
    try:
        scaffold = Scaffold.from_faces(
            rows,
            faces,
            lattice=lattice,
            offsets=offsets,
            radial_orders=radial,
            name=data.get("name", name) if isinstance(data.get("name"), str) else name,
        )
    except ScaffoldError as exc:
        raise ScaffoldError(f"{name}: {exc}") from None
    if "edges" in data:
        edges = _list(data["edges"], f"{name}: edges")
        expected = scaffold.edge_keys.tolist()
        given = [[e[0], e[1], *(e[2] if len(e) > 2 else [])] for e in edges]
        if given != expected:
            raise ScaffoldError(f"{name}: 'edges' does not match the faces' edges in edge order")
    if "labels" in data and "twists" in data:
        raise ScaffoldError(f"{name}: give the twist labels once, as 'labels' ('twists' is the older key)")
    labels = None
    for label_key in ("labels", "twists"):
        if label_key in data:
            labels = _list(data[label_key], f"{name}: {label_key}", scaffold.n_edges)
            for i, t in enumerate(labels):
                _int(t, f"{name}: {label_key}[{i}]")
    nulls = None
    if "nulls" in data:
        nulls = [
            _side(faces, s, f"{name}: nulls[{j}]", starts) for j, s in enumerate(_list(data["nulls"], f"{name}: nulls"))
        ]
    if labels is not None or nulls is not None:
        scaffold = scaffold.with_labels(labels, nulls)
    return scaffold


def voronoi_from_dict(data: dict[str, Any], name: str) -> Scaffold:
    """Build a generalized Voronoi scaffold from its parsed JSON.

    The object is ``{"format": "lkspace-voronoi", "version": 1, "lattice": [[...], ...],
    "points": [[x, y, z], ...], "name": ...}``.
    """
    unknown = set(data) - {"format", "version", "name", "lattice", "points", "comment"}
    if unknown:
        raise ScaffoldError(f"{name}: unknown key(s) {sorted(unknown)}")
    if data.get("version", VERSION) != VERSION:
        raise ScaffoldError(
            f"{name}: voronoi file version {data.get('version')!r} is not supported (expected {VERSION})"
        )
    lattice = Lattice(np.array(_list(data.get("lattice"), f"{name}: lattice"), dtype=float))
    points = _list(data.get("points"), f"{name}: points")
    for i, p in enumerate(points):
        p = _list(p, f"{name}: points[{i}]", 3)
        if not all(isinstance(x, (int, float)) and not isinstance(x, bool) and np.isfinite(x) for x in p):
            raise ScaffoldError(f"{name}: points[{i}]: coordinates must be finite numbers, got {p}")
    label = data.get("name", name) if isinstance(data.get("name"), str) else name
    return voronoi_scaffold(lattice, np.array(points, dtype=float), label)


def scaffold_to_dict(
    scaffold: Scaffold, labels: ArrayLike | None = None, nulls: ArrayLike | None = None
) -> dict[str, Any]:
    """Return the JSON object of ``scaffold``; ``labels``/``nulls`` default to the scaffold's own."""
    labels = scaffold.labels if labels is None else np.asarray(labels)
    nulls = scaffold.nulls if nulls is None else nulls
    starts = scaffold.face_starts

    def side_name(s: int) -> list[int]:
        f = int(np.searchsorted(starts, s, side="right") - 1)
        return [f, int(s - starts[f])]

    out: dict[str, Any] = {
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
    return out


def read_scaffold_json(path: str | os.PathLike) -> Scaffold:
    """Read a scaffold file."""
    name = os.path.basename(str(path))
    try:
        with open(path, encoding="utf-8") as fh:
            data = json.load(fh)
    except json.JSONDecodeError as exc:
        raise ScaffoldError(f"{name} line {exc.lineno}: invalid JSON: {exc.msg}") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ScaffoldError(f"{path}: cannot read: {exc}") from None
    return scaffold_from_dict(data, name)


def format_scaffold_json(scaffold: Scaffold, labels: ArrayLike | None = None, nulls: ArrayLike | None = None) -> str:
    """Return the scaffold file text (JSON) of ``scaffold``."""
    return json.dumps(scaffold_to_dict(scaffold, labels, nulls), indent=1) + "\n"
