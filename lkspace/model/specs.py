"""Parsing twist labels, label sets and null edge-sides as users type them (``docs/formats.md``).

* twist ``SPEC``: one integer (every edge) or a comma list with one integer per edge in
  edge order (:func:`parse_labels`); the content of a twist file naming edges by vertex
  pair (:func:`twist_labels_from_json`, :func:`twist_labels_from_lines`).  This module
  reads no files: :func:`lkspace.io.twists.parse_twist` takes a ``SPEC`` that may be a path.
* label ``SET``: ``-2..2`` (inclusive range) or a comma list ``-2,-1,1,2``.
* null ``SPEC``: comma list of face-sides ``F.K`` (side ``K`` of face ``F``).
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from typing import TypeAlias

import numpy as np

from ..errors import LabelError
from ..words import plural
from .scaffold import Scaffold
from .validation import MAX_LABEL_SET_SIZE, check_label

LabelSetSpec: TypeAlias = str | Sequence[int] | np.ndarray
"""A label set as users give it: text (``"-2..2"``, ``"-2,-1,1,2"``) or integers."""

_INT = re.compile(r"^[+-]?[0-9]+$")
_EDGE = re.compile(r"^(\d+)\s*[-\s]\s*(\d+)(?:\s*\[([-+\d,\s]*)\])?$")


def _to_int(text: str, where: str) -> int:
    text = text.strip()
    if not _INT.match(text):
        shown = repr(text) if len(text) <= 40 else repr(text[:40] + "...")
        raise LabelError(f"{where}: {shown} is not an integer")
    if len(text) > 40:  # far past any bound; int() of thousands of digits is refused by Python
        raise LabelError(f"{where}: an integer of {len(text.lstrip('+-'))} digits is out of range")
    return int(text)


def _to_label(text: str, where: str) -> int:
    digits = text.strip().lstrip("+-")
    if len(digits) > 40 and digits.isdigit():
        raise LabelError(
            f"{where}: an integer of {len(digits)} digits is out of range; labels must lie within -(2**63 - 1)..2**63 - 1"
        )
    return check_label(_to_int(text, where), where)


def parse_label_set(spec: str) -> np.ndarray:
    """``"-2..2"`` or ``"-2,-1,1,2"`` -> sorted unique ``(n_labels,) int64``.

    Examples
    --------
    >>> parse_label_set("-2..2").tolist()
    [-2, -1, 0, 1, 2]
    >>> parse_label_set("2,-2").tolist()
    [-2, 2]
    """
    spec = str(spec).strip()
    where = f"label set {spec!r}" if len(spec) <= 40 else "label set"
    if ".." in spec:
        lo, _, hi = spec.partition("..")
        lo_i, hi_i = _to_label(lo, where), _to_label(hi, where)
        if lo_i > hi_i:
            raise LabelError(f"{where}: empty range")
        if hi_i - lo_i + 1 > MAX_LABEL_SET_SIZE:
            raise LabelError(f"{where}: {hi_i - lo_i + 1} labels; a label set holds at most {MAX_LABEL_SET_SIZE}")
        return np.arange(lo_i, hi_i + 1, dtype=np.int64)
    items = spec.split(",") if spec else []
    if len(items) > MAX_LABEL_SET_SIZE:
        raise LabelError(f"{where}: {len(items)} labels; a label set holds at most {MAX_LABEL_SET_SIZE}")
    values = [_to_label(v, f"{where}: item {i}") for i, v in enumerate(items)]
    if not values:
        raise LabelError("label set is empty")
    return np.unique(np.array(values, dtype=np.int64))


def edge_index(scaffold: Scaffold, name: str) -> int:
    """Edge named by index (``"5"``) or vertex pair (``"3-7"``, periodic ``"3-7[0,1,0]"``)."""
    name = name.strip()
    if _INT.match(name):
        e = _to_int(name, "edge")
        if not 0 <= e < scaffold.n_edges:
            raise LabelError(f"edge {e} out of range 0..{scaffold.n_edges - 1}")
        return e
    m = _EDGE.match(name)
    if not m:
        raise LabelError(f"{name!r} names no edge; write an edge index or a vertex pair like 3-7")
    a, b = sorted((_to_int(m.group(1), "edge"), _to_int(m.group(2), "edge")))
    matches = np.flatnonzero((scaffold.edge_vertices[:, 0] == a) & (scaffold.edge_vertices[:, 1] == b))
    if m.group(3) is not None:
        delta = [_to_int(x, f"edge {name!r}") for x in m.group(3).split(",") if x.strip()]
        if int(m.group(1)) > int(m.group(2)):
            delta = [-x for x in delta]
        matches = np.array([e for e in matches if scaffold.edge_deltas[e].tolist() == delta], np.int64)
    if len(matches) == 0:
        raise LabelError(f"{scaffold.name}: {name!r} is not an edge")
    if len(matches) > 1:
        options = ", ".join(scaffold.edge_name(e) for e in matches)
        raise LabelError(f"{scaffold.name}: {name!r} names several edge classes ({options}); add the offset")
    return int(matches[0])


def is_integer(text: str) -> bool:
    """Whether ``text`` (stripped) is an integer as a twist ``SPEC`` reads it: ``7``, ``-1``, ``+2``."""
    return bool(_INT.match(text.strip()))


def twist_labels_from_json(scaffold: Scaffold, data: object, name: str) -> np.ndarray:
    """Twist labels from the parsed JSON of twist file ``name`` (:mod:`lkspace.io.twists` reads it).

    Either an object ``{"3-7": 1, ...}`` naming edges (``"*"``: the default for edges not
    named), a list of labels in edge order, or a scaffold file with ``labels``.
    """
    if isinstance(data, list):
        return labels_from_list(scaffold, data, name)
    if not isinstance(data, dict):
        raise LabelError(f"{name}: expected a JSON object {{EDGE: LABEL, ...}} or a list of labels")
    for key in ("labels", "twists"):  # a scaffold file ("twists" is the older spelling)
        if key in data:
            if not isinstance(data[key], list):
                raise LabelError(f"{name}: {key!r} must be a list of labels, got {type(data[key]).__name__}")
            return labels_from_list(scaffold, data[key], f"{name} {key!r}")
    entries: list[tuple[str, str, str]] = []
    for k, v in data.items():
        if isinstance(v, bool) or not isinstance(v, int):
            raise LabelError(f"{name} key {k!r}: label {str(v)[:40]!r} is not an integer")
        entries.append((f"{name} key {k!r}", k, str(v)))
    return _labels_of_entries(scaffold, entries, name)


def twist_labels_from_lines(scaffold: Scaffold, text: str, name: str) -> np.ndarray:
    """Twist labels from the text of twist file ``name``: lines ``EDGE T``.

    ``EDGE`` is ``a-b``, ``a b``, an edge index or ``*`` (the default for edges not named);
    ``#`` starts a comment.  Every edge must get a label.
    """
    entries: list[tuple[str, str, str]] = []
    for lineno, raw in enumerate(text.splitlines(), start=1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        edge, _, value = line.rpartition(" ")
        if not edge.strip():
            raise LabelError(f"{name} line {lineno}: expected 'EDGE LABEL', got {raw.strip()!r}")
        entries.append((f"{name} line {lineno}", edge.strip().rstrip(":"), value))
    return _labels_of_entries(scaffold, entries, name)


def _labels_of_entries(scaffold: Scaffold, entries: list[tuple[str, str, str]], name: str) -> np.ndarray:
    """Labels of ``(where, EDGE, LABEL)`` entries of a twist file; every edge named or defaulted by ``*``."""
    labels = np.zeros(scaffold.n_edges, np.int64)
    named = np.zeros(scaffold.n_edges, bool)
    default = None
    for where, edge, value in entries:
        t = _to_label(value, where)
        if edge == "*":
            default = t
            continue
        try:
            e = edge_index(scaffold, edge)
        except LabelError as exc:
            raise LabelError(f"{where}: {exc}") from None
        if named[e]:
            raise LabelError(f"{where}: edge {scaffold.edge_name(e)} labelled twice")
        labels[e], named[e] = t, True
    if default is not None:
        labels[~named] = default
    elif not named.all():
        missing = ", ".join(scaffold.edge_name(e) for e in np.flatnonzero(~named)[:5])
        raise LabelError(
            f"{name}: no label for {plural(int((~named).sum()), 'edge')} ({missing}); add them or a '* T' default line"
        )
    return labels


def labels_from_list(scaffold: Scaffold, values: Sequence[object], where: str = "twist labels") -> np.ndarray:
    """Check a list of per-edge integers and return it as ``(n_edges,) int64`` (with a clear count error)."""
    if len(values) != scaffold.n_edges:
        raise LabelError(
            f"{where}: expected {scaffold.n_edges} twist labels (one per edge of {scaffold.name}), got {len(values)}"
        )
    out = []
    for i, v in enumerate(values):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)):
            raise LabelError(f"{where}: label {i} is {str(v)[:40]!r}, not an integer")
        out.append(check_label(int(v), f"{where}: label {i} (edge {scaffold.edge_name(i)})"))
    return np.array(out, dtype=np.int64)


def parse_labels(scaffold: Scaffold, spec: int | np.integer | str) -> np.ndarray:
    """Twist ``SPEC`` (int or comma list; a path: :func:`lkspace.io.twists.parse_twist`) -> ``(n_edges,) int64``.

    Examples
    --------
    >>> from lkspace import load
    >>> parse_labels(load("tetrahedron"), "-1").tolist()
    [-1, -1, -1, -1, -1, -1]
    """
    if isinstance(spec, (int, np.integer)) and not isinstance(spec, bool):
        return np.full(scaffold.n_edges, check_label(int(spec), "twist label"), np.int64)
    spec = str(spec).strip()
    shown = repr(spec) if len(spec) <= 60 else repr(spec[:60] + "...")
    if not _INT.match(spec) and "," not in spec:
        raise LabelError(f"twist spec {shown} is neither an integer, a comma list, nor an existing file")
    try:  # errors in the spec itself name the parameter: "labels '1,2': ..."
        if _INT.match(spec):
            return np.full(scaffold.n_edges, _to_label(spec, f"labels {shown}"), np.int64)
        parts = spec.split(",")
        if len(parts) != scaffold.n_edges:
            return labels_from_list(scaffold, parts, f"labels {shown}")  # the count error
        values = [_to_label(p, f"labels {shown}: label {i}") for i, p in enumerate(parts)]
        return labels_from_list(scaffold, values, f"labels {shown}")
    except LabelError as exc:
        exc.parameter = "labels"
        raise


def parse_nulls(scaffold: Scaffold, spec: str) -> np.ndarray:
    """Null ``SPEC`` ``"F.K,F.K"`` (side ``K`` of face ``F``) -> ``(n_corners,) bool``."""
    mask = np.zeros(scaffold.n_corners, bool)
    for item in str(spec).split(","):
        item = item.strip()
        if not item:
            continue
        f_text, dot, k_text = item.partition(".")
        if not dot:
            raise LabelError(f"null side {item!r}: write FACE.SIDE, e.g. 0.2 for side 2 of face 0")
        shown = repr(item) if len(item) <= 40 else repr(item[:40] + "...")
        f, k = _to_int(f_text, f"null side {shown}"), _to_int(k_text, f"null side {shown}")
        if not 0 <= f < scaffold.n_faces:
            raise LabelError(f"null side {shown}: face {f} out of range 0..{scaffold.n_faces - 1}")
        if not 0 <= k < scaffold.face_sizes[f]:
            raise LabelError(f"null side {shown}: face {f} has sides 0..{scaffold.face_sizes[f] - 1}")
        mask[scaffold.face_starts[f] + k] = True
    return mask
