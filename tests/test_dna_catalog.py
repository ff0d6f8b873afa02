"""``lkspace enumerate MESH --dna NM``: the catalog of every DNA-buildable design at a scale, and its check.

The rows are compared with a brute force written here: every label vector of the windows
(``itertools.product``), traced by a strand walk of its own and kept when the strands
can be oriented antiparallel on every edge (a 2-colouring of the strands written here,
sharing no code with ``lkspace.dna``).  The windows come from ``natural_twist`` (tested in
``tests/test_dna.py``); the catalog is written by the command line and read by pandas.
"""

from __future__ import annotations

import itertools
import json
import os
import subprocess
import sys
from collections import defaultdict

import numpy as np
import pandas as pd
import pyarrow.parquet as pq
import pytest

import lkspace
from lkspace.catalog.verify import open_catalog
from lkspace.dna.search import natural_twist

from .cli_calls import one_line_error, run


def faces_of(scaffold):
    starts = scaffold.face_starts
    return [[int(v) for v in scaffold.corners[starts[f] : starts[f + 1]]] for f in range(scaffold.n_faces)]


def strands(faces, twist):
    """The strands of a mesh whose edges all have two faces, each a list of passes ``(u, w)`` along edge {u, w}.

    ``twist`` maps ``(a, b)`` (a < b) to its label.  A side's end at ``a`` continues at ``b``
    in the same face for an even label, in the other face for an odd one (with two slots
    the radial order does not matter).
    """
    sides = defaultdict(list)
    for f, face in enumerate(faces):
        for k in range(len(face)):
            u, w = face[k], face[(k + 1) % len(face)]
            sides[(min(u, w), max(u, w))].append((f, k))

    def vertex(port):
        f, k, end = port
        return faces[f][(k + end) % len(faces[f])]

    def port(f, k, v):
        return (f, k, 0) if faces[f][k] == v else (f, k, 1)

    turn = {}
    for f, face in enumerate(faces):
        for k in range(len(face)):
            turn[(f, k, 1)] = (f, (k + 1) % len(face), 0)
            turn[(f, (k + 1) % len(face), 0)] = (f, k, 1)
    cross = {}
    for (a, b), two in sides.items():
        assert len(two) == 2
        for i, (f, k) in enumerate(two):
            g, j = two[(i + twist[(a, b)]) % 2]
            cross[port(f, k, a)] = port(g, j, b)
            cross[port(g, j, b)] = port(f, k, a)
    seen, out = set(), []
    for start in sorted(cross):
        if start in seen:
            continue
        passes, p = [], start
        while True:
            q = cross[p]
            seen.update((p, q))
            passes.append((vertex(p), vertex(q)))
            p = turn[q]
            if p == start:
                break
        out.append(passes)
    return out


def antiparallel(found):
    """Whether the strands can be oriented so that the two passes along every edge run opposite ways."""
    on_edge = defaultdict(list)
    for s, passes in enumerate(found):
        for u, w in passes:
            on_edge[(min(u, w), max(u, w))].append((s, 1 if u < w else -1))
    links = defaultdict(list)  # strand -> (other strand, the sign of the other relative to it)
    for (s1, d1), (s2, d2) in on_edge.values():  # sign1 * d1 == -sign2 * d2
        links[s1].append((s2, -d1 * d2))
        links[s2].append((s1, -d1 * d2))
    sign = {}
    for start in range(len(found)):
        if start in sign:
            continue
        sign[start], todo = 1, [start]
        while todo:
            s = todo.pop()
            for other, relative in links[s]:
                if other not in sign:
                    sign[other] = sign[s] * relative
                    todo.append(other)
                elif sign[other] != sign[s] * relative:
                    return False
    return True


def windows(scaffold, scale, window):
    natural = natural_twist(scaffold, scale)
    return [[t for t in range(1, 200) if abs(t - x) <= window] for x in natural]


def brute_force(scaffold, scale, window, components=None):
    """Rows ``(labels, strands, strand lengths)`` of every buildable design, in the catalog's order."""
    faces = faces_of(scaffold)
    pairs = [tuple(int(v) for v in ab) for ab in scaffold.edge_vertices]
    assert pairs == sorted({(min(u, w), max(u, w)) for f in faces for u, w in zip(f, f[1:] + f[:1], strict=True)})
    rows = []
    for labels in itertools.product(*windows(scaffold, scale, window)):
        found = strands(faces, dict(zip(pairs, labels, strict=True)))
        if antiparallel(found) and components in (None, len(found)):
            rows.append((labels, len(found), sorted((len(p) for p in found), reverse=True)))
    return sorted(rows, key=lambda r: ([t % 2 for t in r[0]], r[0]))


def write_obj(path, vertices, faces):
    lines = [f"v {x:.12g} {y:.12g} {z:.12g}" for x, y, z in vertices]
    lines += ["f " + " ".join(str(v + 1) for v in face) for face in faces]
    path.write_text("\n".join(lines) + "\n")
    return str(path)


def hemi_icosahedron(tmp_path):
    """The projective plane as the icosahedron modulo its antipodal map: 6 vertices, 10 triangles (non-orientable)."""
    ico = lkspace.load("icosahedron")
    v = ico.vertices
    antipode = [int(np.argmin(np.linalg.norm(v + v[i], axis=1))) for i in range(len(v))]
    keep = sorted({min(i, antipode[i]) for i in range(len(v))})
    index = {i: keep.index(min(i, antipode[i])) for i in range(len(v))}
    faces = {}
    for face in faces_of(ico):
        image = [index[i] for i in face]
        faces.setdefault(frozenset(image), image)
    return write_obj(tmp_path / "rp2.obj", v[keep].tolist(), list(faces.values()))


def flipped_cube(tmp_path):
    """The cube with two faces listed the other way round: faces not oriented coherently."""
    cube = lkspace.load("cube")
    faces = faces_of(cube)
    faces[0], faces[3] = faces[0][::-1], faces[3][::-1]
    return write_obj(tmp_path / "flipped.obj", cube.vertices.tolist(), faces)


def enumerate_dna(capsys, tmp_path, mesh, scale, *args):
    out = tmp_path / "dna.parquet"
    code, stdout, err = run(capsys, "enumerate", mesh, "--dna", scale, *args, "-o", out, "--json")
    assert code == 0, err
    return str(out), json.loads(stdout)


CASES = [
    ("cube", 5.3, 1.0),
    ("tetrahedron", 6.0, 1.0),
    ("figure-eight", 6.1, 1.0),
    ("figure-eight", 6.1, 2.0),  # several labels of one parity on an edge
    ("tetrahedron", 6.0, 1.6),
    ("octahedron", 6.0, 1.0),
    ("flipped", 5.3, 1.0),
    ("rp2", 6.25, 0.75),
]


@pytest.mark.parametrize(("name", "scale", "window"), CASES)
def test_catalog_is_the_brute_force(capsys, tmp_path, name, scale, window):
    """Every buildable assignment of the windows, once, in order, with its strands; verify accepts it."""
    mesh = {"flipped": flipped_cube, "rp2": hemi_icosahedron}.get(name, lambda _: name)(tmp_path)
    scaffold = lkspace.load(mesh)
    path, data = enumerate_dna(capsys, tmp_path, mesh, scale, "--dna-window", window)
    expected = brute_force(scaffold, scale, window)
    assert expected, "a case with no buildable design would test little"
    df = pd.read_parquet(path)
    assert [tuple(x) for x in df["labels"]] == [r[0] for r in expected]
    assert df["components"].tolist() == [r[1] for r in expected]
    assert [list(x) for x in df["strand_lengths"]] == [r[2] for r in expected]
    assert (df["orbit_size"] == 1).all() and (df["n_zero"] == 0).all()
    assert data["designs"] == len(expected) and data["group_order"] == 1
    allowed = windows(scaffold, scale, window)
    assert data["assignments"] == int(np.prod([len(w) for w in allowed]))
    meta = json.loads(pq.read_schema(path).metadata[b"lkspace"])
    assert meta["symmetry"] == "none" and meta["assignments"] == data["assignments"]
    assert meta["dna"]["nm_per_unit"] == scale and meta["dna"]["window"] == window
    assert meta["dna"]["labels"] == [[w[0], w[-1]] for w in allowed]
    assert meta["label_set"] == sorted({t for w in allowed for t in w})
    code, out, err = run(capsys, "verify", path, "--json")
    assert code == 0, err
    assert json.loads(out)["checks"].endswith("every row recomputed (DNA designs)")


def test_chen_seeman_cube(tmp_path):
    """The installed command: at 5.3 nm per unit the cube's catalog holds twist 4 everywhere, six strands of 4."""
    out = tmp_path / "x.parquet"
    done = subprocess.run(
        [sys.executable, "-m", "lkspace", "enumerate", "cube", "--dna", "5.3", "-o", str(out)],
        capture_output=True,
        text=True,
        env={**os.environ, "LKSPACE_PROGRESS": "0"},
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("cube at 5.3 nm per unit (DNA, window 1): labels 4..5, symmetry none")
    catalog = lkspace.read_catalog(str(out))
    df, labels = catalog.frame, catalog.labels
    chen_seeman = np.flatnonzero((labels == 4).all(axis=1))
    assert len(chen_seeman) == 1
    row = df.iloc[int(chen_seeman[0])]
    assert row["components"] == 6 and list(row["strand_lengths"]) == [4] * 6
    assert (labels % 2).sum(axis=1).min() == 0 and len(df) == len(brute_force(lkspace.load("cube"), 5.3, 1.0))


def damaged_copy(path, tmp_path, change):
    """Rewrite the catalog with its metadata as it was and ``change(rows)`` applied: only the rows differ."""
    table = pq.read_table(path)
    footer = pq.read_metadata(path).metadata
    rows = table.to_pylist()
    change(rows)
    bad = tmp_path / "bad.parquet"
    damaged = table.from_pylist(rows, schema=table.schema).replace_schema_metadata({b"lkspace": footer[b"lkspace"]})
    pq.write_table(damaged, bad)
    return str(bad)


def test_verify_refuses_damaged_rows(capsys, tmp_path):
    """A row that is not buildable, a row missing (another repeated), a wrong column: each one line, exit 1."""
    path, _ = enumerate_dna(capsys, tmp_path, "figure-eight", 6.1)
    good = [tuple(r[0]) for r in brute_force(lkspace.load("figure-eight"), 6.1, 1.0)]
    unbuildable = next(t for t in itertools.product(*windows(lkspace.load("figure-eight"), 6.1, 1.0)) if t not in good)

    def not_buildable(rows):
        rows[2]["labels"] = list(unbuildable)
        rows[2]["key"] = bytes(unbuildable)

    def repeated(rows):
        rows[3] = dict(rows[4])

    def wrong_strands(rows):
        rows[1]["components"] += 2

    for change, words in [
        (not_buildable, ["row 2: labels " + ",".join(map(str, unbuildable)), "not a buildable design"]),
        (repeated, ["is missing", ",".join(map(str, good[3]))]),
        (wrong_strands, ["row 1: components"]),
    ]:
        bad = damaged_copy(path, tmp_path, change)
        assert open_catalog(bad).n_rows == len(good)  # the structure checks cannot see it
        code, _out, err = run(capsys, "verify", bad)
        assert code == 1
        one_line_error(err, bad, *words)
    code, _out, err = run(capsys, "verify", damaged_copy(path, tmp_path, lambda rows: None))
    assert code == 0, err  # the copy as such is fine


def test_filters_and_counts(capsys, tmp_path):
    """--components and --max-designs filter the rows (and verify recomputes them so); --count-only writes nothing."""
    path, data = enumerate_dna(capsys, tmp_path, "figure-eight", 6.1, "--components", "1")
    expected = brute_force(lkspace.load("figure-eight"), 6.1, 1.0, components=1)
    assert [tuple(x) for x in pd.read_parquet(path)["labels"]] == [r[0] for r in expected]
    assert data["by_components"] == {"1": len(expected)}
    assert run(capsys, "verify", path)[0] == 0
    path, data = enumerate_dna(capsys, tmp_path, "cube", 5.3, "--max-designs", "5")
    assert [tuple(x) for x in pd.read_parquet(path)["labels"]] == [
        r[0] for r in brute_force(lkspace.load("cube"), 5.3, 1)
    ][:5]
    assert run(capsys, "verify", path)[0] == 0
    code, out, err = run(capsys, "enumerate", "cube", "--dna", "5.3", "--count-only", "--json")
    assert code == 0, err
    counted = json.loads(out)
    assert counted["designs"] == 128 and counted["written"] is None
    assert counted["by_components"] == {"2": 100, "4": 27, "6": 1}
    assert sum(counted["by_components"].values()) == len(brute_force(lkspace.load("cube"), 5.3, 1))


@pytest.mark.parametrize(
    ("args", "code", "words"),
    [
        (("cube", "--dna", "5.3", "--labels", "1..3"), 2, ["--labels", "window"]),
        (("cube", "--dna", "5.3", "--symmetry", "rotations"), 2, ["--symmetry", "symmetry none"]),
        (("cube", "--dna", "5.3", "--jobs", "2"), 2, ["--jobs"]),
        (("cube", "--dna", "5.3", "--mode", "residues"), 2, ["--mode"]),
        (("cube", "--dna", "5.3", "--no-zero"), 2, ["--no-zero", "positive"]),
        (("cube", "--dna", "5.3", "--invariant", "C3"), 2, ["--invariant"]),
        (("cube", "--dna", "5.3", "--tolerance", "0.01"), 2, ["--tolerance", "no symmetry"]),
        (("cube", "--dna", "5.3", "--resume"), 2, ["--resume", "one file"]),
        (("cube", "--dna-window", "2"), 2, ["--dna-window needs --dna"]),
        (("book:3", "--dna", "5"), 1, ["edge 0 (0-1) has 3 faces"]),
        (("cube", "--dna", "1"), 1, ["edge 0 (0-1) has no label", "--dna-window"]),
        (("cube", "--dna", "5.3", "--dna-window", "3"), 2, ["68,024,448 buildable assignments", "--dna-window"]),
    ],
)
def test_refusals(capsys, tmp_path, args, code, words):
    """What does not make sense with --dna is one line naming it, and nothing is written."""
    out = tmp_path / "x.parquet"
    got, _out, err = run(capsys, "enumerate", *args, "-o", out)
    assert got == code
    one_line_error(err, *words)
    assert not out.exists() and os.listdir(tmp_path) == []


def test_symmetry_none_is_accepted(capsys, tmp_path):
    """--symmetry none says what a DNA catalog does anyway."""
    path, data = enumerate_dna(capsys, tmp_path, "tetrahedron", 6.0, "--symmetry", "none")
    assert data["designs"] == len(brute_force(lkspace.load("tetrahedron"), 6.0, 1.0))


def test_output_checked_before_work(capsys, tmp_path):
    """-o onto a file lkspace did not write, or onto a URL, is refused and the file stays as it was."""
    foreign = tmp_path / "notes.parquet"
    foreign.write_bytes(b"not a catalog")
    code, _out, err = run(capsys, "enumerate", "cube", "--dna", "5.3", "-o", foreign)
    assert code == 2 and foreign.read_bytes() == b"not a catalog"
    one_line_error(err, "notes.parquet")
    code, _out, err = run(capsys, "enumerate", "cube", "--dna", "5.3", "-o", "memory://cat.parquet")
    assert code == 2
    one_line_error(err, "one local .parquet file")


def test_rows_export_and_identify(capsys, tmp_path):
    """A row of a DNA catalog is a design like any other: export and identify read it."""
    path, _ = enumerate_dna(capsys, tmp_path, "figure-eight", 6.1, "--components", "1")
    code, out, err = run(capsys, "identify", path, "--row", "0", "--json")
    assert code == 0, err
    assert json.loads(out)["components"] == 1


def bowtie(tmp_path):
    """Two tetrahedra sharing one vertex (its faces make two separate fans there)."""
    vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [-1, 0, 0], [0, -1, 0], [0, 0, -1]]
    faces = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3], [0, 4, 5], [0, 6, 4], [0, 5, 6], [4, 6, 5]]
    return write_obj(tmp_path / "bowtie.obj", vertices, faces)


@pytest.mark.parametrize("make", [flipped_cube, hemi_icosahedron, bowtie, lambda _: "prism:3"])
def test_parity_patterns_are_the_antiparallel_ones(tmp_path, make):
    """Every parity pattern of the mesh: listed by lkspace.dna.parity exactly when the strands run antiparallel."""
    from lkspace.dna.parity import parity_patterns, parity_system

    scaffold = lkspace.load(make(tmp_path))
    faces, n = faces_of(scaffold), scaffold.n_edges
    pairs = [tuple(int(v) for v in ab) for ab in scaffold.edge_vertices]
    truth = set()
    for odd in itertools.product((0, 1), repeat=n):
        if antiparallel(strands(faces, dict(zip(pairs, (2 - x for x in odd), strict=True)))):
            truth.add(int("".join(map(str, odd)), 2))
    listed = parity_patterns(parity_system(scaffold), {})
    assert list(listed) == sorted(truth) and listed.count == len(truth) > 0
    fixed = parity_patterns(parity_system(scaffold), {0: 1})  # edge 0 odd: the most significant bit
    assert list(fixed) == sorted(p for p in truth if p >> (n - 1))


def test_orient_judges_patterns_it_does_not_accept(monkeypatch):
    """Were the linear algebra to list every parity pattern, orient() would still keep only the buildable ones."""
    from lkspace.catalog import dna_rows
    from lkspace.dna.parity import Patterns

    cube = lkspace.load("cube")
    every = Patterns(0, tuple(1 << i for i in range(cube.n_edges)))
    monkeypatch.setattr(dna_rows, "parity_patterns", lambda system, fixed: every)
    space = dna_rows.dna_space(cube, 5.3)
    labels = np.concatenate([block.labels for block in dna_rows.dna_blocks(space)])
    assert [tuple(row) for row in labels.tolist()] == [r[0] for r in brute_force(cube, 5.3, 1.0)]
