"""Hypothesis strategies: random non-manifold scaffolds and labels."""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st

from lkspace import Scaffold


@st.composite
def scaffolds(draw, max_vertices: int = 8, max_faces: int = 7):
    """Random polygon meshes with generic vertex positions (unambiguous radial order).

    Faces are random vertex cycles, so edges of any degree, boundary, vertex-only
    contacts and two-sided polygons all occur.
    """
    n = draw(st.integers(3, max_vertices))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    vertices = rng.normal(size=(n, 3))
    n_faces = draw(st.integers(1, max_faces))
    faces = []
    for _ in range(n_faces):
        size = draw(st.integers(3, min(n, 6)))
        faces.append(draw(st.permutations(range(n)))[:size])
    if draw(st.booleans()) and faces:  # a two-sided polygon now and then
        faces.append(list(reversed(faces[0])))
    return Scaffold.from_faces(vertices, faces, name="random")


def _traceable(scaffold) -> bool:
    from lkspace.errors import RadialOrderError

    try:
        scaffold.radial
    except RadialOrderError:  # two faces at one angle around an edge of degree >= 3
        return False
    return True


def traceable_scaffolds(**kwargs):
    """Random scaffolds whose radial order is unambiguous."""
    return scaffolds(**kwargs).filter(_traceable)


# ---- inputs at and past the bounds (tests/test_fuzz_bounds.py) ---------------------------
# Each strategy below makes input that is cheap to write but expensive if lkspace does not
# check its size first: huge polygons, unused vertices, supercells, parameters, floats.

EXTREME_FLOATS = ["5e-324", "1e-300", "2.3e-308", "1e-12", "1e300", "1.7976931348623157e308"]
"""Option values at the edges of float64: subnormal, tiny, huge (nan and inf are refused by type)."""

LENGTH_OPTIONS = ["--thickness", "--clearance", "--scale", "--inset", "--pitch", "--helix-radius", "--tube-radius",
                  "--normal-offset"]  # fmt: skip
"""Numeric options of ``lkspace export`` that take a length or a factor."""

MATHTEXT_PIECES = ["$", "\\$", "\\frac{", "}", "{", "^", "_", "\\sqrt", "\\alpha", "\\foo", "x", " ", "\\", "\\left(",
                   "\\right)", "\\mathrm{", "2", "%", "#", "&"]  # fmt: skip


@st.composite
def mathtext_titles(draw) -> str:
    """A picture title made of mathtext pieces: often broken (odd braces, unknown commands), sometimes fine."""
    return "".join(draw(st.lists(st.sampled_from(MATHTEXT_PIECES), min_size=1, max_size=8)))


def polygon_obj(n_sides: int, two_sided: bool) -> bytes:
    """An OBJ of one regular ``n_sides``-gon (and its reverse when ``two_sided``): big, cheap to write."""
    angles = 2 * np.pi * np.arange(n_sides) / n_sides
    lines = [f"v {np.cos(a):.9f} {np.sin(a):.9f} 0" for a in angles]
    lines.append("f " + " ".join(str(i + 1) for i in range(n_sides)))
    if two_sided:
        lines.append("f " + " ".join(str(i + 1) for i in reversed(range(n_sides))))
    return ("\n".join(lines) + "\n").encode()


def unused_vertices_obj(n_unused: int, coincident: bool) -> bytes:
    """An OBJ of one triangle and ``n_unused`` vertices in no face (all at one point, or on a line)."""
    spare = "v 0 0 0\n" * n_unused if coincident else "".join(f"v {i} 5 5\n" for i in range(n_unused))
    return ("v 0 0 0\nv 1 0 0\nv 0 1 0\n" + spare + "f 1 2 3\n").encode()


def strip_obj(n_quads: int) -> bytes:
    """An OBJ strip of ``n_quads`` quads in a row (``3 n + 1`` edges), slightly bent so it has no symmetry."""
    lines = [f"v {i} {y} {0.001 * (i % 7)}" for i in range(n_quads + 1) for y in (0, 1)]
    lines += [f"f {2 * i + 1} {2 * i + 3} {2 * i + 4} {2 * i + 2}" for i in range(n_quads)]
    return ("\n".join(lines) + "\n").encode()


SUPERCELL_BASES = {"tiling:square": 2, "tiling:hexagonal": 2, "honeycomb:cP": 3, "honeycomb:cI": 3}
"""Periodic built-ins and their dimension, for supercell specs."""


@st.composite
def oversized_supercells(draw) -> str:
    """A supercell ``NAME@AxB[xC]`` with more faces than ``MAX_SUPERCELL_FACES`` (sizes up to 10^12 cells)."""
    name = draw(st.sampled_from(sorted(SUPERCELL_BASES)))
    dim = SUPERCELL_BASES[name]
    sizes = [draw(st.integers(1, 10**4)) for _ in range(dim)]
    sizes[draw(st.integers(0, dim - 1))] = draw(st.integers(200_001, 10**12))  # past the bound alone
    return f"{name}@{'x'.join(map(str, sizes))}"


@st.composite
def oversized_families(draw) -> str:
    """``dihedron:N``, ``book:K`` or ``kaleidocycle:K`` past ``MAX_FAMILY_PARAMETER`` (1000)."""
    family = draw(st.sampled_from(["dihedron", "book", "kaleidocycle"]))
    n = draw(st.one_of(st.integers(1001, 10**6), st.sampled_from([10**18, 10**100])))
    return f"{family}:{2 * (n // 2) if family == 'kaleidocycle' else n}"


# ---- bad input for the command line (tests/test_fuzz_cli.py) ------------------------------
# Each strategy below makes input that is certainly bad: a valid base with one defect.

JUNK = st.one_of(
    st.booleans(),
    st.none(),
    st.text(max_size=4),
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([10**30, -(2**63), 2**63, 2**64 + 1, 10**400]),
    st.dictionaries(st.text(max_size=2), st.integers(), max_size=2),
)
"""Values of the wrong type or far out of range (never a list, never a small integer)."""

NOT_INDEX = st.one_of(JUNK, st.integers(max_value=-1), st.integers(min_value=4, max_value=2**70))
"""Never a valid vertex index of a 4-vertex mesh."""

BAD_NUMBER_TOKENS = ["nan", "inf", "-inf", "1e400", "1" + "0" * 400, "x", "0x1", "1,5", "--1", "1e13", "NaN", "²"]
BAD_INDEX_TOKENS = ["0", "5", "-5", "1" + "0" * 30, "1.5", "a", "1e3", "9223372036854775808", "-0", "½", "+-1"]

TETRA_V = ["v 1 1 1", "v 1 -1 -1", "v -1 1 -1", "v -1 -1 1"]
TETRA_F = ["f 1 2 3", "f 1 4 2", "f 1 3 4", "f 2 4 3"]


@st.composite
def bad_obj_files(draw) -> bytes:
    """A tetrahedron OBJ with one defect (bad coordinate, index, statement, byte, or nothing at all)."""
    lines = TETRA_V + TETRA_F
    kind = draw(
        st.sampled_from(
            ["coordinate", "count", "index", "short-face", "repeat", "statement", "bytes", "empty", "no-faces", "zero"]
        )
    )
    if kind == "coordinate":
        row = draw(st.integers(0, 3))
        parts = lines[row].split()
        parts[draw(st.integers(1, 3))] = draw(st.sampled_from(BAD_NUMBER_TOKENS))
        lines[row] = " ".join(parts)
    elif kind == "count":
        lines[draw(st.integers(0, 3))] = "v" + " 0.5" * draw(st.sampled_from([0, 1, 2, 5, 9]))
    elif kind == "index":
        row = draw(st.integers(4, 7))
        parts = lines[row].split()
        token = draw(st.sampled_from(BAD_INDEX_TOKENS))
        parts[draw(st.integers(1, 3))] = token + draw(st.sampled_from(["", "/1", "//2", "/1/1"]))
        lines[row] = " ".join(parts)
    elif kind == "short-face":
        lines[draw(st.integers(4, 7))] = draw(st.sampled_from(["f", "f 1", "f 1 2", "f 1/1 2/2"]))
    elif kind == "repeat":
        lines[draw(st.integers(4, 7))] = draw(st.sampled_from(["f 1 2 1", "f 2 2 3 4", "f 1 2 3 -4 1"]))
    elif kind == "statement":
        lines.insert(draw(st.integers(0, 8)), draw(st.sampled_from(["vv 1 2 3", "face 1 2 3", "x", "F 1 2 3", "3"])))
    elif kind == "empty":
        lines = draw(st.sampled_from([[], ["# only a comment"], ["", "   "]]))
    elif kind == "no-faces":
        lines = draw(st.sampled_from([TETRA_V, TETRA_F, TETRA_V + ["vt 0 0", "vn 0 0 1"]]))
    elif kind == "zero":
        lines = TETRA_V + ["v 1 1 1"] + ["f 1 5 2"] + TETRA_F
    newline = draw(st.sampled_from(["\n", "\r\n"]))
    data = newline.join(lines).encode() + newline.encode()
    if kind == "bytes":
        at = draw(st.integers(0, len(data)))
        data = (
            data[:at] + draw(st.sampled_from([b"\xff", b"\xfe\xfe", b"\xc3", b"\xed\xa0\x80", b"\x80abc"])) + data[at:]
        )
    if draw(st.booleans()):
        data = b"\xef\xbb\xbf" + data
    return data


TETRA_JSON = {
    "format": "lkspace-scaffold",
    "version": 1,
    "vertices": [[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]],
    "faces": [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]],
}
"""A good scaffold file (the tetrahedron, six edges) that the strategies below break."""


@st.composite
def bad_scaffold_json(draw) -> bytes:
    """A scaffold file with one defect in one field, or malformed as a whole."""
    import copy
    import json

    data = copy.deepcopy(TETRA_JSON)
    field = draw(
        st.sampled_from(
            ["format", "version", "name", "vertices", "vertex", "coordinate", "faces", "face", "index", "lattice",
             "offsets", "radial_orders", "edges", "labels", "label", "nulls", "unknown", "missing", "whole"]
        )
    )  # fmt: skip
    if field in ("format", "version", "name"):
        data[field] = draw(JUNK.filter(lambda v: not isinstance(v, str) or field != "name"))
    elif field in ("vertices", "faces", "lattice", "offsets", "radial_orders", "labels", "nulls"):
        data[field] = draw(st.one_of(JUNK, st.lists(JUNK, min_size=1, max_size=3)))
    elif field == "vertex":
        data["vertices"][draw(st.integers(0, 3))] = draw(st.one_of(JUNK, st.lists(st.integers(), max_size=2)))
    elif field == "coordinate":
        data["vertices"][draw(st.integers(0, 3))][draw(st.integers(0, 2))] = draw(JUNK)
    elif field == "face":
        data["faces"][draw(st.integers(0, 3))] = draw(st.one_of(JUNK, st.lists(st.integers(0, 3), max_size=2)))
    elif field == "index":
        data["faces"][draw(st.integers(0, 3))][draw(st.integers(0, 2))] = draw(NOT_INDEX)
    elif field == "edges":
        data["edges"] = draw(st.one_of(JUNK, st.lists(st.lists(NOT_INDEX, max_size=3), min_size=1, max_size=6)))
    elif field == "label":
        data["labels"] = [0] * 6
        data["labels"][draw(st.integers(0, 5))] = draw(
            JUNK.filter(lambda v: not isinstance(v, int) or v is True or v is False or abs(v) > 2**63 - 1)
        )
    elif field == "unknown":
        data[draw(st.sampled_from(["colour", "twist", "Vertices", ""]))] = 1
    elif field == "missing":
        del data[draw(st.sampled_from(["vertices", "faces"]))]
    else:
        return draw(
            st.sampled_from(
                [b"", b"[1, 2]", b"5", b'"text"', b"{", b"[" * 5000 + b"]" * 5000, b'{"vertices": [[1e999, 0, 0]]}',
                 b"\xff\xfe{}", b'{"vertices": ' + b"[" * 100000 + b"]" * 100000 + b"}", b"\xef\xbb\xbf[]"]
            )
        )  # fmt: skip
    return json.dumps(data).encode()


@st.composite
def bad_twist_files(draw) -> tuple[str, bytes]:
    """``(extension, contents)`` of a twist file for the cube (12 edges) with one defect."""
    import json

    form = draw(st.sampled_from(["json-key", "json-list", "json-value", "json-labels", "text", "text-edge", "raw"]))
    if form == "json-key":
        return ".json", json.dumps({"twists": draw(JUNK)}).encode()
    if form == "json-labels":
        n = draw(st.sampled_from([0, 1, 11, 13]))
        return ".json", json.dumps({"labels": [1] * n}).encode()
    if form == "json-list":
        return ".json", json.dumps([1] * 11 + [draw(JUNK)]).encode()
    if form == "json-value":
        return ".json", json.dumps({"*": 0, "0-1": draw(JUNK)}).encode()
    if form == "text":
        value = draw(st.sampled_from(["x", "1.5", str(2**63), "-" + "9" * 50, "", "1 2"]))
        return ".txt", f"* 0\n0-1 {value}\n".encode()
    if form == "text-edge":
        edge = draw(st.sampled_from(["0-0", "0-8", "7-7", "9-1", "1" + "0" * 30 + "-2", "a-b", "12", "-1", "0-1[1]"]))
        return ".txt", f"* 0\n{edge} 1\n".encode()
    return ".txt", draw(st.sampled_from([b"", b"# nothing\n", b"0-1 1\n", b"\xff 1\n", b"* 1\n* 1\n0-1 1\n0-1 2\n"]))


HUGE = ["9223372036854775808", str(2**64), "-" + str(2**63), "1" + "0" * 30, "9" * 5000]
BAD_TWISTS = st.one_of(
    st.sampled_from(HUGE + ["1.5", "x", "", " ", "1,,2", "--1", "1e3", "0x10", "½", ","]),
    st.lists(st.integers(-3, 3).map(str), min_size=1, max_size=30)
    .filter(lambda v: len(v) not in (1, 12))
    .map(",".join),
    st.integers(0, 11).map(lambda i: ",".join(["1"] * i + [HUGE[i % len(HUGE)]] + ["1"] * (11 - i))),
)
"""``--twist`` values that are bad for the cube (12 edges)."""

BAD_NULLS = st.sampled_from(
    ["x", "1", "6.0", "0.4", "-1.0", "0.-1", "1" + "0" * 30 + ".0", "0." + "9" * 50, "0.0,x", "."]
)
"""``--null`` values that are bad for the cube (6 quads)."""

BAD_LABEL_SETS = st.sampled_from(
    ["", ",", "x", "2..-2", "1..", "..1", "1.5", "-2..2..3", f"0..{2**63}", f"-{2**62}..{2**62}", "9" * 5000,
     "0..1000000", "1,,x", "--2..2"]
)  # fmt: skip
"""``--labels`` values that are bad."""

BAD_NAMES = st.one_of(
    st.sampled_from(["book", "book:", "book:x", "book:0", "book:-3", "book:1001", "book:999999999999", "book:3.5",
                     "book:" + "9" * 5000, "dihedron:2", "dihedron:999999999999", "dihedron:1_000", "honeycomb:cP@0x1x1",
                     "honeycomb:cP@2x2", "honeycomb:cP@1000x1000x1000", "honeycomb:cP@" + "9" * 400 + "x1x1",
                     "tiling:square@2x2x2", "cube@2x2x2", "honeycomb:xx", "tiling:", "voronoi:", "prism", "", "@",
                     "honeycomb:cI@100x100x100", "book:3@2x2", "dihedron:+5 "]),
    st.integers(1001, 10**15).map(lambda n: f"book:{n}"),
    st.tuples(st.integers(60, 10**6), st.integers(60, 10**6), st.integers(60, 100)).map(
        lambda t: f"honeycomb:cP@{t[0]}x{t[1]}x{t[2]}"
    ),
)  # fmt: skip
"""MESH values that are neither files nor good built-in names."""


PLANE_LATTICES = {  # reduced bases: the brute-force reference needs N entries up to 2 only
    "square": [[1.0, 0, 0], [0, 1, 0]],
    "hexagonal": [[1.0, 0, 0], [0.5, 3**0.5 / 2, 0]],
    "rectangular": [[1.0, 0, 0], [0, 1.5, 0]],
    "centred": [[1.0, 0, 0], [0.5, 1.25, 0]],
    "oblique": [[1.0, 0, 0], [0.3, 1.2, 0]],
}


@st.composite
def voronoi_tilings(draw):
    """``(lattice name, generators (n, 3))``: 1-3 points at quarter lattice coordinates of a plane lattice."""
    name = draw(st.sampled_from(sorted(PLANE_LATTICES)))
    quarters = st.tuples(st.integers(0, 3), st.integers(0, 3))
    cells = draw(st.lists(quarters, min_size=1, max_size=3, unique=True))
    basis = np.array(PLANE_LATTICES[name])
    return name, np.array(cells, dtype=np.float64) / 4 @ basis


def malformed_lists(n: int) -> st.SearchStrategy[str]:
    """Comma lists of ``n`` small integers with one item empty or spelled with non-ASCII digits (read as 3 or 1 once)."""
    items = st.lists(st.integers(-2, 2).map(str), min_size=n, max_size=n)
    bad = st.sampled_from(["", " ", "\u0663", "\uff11", "-\u0661", "\u0967", "1\u0662"])
    return st.tuples(items, st.integers(0, n - 1), bad).map(
        lambda t: ",".join([*t[0][: t[1]], t[2], *t[0][t[1] + 1 :]])
    )
