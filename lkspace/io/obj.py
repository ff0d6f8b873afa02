"""Wavefront OBJ polygon meshes.

Read: ``v x y z [w]`` and ``v x y z r g b [a]`` lines (a weight or a vertex colour, as
Blender and MeshLab write, is ignored) and ``f a b c ...`` lines, face entries ``a``,
``a/b``, ``a//c`` or ``a/b/c`` with 1-based or negative (relative) indices; ``#``
comments; a line ending in ``\\`` continues on the next; ``vt``, ``vn``, ``vp``, ``o``,
``g``, ``s``, ``usemtl``, ``mtllib``, ``l`` and ``p`` lines are ignored.  Any other
malformed line is an error naming the file and line (a continued statement: its first).
A UTF-8 byte-order mark is fine; coordinates must be finite and within
``MAX_COORDINATE``.  ``weld`` merges vertices closer than a tolerance
(:mod:`lkspace.io.weld`) before the scaffold is built.
"""

from __future__ import annotations

import os
import re

from ..errors import ScaffoldError
from ..model.scaffold import Scaffold
from ..model.validation import MAX_COORDINATE
from ..runtime.progress import task
from .text import read_text
from .weld import default_tolerance, weld

_INDEX = re.compile(r"^[+-]?[0-9]{1,18}$")

CHUNK = 65536
"""Lines parsed between two progress updates."""

IGNORED = {"vt", "vn", "vp", "o", "g", "s", "usemtl", "mtllib", "l", "p", "cstype", "deg", "curv", "parm", "end"}


def parse_obj(text: str, name: str = "<obj>", tol: float | bool | None = None) -> Scaffold:
    """Parse OBJ ``text``; ``name`` is used in error messages.

    ``tol``: weld vertices closer than ``tol`` (``True``: the default tolerance of
    :func:`~lkspace.io.weld.default_tolerance`; ``None`` or ``False``: no welding).
    """
    vertices: list[list[float]] = []
    faces: list[list[int]] = []
    # a byte-order mark is no statement; lines end at \n, \r\n or \r only (as editors number them)
    lines = text.removeprefix("\ufeff").replace("\r\n", "\n").replace("\r", "\n").split("\n")
    with task(f"reading {name}", total=len(lines)) as step:
        pending, first = "", 0  # a statement continued on the next line, and its first line
        for start in range(0, len(lines), CHUNK):
            for lineno, raw in enumerate(lines[start : start + CHUNK], start=start + 1):
                body = raw.split("#", 1)[0].rstrip()
                if body.endswith("\\"):
                    first = first if pending else lineno
                    pending += body[:-1] + " "
                    continue
                where = f"{name} line {first if pending else lineno}"
                _parse_line(pending + raw, where, vertices, faces)
                pending = ""
            step.advance(min(CHUNK, len(lines) - start))
        if pending:  # the last line continued on no line
            _parse_line(pending, f"{name} line {first}", vertices, faces)
    if not vertices:
        raise ScaffoldError(f"{name}: no vertices ('v' lines) found")
    if not faces:
        raise ScaffoldError(f"{name}: no faces ('f' lines) found")
    if tol is not None and tol is not False:
        try:
            points, faces = weld((vertices, faces), default_tolerance(vertices) if tol is True else float(tol))
        except ScaffoldError as exc:
            raise ScaffoldError(f"{name}: {exc}", usage=exc.exit_code == 2) from None
        return Scaffold.from_faces(points, faces, name=name)
    return Scaffold.from_faces(vertices, faces, name=name)


def _parse_line(raw: str, where: str, vertices: list[list[float]], faces: list[list[int]]) -> None:
    """Parse one OBJ line into ``vertices`` or ``faces``; ``where`` names it in messages."""
    line = raw.split("#", 1)[0].strip()
    if not line:
        return
    tag, *parts = line.split()
    shown = raw.strip() if len(raw.strip()) <= 60 else raw.strip()[:57] + "..."
    if tag == "v":
        if len(parts) not in (3, 4, 6, 7):
            raise ScaffoldError(
                f"{where}: vertex needs 3 coordinates (then a weight or an r g b colour), got {len(parts)} "
                f"values: {shown!r}"
            )
        try:
            xyz = [float(p) for p in parts[:3]]
            for extra in parts[3:]:  # the weight or colour: unused, but numbers
                float(extra)
        except ValueError:
            raise ScaffoldError(f"{where}: vertex coordinates must be numbers: {shown!r}") from None
        if not all(abs(x) <= MAX_COORDINATE for x in xyz):  # NaN fails too
            raise ScaffoldError(
                f"{where}: vertex {len(vertices) + 1} coordinate is not a finite number within "
                f"+-{MAX_COORDINATE:g}: {shown!r}"
            )
        vertices.append(xyz)
    elif tag == "f":
        if len(parts) < 3:
            raise ScaffoldError(f"{where}: face {len(faces)} has {len(parts)} vertices; a face needs at least 3")
        n = len(vertices)
        face = []
        for part in parts:
            token, *refs = part.split("/")  # v, v/vt, v//vn or v/vt/vn: the texture and normal indices unused
            if not _INDEX.match(token) or len(refs) > 2 or not all(_INDEX.match(r) for r in refs if r):
                raise ScaffoldError(f"{where}: face vertex {part[:30]!r} is not an integer index in range")
            index = int(token)
            if 0 < index <= n:
                face.append(index - 1)
            elif index < 0 and -index <= n:
                face.append(n + index)
            else:
                raise ScaffoldError(f"{where}: face vertex index {index} out of range 1..{n} (or -{n}..-1)")
        if len(set(face)) != len(face):
            raise ScaffoldError(f"{where}: face {len(faces)} repeats a vertex: {shown!r}")
        faces.append(face)
    elif tag not in IGNORED:
        raise ScaffoldError(f"{where}: unknown OBJ statement {tag[:30]!r}")


def read_obj(path: str | os.PathLike, tol: float | bool | None = None) -> Scaffold:
    """Read an OBJ file (welded with tolerance ``tol``, see :func:`parse_obj`)."""
    return parse_obj(read_text(path, "OBJ"), name=os.path.basename(str(path)), tol=tol)


def format_obj(scaffold: Scaffold) -> str:
    """OBJ text of a finite scaffold (vertices, faces; 1-based indices)."""
    if scaffold.periodic:
        raise ScaffoldError(f"{scaffold.name}: OBJ cannot hold a periodic scaffold; write a .json scaffold file")
    lines = [f"# lkspace scaffold {scaffold.name}"]
    lines += [f"v {x!r} {y!r} {z!r}" for x, y, z in scaffold.vertices.tolist()]
    lines += ["f " + " ".join(str(v + 1) for v in face) for face in scaffold.faces()]
    return "\n".join(lines) + "\n"
