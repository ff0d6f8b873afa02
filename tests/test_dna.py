"""DNA export (docs/dna.md): the antiparallel rule by brute force, and the files read back independently.

Files are written by the real command line and read by ``tests/dna_reader.py``, which
shares no code with :mod:`lkspace.dna`; knot types come from topoly, linking numbers from
counting crossings of a projection, the design's own from ``lkspace identify``.
"""

from __future__ import annotations

import itertools
import json
import os
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import lkspace
from lkspace.dna.model import orient
from lkspace.errors import LabelError
from lkspace.strands.tracing import trace

from .cli_calls import one_line_error, run
from .dna_reader import PAIRS, crossings, read

FENE = (0.5025, 1.0025)
"""oxDNA's backbone bond stays finite between these distances of backbone sites (oxDNA units)."""
CLASH = 0.55
"""Least distance between centres of mass of nucleotides that are not backbone neighbours (units, 0.47 nm;
second neighbours where a linker meets a helix come closest)."""


def odd_edges_form_a_cut(scaffold, odd):
    """The rule of docs/dna.md: the vertices 2-colour so that exactly the odd edges join two colours."""
    colour = {}
    ab = scaffold.edge_vertices
    for start in range(scaffold.n_vertices):
        if start in colour:
            continue
        colour[start] = 0
        stack = [start]
        while stack:
            v = stack.pop()
            for e in np.flatnonzero((ab[:, 0] == v) | (ab[:, 1] == v)):
                w = int(ab[e, 1] if ab[e, 0] == v else ab[e, 0])
                c = colour[v] ^ int(odd[e])
                if w not in colour:
                    colour[w] = c
                    stack.append(w)
                elif colour[w] != c:
                    return False
    return True


@pytest.mark.parametrize("name", ["tetrahedron", "cube", "prism:3", "figure-eight", "octahedron"])
def test_antiparallel_rule_matches_brute_force(name):
    """Every parity pattern: orient() succeeds exactly when the odd edges form a cut, and then runs antiparallel."""
    s = lkspace.load(name)
    forward = s.side_forward[s.radial.edge_sides].reshape(-1, 2)
    assert (forward[:, 0] != forward[:, 1]).all(), "the rule is stated for coherently oriented faces"
    accepted = 0
    for odd in itertools.product([0, 1], repeat=s.n_edges):
        labels = 2 - np.array(odd)
        try:
            passes = orient(trace(s, labels))
        except LabelError:
            assert not odd_edges_form_a_cut(s, odd), (name, odd)
            continue
        assert odd_edges_form_a_cut(s, odd), (name, odd)
        accepted += 1
        assert (len(passes.starts) - 1) % 2 == (s.n_vertices - s.n_edges) % 2  # strands have the parity of V - E
        for e in range(s.n_edges):
            assert sorted(passes.from_a[passes.edge == e].tolist()) == [False, True]
    assert accepted == 2 ** (s.n_vertices - 1)  # one cut per 2-colouring up to swapping the colours


def export(capsys, tmp_path, *args):
    out = tmp_path / "x.oxdna"
    code, stdout, err = run(capsys, "export", *args, "-o", out, "--json")
    assert code == 0, err
    data = json.loads(stdout)
    assert sorted(os.listdir(tmp_path)) == ["x.dat", "x.oxview", "x.top"]
    return str(tmp_path / "x"), data


def linking_matrix(o):
    d = np.array([0.31, -0.57, 0.76])  # a generic direction
    n = len(o.sequences)
    m = np.zeros((n, n), int)
    for i, j in itertools.combinations(range(n), 2):
        m[i, j] = m[j, i] = crossings(o.strand(i), o.strand(j), d)
        assert crossings(o.strand(j), o.strand(i), -d) == m[i, j]  # another projection agrees
    return m


def check_dna(o):
    """Closed strands, bonded distances, pairs, complementarity, clashes, runs."""
    assert all(o.circular)
    assert "".join(o.sequences) == o.view_types
    bb = o.backbone()
    n = len(o.r)
    bonded = set()
    for k in range(len(o.sequences)):
        idx = np.arange(o.starts[k], o.starts[k + 1])
        nxt = np.roll(idx, -1)
        dist = np.linalg.norm(bb[nxt] - bb[idx], axis=1)
        assert FENE[0] < dist.min() and dist.max() < FENE[1], (k, dist.min(), dist.max())
        bonded |= set(zip(idx.tolist(), nxt.tolist()))
    paired = np.flatnonzero(o.pair >= 0)
    assert (o.pair[o.pair[paired]] == paired).all()
    seq = "".join(o.sequences)
    assert all((seq[i], seq[o.pair[i]]) in PAIRS for i in paired)
    gap = np.linalg.norm(o.r[paired] - o.r[o.pair[paired]], axis=1)
    assert (np.abs(gap - 1.2) < 0.05).all()  # oxDNA's duplex: centres 2 x 0.6 units apart, bases facing
    assert (np.einsum("ij,ij->i", o.a1[paired], o.a1[o.pair[paired]]) < -0.99).all()
    assert (np.einsum("ij,ij->i", o.a3[paired], o.a3[o.pair[paired]]) < -0.99).all()  # antiparallel
    d = np.linalg.norm(o.r[:, None] - o.r[None], axis=2)
    d[np.arange(n), np.arange(n)] = np.inf
    for i, j in bonded:
        d[i, j] = d[j, i] = np.inf
    assert d.min() > CLASH, d.min()
    for k, s in enumerate(o.sequences):
        paired_k = "".join(c if o.pair[o.starts[k] + i] >= 0 else " " for i, c in enumerate(s))
        assert not re.search(r"(A{4}|C{4}|G{4}|T{4})", paired_k), s
    assert (np.abs(o.r - o.box / 2) < o.box / 2).all()


def neighbours(scaffold, tr):
    """Pairs of strands that share an edge (their faces' strands wind there)."""
    faces = [set(tr.strand_faces(k).tolist()) for k in range(tr.components)]
    out = set()
    for f, g in scaffold.radial.edge_sides.reshape(-1, 2):
        ff, gg = scaffold.corner_face[f], scaffold.corner_face[g]
        i = next(k for k in range(len(faces)) if ff in faces[k])
        j = next(k for k in range(len(faces)) if gg in faces[k])
        out.add((min(i, j), max(i, j)))
    return out


def design_linking(capsys, *args):
    code, out, err = run(capsys, "identify", *args, "--json")
    assert code == 0, err
    return json.loads(out)


@pytest.mark.parametrize(("name", "strands", "length"), [("cube", 6, [96] * 6), ("truncated-octahedron", 14, None)])
def test_seeman_polyhedra(capsys, tmp_path, name, strands, length):
    """Chen-Seeman cube and Zhang-Seeman truncated octahedron: one cyclic strand per face, linked -2 per shared edge."""
    stem, data = export(capsys, tmp_path, name, "--twist", "4")
    o = read(stem)
    check_dna(o)
    assert len(o.sequences) == strands == data["strands"]
    assert data["base_pairs"] == [21] * len(data["base_pairs"])
    s = lkspace.load(name)
    sizes = np.diff(s.face_starts)
    lengths = [len(q) for q in o.sequences]
    if length is not None:
        assert lengths == length
    paired = [int(np.sum(o.pair[o.starts[k] : o.starts[k + 1]] >= 0)) for k in range(strands)]
    assert sorted(paired) == sorted((21 * sizes).tolist())  # 21 bp on every side of every face
    m = linking_matrix(o)
    tr = trace(s, np.full(s.n_edges, 4))
    near = neighbours(s, tr)
    for i, j in itertools.combinations(range(strands), 2):
        # right-handed B-DNA, strands 5' -> 3' (antiparallel): two turns = linking number -2
        assert m[i, j] == (-2 if (i, j) in near else 0), (i, j, m[i, j])
    if name == "cube":
        ident = design_linking(capsys, name, "--twist", "4")
        assert np.array_equal(np.abs(ident["linking_matrix"]), np.abs(m))


def test_chen_seeman_twenty_base_pairs(capsys, tmp_path):
    """--bp-per-turn 10 gives Chen and Seeman's 20 base pairs per edge; the topology is the same."""
    stem, data = export(capsys, tmp_path, "cube", "--twist", "4", "--bp-per-turn", "10")
    assert data["base_pairs"] == [20] * 12
    o = read(stem)
    check_dna(o)
    m = linking_matrix(o)
    assert sorted(np.abs(m).sum(axis=0).tolist()) == [8] * 6  # each face linked twice to 4 neighbours


@pytest.mark.parametrize(("labels", "knot"), [("2,1,2,1,1", "7_4"), ("2,3,2,1,1", "9_35")])
def test_single_stranded_knots(capsys, tmp_path, labels, knot):
    """One-strand designs on the figure-eight mesh (a theta graph): topoly names the backbone as lkspace does."""
    import topoly

    stem, data = export(capsys, tmp_path, "figure-eight", "--twist", labels)
    o = read(stem)
    check_dna(o)
    assert len(o.sequences) == 1 and data["components"] == 1
    name = topoly.alexander(o.strand(0).tolist(), closure=topoly.params.Closure.CLOSED, max_cross=60)
    ident = design_linking(capsys, "figure-eight", "--twist", labels)
    assert name == knot == ident["name"].lstrip("m")


def test_refusals(capsys, tmp_path):
    """Unbuildable designs: one line naming an edge, exit 1, nothing written."""
    out = tmp_path / "x.oxdna"
    cases = [
        (("dihedron:3", "--twist", "1"), "antiparallel"),  # the trefoil as a Moebius band's boundary
        (("dihedron:3", "--twist", "0,2,1"), "positive twist"),  # lookup's trefoil has a zero label
        (("book:3", "--twist", "4"), "3 faces"),
        (("cube", "--twist", "-4"), "right-handed"),
    ]
    for args, words in cases:
        code, _out, err = run(capsys, "export", *args, "-o", out)
        assert code == 1
        one_line_error(err, words, "edge")
    code, _out, err = run(capsys, "export", "cube", "--twist", "4", "--tubes", "-o", out)
    assert code == 2
    one_line_error(err, "--tubes")
    code, _out, err = run(capsys, "export", "cube", "--twist", "4", "--seed", "1", "-o", tmp_path / "x.obj")
    assert code == 2
    assert os.listdir(tmp_path) == []


def test_deterministic_and_seeded(capsys, tmp_path):
    for sub in "abc":
        (tmp_path / sub).mkdir()
    a, _ = export(capsys, tmp_path / "a", "tetrahedron", "--twist", "4")
    b, _ = export(capsys, tmp_path / "b", "tetrahedron", "--twist", "4")
    c, _ = export(capsys, tmp_path / "c", "tetrahedron", "--twist", "4", "--seed", "7")
    text = lambda path: Path(path).read_text()  # noqa: E731
    for ext in (".top", ".dat", ".oxview"):
        assert text(a + ext) == text(b + ext)
    assert text(a + ".top") != text(c + ".top")
    assert text(a + ".dat") == text(c + ".dat")


def test_given_sequence(capsys, tmp_path):
    """--sequence sets strand 0; its partners are complementary; a wrong length or a self-pair clash is refused."""
    given = "ACGTTGCA" * 12
    stem, _ = export(capsys, tmp_path, "cube", "--twist", "4", "--sequence", given.lower())
    o = read(stem)
    assert o.sequences[0] == given
    paired = np.flatnonzero(o.pair >= 0)
    seq = "".join(o.sequences)
    assert all((seq[i], seq[o.pair[i]]) in PAIRS for i in paired)
    for args, words in [
        (("cube", "--twist", "4", "--sequence", "ACGT"), "96"),
        (("figure-eight", "--twist", "2,1,2,1,1", "--sequence", "A" * 130), "complementary"),
    ]:
        code, _out, err = run(capsys, "export", *args, "-o", tmp_path / "y.oxdna")
        assert code == 2
        one_line_error(err, "--sequence", words)
    assert not any(p.name.startswith("y") for p in tmp_path.iterdir())


def test_nothing_half_written(capsys, tmp_path):
    """A target that cannot be written (NAME.dat is a folder) is refused before any file appears."""
    (tmp_path / "x.dat").mkdir()
    code, _out, err = run(capsys, "export", "cube", "--twist", "4", "-o", tmp_path / "x.oxdna")
    assert code == 2
    one_line_error(err, "x.dat")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.dat"]


def test_buildable_designs_at_a_scale():
    """At the scale the export chooses for the cube at twist 4, twist 4 is the one design within half a turn;
    on figure-eight at 6.1 nm per unit the one-strand designs include 9_35's labels, each buildable."""
    from lkspace.dna.search import buildable_designs, natural_twist

    cube = lkspace.load("cube")
    assert np.allclose(natural_twist(cube, 5.29989898732), 4)
    assert [d.tolist() for d in buildable_designs(cube, 5.29989898732, window=0.5)] == [[4] * 12]
    f = lkspace.load("figure-eight")
    found = [d.tolist() for d in buildable_designs(f, 6.1, components=1)]
    assert [2, 3, 2, 1, 1] in found
    for labels in found:
        assert trace(f, labels).components == 1
        orient(trace(f, labels))
        odd = np.array(labels) % 2
        assert odd_edges_form_a_cut(f, odd)
    everything = {tuple(d) for d in buildable_designs(f, 6.1)}
    brute = {
        t
        for t in itertools.product(*[range(1, 5)] * 5)
        if odd_edges_form_a_cut(f, np.array(t) % 2) and np.all(np.abs(np.array(t) - natural_twist(f, 6.1)) <= 1)
    }
    assert everything == brute


def test_studio_download(tmp_path):
    """The studio's DNA download is a zip of the three files, read back like the command's; unbuildable is refused."""
    import zipfile

    from lkspace.errors import LkspaceError
    from lkspace.studio.designs import EXPORTS, export_bytes

    assert "oxdna" in EXPORTS
    content, name = export_bytes(lkspace.load("cube"), np.full(12, 4), None, "oxdna")
    assert name == "cube_t4.4.4.4.4.4.4.4.4.4.4.4.oxdna.zip"
    (tmp_path / name).write_bytes(content)
    with zipfile.ZipFile(tmp_path / name) as archive:
        assert sorted(archive.namelist()) == sorted(
            f"cube_t4.4.4.4.4.4.4.4.4.4.4.4{s}" for s in (".top", ".dat", ".oxview")
        )
        archive.extractall(tmp_path)
    o = read(str(tmp_path / "cube_t4.4.4.4.4.4.4.4.4.4.4.4"))
    check_dna(o)
    assert len(o.sequences) == 6
    assert export_bytes(lkspace.load("cube"), np.full(12, 4), None, "oxdna")[0] == content
    with pytest.raises(LkspaceError, match="positive twist"):
        export_bytes(lkspace.load("cube"), np.zeros(12, np.int64), None, "oxdna")


def test_solve_restricted_to_dna(capsys):
    """solve --dna NM: exhaustive over the window, answers buildable and re-checked here; bad combinations refused."""
    code, out, err = run(
        capsys, "solve", "figure-eight", "--components", "1", "--dna", "6.1", "--count", "10", "--json"
    )
    assert code == 0, err
    data = json.loads(out)
    assert data["status"] == "feasible"
    assert sorted(tuple(s["labels"]) for s in data["solutions"]) == sorted(
        [(2, 3, 2, 1, 1), (2, 3, 1, 1, 2), (1, 3, 2, 2, 1), (1, 3, 1, 2, 2)]
    )
    f = lkspace.load("figure-eight")
    for s in data["solutions"]:
        assert trace(f, s["labels"]).components == 1
        orient(trace(f, s["labels"]))
    code, out, err = run(capsys, "solve", "figure-eight", "--type", "9_35", "--dna", "6.1", "--json")
    assert json.loads(out)["solutions"][0] == {"labels": [2, 3, 2, 1, 1], "name": "9_35", "components": 1}
    code, out, err = run(capsys, "solve", "cube", "--components", "1", "--dna", "5.3", "--json")
    assert code == 0 and json.loads(out)["status"] == "infeasible"  # V - E even: never one strand
    for args, words in [(("--no-zero",), "--no-zero"), ((), "--components")]:
        code, _out, err = run(capsys, "solve", "cube", "--dna", "5.3", *(("-n", "1") if args else ()), *args)
        assert code == 2
        one_line_error(err, words)


@pytest.mark.parametrize("scale", ["1e308", "99999999999999999999", "1e7", "5.2"])
def test_a_scale_too_large_or_too_small_is_one_line_naming_its_flag(capsys, tmp_path, scale):
    """--nm-per-unit 1e308 was an internal error (NaN linkers) and 1e20 a hang (a linker of 10^20 nucleotides);
    the scale's messages named --scale, the geometry's flag."""
    code, _out, err = run(capsys, "export", "cube", "--twist", "4", "--nm-per-unit", scale, "-o", tmp_path / "x.oxdna")
    assert code == 2
    one_line_error(err, "--nm-per-unit", "use a scale of at")
    assert "--scale" not in err
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("twist", ["100000", "922337203685477580", "9223372036854775807"])
def test_helices_past_the_bound_are_refused_before_any_is_built(capsys, tmp_path, twist):
    """At the default scale the size was unbounded: --twist 100000 ran for minutes, 9.2e17 was an internal
    error (an array too big) and 2**63 - 1 wrapped around to one base pair per edge (a wrong design written)."""
    code, _out, err = run(capsys, "export", "cube", "--twist", twist, "-o", tmp_path / "x.oxdna")
    assert code == 2
    one_line_error(err, "cube: its helices alone need", "past the 1,000,000 lkspace builds", "use smaller twists")
    assert os.listdir(tmp_path) == []


def stretched_box(ratio):
    """A box 1 x 1 x ``ratio``: at the default scale its short edges set the scale, its long edges take linkers."""
    corners = [(x, y, z * ratio) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    faces = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
    return lkspace.Scaffold.from_faces(np.array(corners, float), faces, name=f"box-{ratio:g}")


def test_linkers_past_the_bound_at_the_default_scale_are_refused(capsys, tmp_path):
    """A box 10,000 times longer than wide: 1.4 million nucleotides of linkers at the default scale (minutes,
    gigabytes); now one line before any is placed."""
    lkspace.io.write(stretched_box(10_000), tmp_path / "long.obj")
    code, _out, err = run(capsys, "export", tmp_path / "long.obj", "--twist", "4", "-o", tmp_path / "x.oxdna")
    assert code == 2
    one_line_error(err, "long.obj: at 10.6 nm per mesh unit its linkers could need", "make its edges more even")
    assert sorted(os.listdir(tmp_path)) == ["long.obj"]


@settings(max_examples=25, deadline=None, derandomize=True)
@given(ratio=st.floats(1, 60), twist=st.integers(1, 8))
def test_the_linker_bound_holds(ratio, twist):
    """Property: the linkers built never exceed the bound the size check uses."""
    from lkspace.dna.build import build
    from lkspace.dna.helix import edge_frames, linker_bound

    box = stretched_box(ratio)
    design = build(box, np.full(box.n_edges, twist))
    linkers = int(np.sum(design.nucleotides.edge < 0))
    assert linkers <= linker_bound(box, design.bp, edge_frames(box)[3], design.nucleotides.scale)
