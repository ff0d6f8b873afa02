"""The lkspace design file: a scaffold, its twist labels and the view that shows them.

Format version 1 (docs/formats.md)::

    {
      "format": "lkspace-design", "version": 1,
      "scaffold": "cube",                     # a built-in name, or a scaffold file object
                                              # ({"format": "lkspace-scaffold", ...}) embedded
      "labels": [t_0, t_1, ...],              # one twist label per edge, edge order
      "nulls": [[face, k], ...],              # optional: null edge-sides
      "block": [2, 2, 2],                     # optional, periodic scaffolds: lattice copies drawn
      "view": {"position": [x, y, z], "target": [x, y, z], "up": [x, y, z]}   # optional camera
    }

The studio saves and opens it (``save design`` / ``open design``, ``lkspace studio
design.json``).  Reading checks every field against the scaffold and stops at the first
problem with one message naming the field (``cube.design.json: labels: expected 12 twist
labels (one per edge of cube), got 11``).  Unknown keys are an error, as in the scaffold file.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, NotRequired, TypedDict

import numpy as np

from ..errors import LabelError, ScaffoldError
from ..model.scaffold import Scaffold
from ..model.validation import validate_labels
from ..words import noun
from .json_fields import array, integer, point, shown, text
from .scaffold_json import ScaffoldJSON, scaffold_from_dict, scaffold_to_dict
from .text import parse_json


class DesignJSON(TypedDict):
    """The object of a design file, as :func:`design_to_dict` writes it (see the module docstring)."""

    format: str
    version: int
    scaffold: str | ScaffoldJSON
    labels: list[int]
    nulls: NotRequired[list[list[int]]]
    block: NotRequired[list[int]]
    view: NotRequired[dict[str, list[float]]]


FORMAT = "lkspace-design"
VERSION = 1
KEYS = {"format", "version", "scaffold", "labels", "nulls", "block", "view", "comment"}
VIEW_KEYS = ("position", "target", "up")
MAX_BLOCK_SIZE = 64
"""Largest lattice copy count along one axis of a design's block."""


@dataclass(frozen=True, eq=False)
class Design:
    """A design read from a file.

    ``builtin`` is the built-in name of the scaffold (``None``: the scaffold was embedded);
    ``labels`` is ``(n_edges,) int64``, ``nulls`` a ``(n_corners,) bool`` mask or ``None``;
    ``block`` the lattice copies per axis; ``view`` maps ``position``/``target``/``up`` to 3 floats.
    """

    scaffold: Scaffold
    builtin: str | None
    labels: np.ndarray
    nulls: np.ndarray | None
    block: tuple[int, ...] | None
    view: dict[str, tuple[float, float, float]] | None


def is_design(data: Any) -> bool:
    """Whether parsed JSON ``data`` says it is a design file (rather than a scaffold file)."""
    return isinstance(data, dict) and data.get("format") == FORMAT


def _labels(value: Any, scaffold: Scaffold, name: str) -> np.ndarray:
    items = array(value, f"{name}: labels")
    if len(items) != scaffold.n_edges:
        raise LabelError(
            f"{name}: labels: expected {scaffold.n_edges} twist labels (one per edge of {scaffold.name}), "
            f"got {len(items)}"
        )
    for i, t in enumerate(items):
        if isinstance(t, bool) or not isinstance(t, int):
            raise LabelError(f"{name}: labels[{i}] (edge {scaffold.edge_name(i)}): expected an integer, got {shown(t)}")
    try:
        array_ = np.array(items, dtype=np.int64)
    except OverflowError:
        array_ = np.array(items, dtype=object)  # past int64: validate_labels names the label and the range
    try:
        return validate_labels(scaffold, array_)
    except LabelError as exc:
        raise LabelError(f"{name}: labels: {exc}") from None


def _nulls(value: Any, scaffold: Scaffold, name: str) -> np.ndarray | None:
    if value is None:
        return None
    starts = scaffold.face_starts
    mask = np.zeros(scaffold.n_corners, bool)
    for i, pair in enumerate(array(value, f"{name}: nulls")):
        where = f"{name}: nulls[{i}]"
        face, k = array(pair, where, 2)
        f = integer(face, f"{where}[0] (face)", 0, scaffold.n_faces - 1)
        mask[starts[f] + integer(k, f"{where}[1] (side)", 0, int(starts[f + 1] - starts[f]) - 1)] = True
    return mask


def _block(value: Any, scaffold: Scaffold, name: str) -> tuple[int, ...] | None:
    if value is None:
        return None
    if not scaffold.periodic:
        raise ScaffoldError(f"{name}: block: {scaffold.name} is not periodic (a block is for lattices)")
    sizes = array(value, f"{name}: block", scaffold.dim)
    return tuple(integer(n, f"{name}: block[{i}]", 1, MAX_BLOCK_SIZE) for i, n in enumerate(sizes))


def read_view(value: Any, name: str) -> dict[str, tuple[float, float, float]] | None:
    """Return the camera of a design (``position``, ``target``, ``up``: 3 floats each), or ``None``."""
    if value is None:
        return None
    if not isinstance(value, dict):
        raise ScaffoldError(f"{name}: view: expected an object with position, target and up")
    unknown = set(value) - set(VIEW_KEYS)
    if unknown:
        raise ScaffoldError(f"{name}: view: unknown {noun(len(unknown), 'key')} {shown(sorted(unknown))}")
    out = {}
    for key in VIEW_KEYS:
        if key not in value:
            raise ScaffoldError(f"{name}: view: {key} missing (3 numbers)")
        x, y, z = point(value[key], f"{name}: view.{key}")
        out[key] = (x, y, z)
    if out["position"] == out["target"]:
        raise ScaffoldError(f"{name}: view: position and target are the same point")
    if not any(out["up"]):
        raise ScaffoldError(f"{name}: view: up is the zero vector")
    return out


def design_from_dict(data: Any, name: str, resolve: Callable[[str], Scaffold]) -> Design:
    """Read a parsed design file; ``resolve`` turns a built-in name into its scaffold (raising for unknown names)."""
    if not isinstance(data, dict):
        raise ScaffoldError(f"{name}: expected a JSON object, got {type(data).__name__}")
    if data.get("format") != FORMAT:
        raise ScaffoldError(f"{name}: format {shown(data.get('format'))} is not {FORMAT!r}")
    unknown = set(data) - KEYS
    if unknown:
        raise ScaffoldError(f"{name}: unknown {noun(len(unknown), 'key')} {shown(sorted(unknown))}")
    version = data.get("version")
    if isinstance(version, bool) or version != VERSION:
        raise ScaffoldError(f"{name}: design file version {shown(version)} is not supported (expected {VERSION})")
    given = data.get("scaffold")
    if isinstance(given, str):
        builtin: str | None = text(given, f"{name}: scaffold")
        scaffold = resolve(given)
    elif isinstance(given, dict):
        builtin, scaffold = None, scaffold_from_dict(given, f"{name}: scaffold")
    else:
        raise ScaffoldError(f"{name}: scaffold: a built-in name or a scaffold file object, got {shown(given)}")
    if "labels" not in data:
        raise LabelError(f"{name}: labels missing (one twist label per edge of {scaffold.name})")
    return Design(
        scaffold,
        builtin,
        _labels(data["labels"], scaffold, name),
        _nulls(data.get("nulls"), scaffold, name),
        _block(data.get("block"), scaffold, name),
        read_view(data.get("view"), name),
    )


def read_design(text_: str, name: str, resolve: Callable[[str], Scaffold]) -> Design:
    """Read design file text (``name`` for messages); see :func:`design_from_dict`."""
    return design_from_dict(parse_json(text_, name), name, resolve)


def design_to_dict(
    scaffold: Scaffold,
    builtin: str | None,
    labels: np.ndarray,
    nulls: np.ndarray | None = None,
    block: tuple[int, ...] | None = None,
    view: dict[str, tuple[float, float, float]] | None = None,
) -> DesignJSON:
    """Return the design file object: the scaffold by its built-in name, or embedded when ``builtin`` is ``None``."""
    if builtin is None:
        embedded = scaffold_to_dict(scaffold)
        embedded.pop("labels", None)  # the design's own labels and nulls are the ones that count
        embedded.pop("nulls", None)
    out: DesignJSON = {
        "format": FORMAT,
        "version": VERSION,
        "scaffold": builtin if builtin is not None else embedded,
        "labels": [int(t) for t in labels],
    }
    if nulls is not None and np.any(nulls):
        starts = scaffold.face_starts
        sides = np.flatnonzero(nulls)
        faces = np.searchsorted(starts, sides, side="right") - 1
        out["nulls"] = [[int(f), int(s - starts[f])] for f, s in zip(faces, sides, strict=True)]
    if block is not None and scaffold.periodic:
        out["block"] = [int(n) for n in block]
    if view is not None:
        out["view"] = {key: [float(x) for x in view[key]] for key in VIEW_KEYS}
    return out


def format_design(design: DesignJSON) -> str:
    """Return the file text of a design object: one line per field, labels on one line."""
    lines = [f" {json.dumps(key)}: {json.dumps(value)}" for key, value in design.items()]
    return "{\n" + ",\n".join(lines) + "\n}\n"
