"""Twist ``SPEC`` as users type it, where it may name a twist file (``docs/formats.md``).

A ``SPEC`` that is an integer is always a label, even if a file of that name exists; any
other text names a twist file when such a file exists, else it is a comma list.  The
parsing itself is :mod:`lkspace.model.specs`'s; this module only reads the file.
"""

from __future__ import annotations

import os

import numpy as np

from ..errors import LabelError
from ..model.scaffold import Scaffold
from ..model.specs import is_integer, parse_labels, twist_labels_from_json, twist_labels_from_lines
from .text import parse_json, read_text


def read_twist_file(scaffold: Scaffold, path: str) -> np.ndarray:
    """Twist labels ``(n_edges,) int64`` from a file naming edges.

    Either a JSON object ``{"3-7": 1, ...}`` (or a list of labels, or a scaffold file with
    ``labels``), or text lines ``EDGE T`` where ``EDGE`` is ``a-b``, ``a b``, an edge index
    or ``*`` (the default for edges not named).  ``#`` starts a comment.  Every edge must
    get a label.
    """
    name = os.path.basename(path)
    text = read_text(path, "twist", LabelError)
    if text.lstrip().startswith(("{", "[")):
        return twist_labels_from_json(scaffold, parse_json(text, name, LabelError), name)
    return twist_labels_from_lines(scaffold, text, name)


def parse_twist(scaffold: Scaffold, spec: int | np.integer | str | os.PathLike[str]) -> np.ndarray:
    """Twist ``SPEC`` (int, comma list, or path of a twist file) -> ``(n_edges,) int64``.

    Examples
    --------
    >>> from lkspace import load
    >>> parse_twist(load("tetrahedron"), "-1").tolist()
    [-1, -1, -1, -1, -1, -1]
    """
    if isinstance(spec, os.PathLike):
        return read_twist_file(scaffold, os.fspath(spec))
    if isinstance(spec, str) and not is_integer(spec) and os.path.lexists(spec.strip()):
        return read_twist_file(scaffold, spec.strip())
    return parse_labels(scaffold, spec)
