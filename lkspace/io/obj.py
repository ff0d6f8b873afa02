"""Wavefront OBJ polygon meshes.

Read: ``v x y z [w]`` and ``f a b c ...`` lines, face entries ``a``, ``a/b``, ``a//c`` or
``a/b/c`` with 1-based or negative (relative) indices; ``#`` comments; ``vt``, ``vn``,
``vp``, ``o``, ``g``, ``s``, ``usemtl``, ``mtllib`` and ``l`` lines are ignored.  Any other
malformed line is an error naming the file and line.
"""

from __future__ import annotations

import os

import numpy as np

from ..errors import ScaffoldError
from ..model.scaffold import Scaffold

IGNORED = {"vt", "vn", "vp", "o", "g", "s", "usemtl", "mtllib", "l", "p", "cstype", "deg", "curv", "parm", "end"}


def parse_obj(text: str, name: str = "<obj>") -> Scaffold:
    """Parse OBJ ``text``; ``name`` is used in error messages."""
    vertices: list[list[float]] = []
    faces: list[list[int]] = []
    for lineno, raw in enumerate(text.splitlines(), start=1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        tag, *parts = line.split()
        where = f"{name} line {lineno}"
        if tag == "v":
            if len(parts) not in (3, 4):
                raise ScaffoldError(f"{where}: vertex needs 3 coordinates, got {len(parts)}: {raw.strip()!r}")
            try:
                xyz = [float(p) for p in parts[:3]]
            except ValueError:
                raise ScaffoldError(f"{where}: vertex coordinates must be numbers: {raw.strip()!r}") from None
            if not all(np.isfinite(xyz)):
                raise ScaffoldError(f"{where}: vertex {len(vertices)} has a non-finite coordinate: {raw.strip()!r}")
            vertices.append(xyz)
        elif tag == "f":
            if len(parts) < 3:
                raise ScaffoldError(f"{where}: face {len(faces)} has {len(parts)} vertices; a face needs at least 3")
            face = []
            for part in parts:
                token = part.split("/", 1)[0]
                try:
                    index = int(token)
                except ValueError:
                    raise ScaffoldError(f"{where}: face vertex {part!r} is not an integer index") from None
                n = len(vertices)
                if index > 0 and index <= n:
                    face.append(index - 1)
                elif index < 0 and -index <= n:
                    face.append(n + index)
                else:
                    raise ScaffoldError(f"{where}: face vertex index {index} out of range 1..{n} (or -{n}..-1)")
            if len(set(face)) != len(face):
                raise ScaffoldError(f"{where}: face {len(faces)} repeats a vertex: {parts}")
            faces.append(face)
        elif tag in IGNORED:
            continue
        else:
            raise ScaffoldError(f"{where}: unknown OBJ statement {tag!r}")
    if not vertices:
        raise ScaffoldError(f"{name}: no vertices ('v' lines) found")
    if not faces:
        raise ScaffoldError(f"{name}: no faces ('f' lines) found")
    return Scaffold.from_faces(vertices, faces, name=name)


def read_obj(path: str | os.PathLike) -> Scaffold:
    """Read an OBJ file."""
    try:
        with open(path, encoding="utf-8") as fh:
            text = fh.read()
    except (OSError, UnicodeDecodeError) as exc:
        raise ScaffoldError(f"{path}: cannot read: {exc}") from None
    return parse_obj(text, name=os.path.basename(str(path)))


def format_obj(scaffold: Scaffold) -> str:
    """OBJ text of a finite scaffold (vertices, faces; 1-based indices)."""
    if scaffold.periodic:
        raise ScaffoldError(f"{scaffold.name}: OBJ cannot hold a periodic scaffold; write a .json scaffold file")
    lines = [f"# lkspace scaffold {scaffold.name}"]
    lines += [f"v {x!r} {y!r} {z!r}" for x, y, z in scaffold.vertices.tolist()]
    lines += ["f " + " ".join(str(v + 1) for v in face) for face in scaffold.faces()]
    return "\n".join(lines) + "\n"
