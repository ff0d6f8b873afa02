"""Design to a target: solve --type / --linking-matrix and atlas, against known answers."""

import json
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import lkspace
from lkspace import identify, load

pytest.importorskip("spherogram")
pytest.importorskip("snappy")

from lkspace.linktypes.atlas import AtlasOptions, atlas  # noqa: E402
from lkspace.linktypes.linking import matches, parse_linking_matrix  # noqa: E402
from lkspace.linktypes.names import parse_type  # noqa: E402
from lkspace.linktypes.screen import Goal  # noqa: E402
from lkspace.linktypes.search import SearchOptions, solve_target  # noqa: E402

from .cli_calls import run


def solve_type(mesh, name, labels="-1..1", **kw):
    target = parse_type(name, kw.pop("chirality", "any"))
    lo, hi = (int(x) for x in labels.split(".."))
    options = SearchOptions(**kw)
    return solve_target(load(mesh), Goal(target.components, target), label_set=np.arange(lo, hi + 1), options=options)


def assert_reidentified(mesh, solution, name):
    """An answer names the type again under an independent call (another projection seed)."""
    solution = solution if isinstance(solution, dict) else solution.to_json()
    again = identify(mesh, solution["labels"], seed=17)
    assert again.name == name and again.components == solution["components"]
    return again


@pytest.mark.parametrize(("n", "name"), [(3, "3_1"), (4, "L4a1"), (5, "5_1"), (6, "L6a3"), (7, "7_1")])
def test_dihedra_make_the_torus_knots_and_links_t2n(n, name):
    result = solve_type(f"dihedron:{n}", name, "0..1")
    assert result.status == "found"
    (sol,) = result.solutions
    assert sol.labels == (1,) * n and sol.name == name
    assert_reidentified(f"dihedron:{n}", sol, name)


def test_book3_twist_2_is_the_trefoil():
    result = solve_type("book:3", "3_1", "0..2", count=1)
    assert result.status == "found"
    sol = result.solutions[0]
    assert sol.labels[0] == 2 and sum(abs(t) for t in sol.labels) == 2  # the spine edge alone
    assert_reidentified("book:3", sol, "3_1")


def test_tetrahedron_all_ones_is_the_borromean_rings(capsys):
    code, out, err = run(capsys, "solve", "tetrahedron", "--type", "L6a4", "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data["status"] == "found" and data["target"]["table"] == "linkinfo"
    sol = data["solutions"][0]
    assert sol["labels"] in ([1] * 6, [-1] * 6) and sol["name"] == "L6a4" and sol["reidentified"]
    assert_reidentified("tetrahedron", sol, "L6a4")


def test_figure_eight_mesh_gives_4_1():
    result = solve_type("figure-eight", "4_1")
    assert result.status == "found"
    assert_reidentified("figure-eight", result.solutions[0], "4_1")


def test_chirality_is_asked_for_and_reported():
    left = solve_type("dihedron:3", "m3_1", "-1..1").solutions[0]
    right = solve_type("dihedron:3", "3_1", "-1..1", chirality="table").solutions[0]
    assert left.chiral_name == "m3_1" and left.mirror is True
    assert right.chiral_name == "3_1" and right.mirror is False
    assert identify("dihedron:3", left.labels).details["chiral_name"] == "m3_1"
    assert parse_type("m4_1").amphichiral  # the figure-eight knot is its own mirror image


def test_absent_type_is_proved_absent(capsys):
    result = solve_type("tetrahedron", "4_1")
    assert result.status == "exhausted" and result.complete and not result.solutions
    code, out, err = run(capsys, "solve", "tetrahedron", "--type", "5_1", "--labels", "-1..1", "--json")
    assert code == 0 and json.loads(out)["status"] == "exhausted"


def test_time_running_out_is_unknown():
    # a 13-crossing knot among the octahedron's ten million designs: not decided in half a second
    result = solve_type("octahedron", "13a_1", "-2..2", time_limit=0.5)
    assert result.status == "unknown" and not result.complete


def test_linking_matrix_targets(capsys):
    code, out, err = run(capsys, "solve", "tetrahedron", "--linking-matrix", "0,1,1;1,0,1;1,1,0", "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data["status"] == "found"
    got = np.array(data["solutions"][0]["linking_matrix"])
    assert matches(got, parse_linking_matrix("0,1,1;1,0,1;1,1,0"))
    assert np.array_equal(np.array(identify("tetrahedron", data["solutions"][0]["labels"]).linking_matrix), got)
    # three rings, none linked with another but not split apart: the Borromean rings
    code, out, err = run(capsys, "solve", "tetrahedron", "--linking-matrix", "0,0,0;0,0,0;0,0,0", "--type", "L6a4")
    assert code == 0 and "found" in out, err
    # every pair linked twice: absent from the tetrahedron's -1..1 space
    code, out, err = run(capsys, "solve", "tetrahedron", "--labels", "-1..1", "--linking-matrix", "0,2,2;2,0,2;2,2,0")
    assert code == 0 and "exhausted" in out, err


def test_signed_linking_matrix():
    hopf = Goal(2, None, parse_linking_matrix("0,1;1,0"), signed=True)
    anti = Goal(2, None, parse_linking_matrix("0,-1;-1,0"), signed=True)
    a = solve_target(load("dihedron:4"), anti, label_set=np.arange(0, 2), options=SearchOptions(count=1))
    b = solve_target(load("dihedron:4"), hopf, label_set=np.arange(-1, 1), options=SearchOptions(count=1))
    assert solve_target(load("dihedron:4"), hopf, label_set=np.arange(0, 2)).status == "exhausted"
    # the two faces of a dihedron run in opposite directions: positive twists link them negatively
    for result, sign in ((a, -1), (b, 1)):
        assert result.status == "found"
        assert result.solutions[0].linking_matrix[0][1] == sign


@settings(max_examples=40, deadline=None)
@given(st.integers(2, 6).flatmap(lambda n: st.tuples(
    st.lists(st.integers(-3, 3), min_size=n * (n - 1) // 2, max_size=n * (n - 1) // 2), st.permutations(range(n)))))  # fmt: skip
def test_linking_matrices_match_up_to_renumbering(data):
    upper, perm = data
    n = len(perm)
    m = np.zeros((n, n), np.int64)
    m[np.triu_indices(n, 1)] = upper
    m = m + m.T
    p = np.array(perm)
    assert matches(m[p][:, p], m, signed=True)
    assert matches(-m, m) and (matches(-m, m, signed=True) == (not np.any(m)) or matches(-m, m, signed=True))
    if np.any(m):
        bumped = m.copy()
        i, j = np.argwhere(m != 0)[0]
        bumped[i, j] = bumped[j, i] = m[i, j] + 10
        assert not matches(bumped, m)


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--type", "9_99"], ["no such knot or link type", "9_99"]),
        (["--type", "K5a9"], ["no such knot or link type"]),
        (["--linking-matrix", "0,1;2,0"], ["not symmetric"]),
        (["--linking-matrix", "0,x;1,0"], ["write integers"]),
        (["--type", "3_1", "--components", "1"], ["do not apply"]),
        (["--type", "m3_1", "--chirality", "table"], ["mirror image"]),
        (["--components", "1", "--chirality", "mirror"], ["apply to --type"]),
        (["--type", "L6a4", "--linking-matrix", "0,1;1,0"], ["components"]),
    ],
)
def test_bad_targets_are_one_line_and_exit_2(capsys, args, words):
    code, out, err = run(capsys, "solve", "tetrahedron", *args)
    assert code == 2 and err.count("\n") == 1 and err.startswith("lkspace: error: "), err
    for word in words:
        assert word in err


def test_installed_cli_solves_and_maps(tmp_path):
    exe = [sys.executable, "-m", "lkspace"]
    out = subprocess.run([*exe, "solve", "dihedron:5", "--type", "5_1", "--json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout)["solutions"][0]["name"] == "5_1"
    bad = subprocess.run([*exe, "solve", "cube", "--type", "nope"], capture_output=True, text=True)
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1 and "Traceback" not in bad.stderr
    folder = tmp_path / "atlas"
    done = subprocess.run(
        [*exe, "atlas", "dihedron:4", "--labels", "-1..1", "-o", str(folder), "--pictures", "1", "--json"],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    data = json.loads(done.stdout)
    names = {t["name"] for t in data["types"]}
    assert {"0_1", "L2a1", "L4a1"} <= names
    assert (folder / "README.md").read_text().count("| L4a1") == 1 or "L4a1" in (folder / "README.md").read_text()
    pngs = list(folder.glob("*.png"))
    assert len(pngs) == 1 and pngs[0].stat().st_size < 150_000


def test_atlas_agrees_with_the_catalogs_identification(tmp_path, capsys):
    catalog = tmp_path / "tet.parquet"
    code, out, err = run(capsys, "enumerate", "tetrahedron", "--labels", "-1..1", "--identify", "-o", catalog)
    assert code == 0, err
    code, out, err = run(capsys, "atlas", catalog, "--json")
    assert code == 0, err
    keep = ("designs", "assignments", "simplest_sum_abs", "chirality")
    from_catalog = {t["name"]: [t[k] for k in keep] for t in json.loads(out)["types"]}
    direct = atlas(load("tetrahedron"), np.arange(-1, 2)).to_json()
    named = {t["name"]: [t[k] for k in keep] for t in direct["types"] if t["name"][0] not in "su"}
    assert direct["designs"] == 87 and direct["assignments"] == 3**6
    for name, counts in named.items():
        assert from_catalog[name] == counts, name
    assert named["L6a4"][:2] == [2, 2] and named["3_1"][0] == 4


def test_atlas_resumes_from_its_cache(tmp_path):
    first = atlas(load("dihedron:3"), np.arange(-1, 2), str(tmp_path)).to_json()
    assert first["identified_now"] == first["designs"]
    lines = (tmp_path / "cache.jsonl").read_text().splitlines()
    (tmp_path / "cache.jsonl").write_text("\n".join(lines[:-2]) + "\n" + lines[-2][:5])  # an interrupted run
    again = atlas(load("dihedron:3"), np.arange(-1, 2), str(tmp_path)).to_json()
    assert again["identified_now"] == 2 and again["types"] == first["types"]


def test_hoste_thistlethwaite_names_with_chirality():
    import snappy

    from lkspace.knots.naming import name_pd, one_based

    for name in ("K14n10910", "L13n4723"):
        link = snappy.HTLinkExteriors[name].link()
        for mirrored, lk in ((False, link), (True, link.mirror())):
            got = name_pd(one_based(lk.PD_code()), len(lk.link_components))
            assert (got.name, got.table, got.mirror) == (name, "HTLinkExteriors", mirrored)
    target = parse_type("K14n10910")
    assert (target.components, target.crossings, target.table) == (1, 14, "HTLinkExteriors")


def reverse_component(pd, component_edges):
    """The PD code with one component (edges numbered consecutively) run the other way."""
    a, b = min(component_edges), max(component_edges)

    def flip(e):
        return a + b - e if a <= e <= b else e

    out = []
    for i, j, k, ll in pd:
        x = [flip(i), flip(j), flip(k), flip(ll)]
        out.append([x[2], x[3], x[0], x[1]] if a <= i <= b else x)  # the incoming under edge first
    return out


def test_jones_filter_holds_every_orientation_of_a_link():
    """Reversing a component changes the Jones polynomial; the target's fingerprints hold both."""
    import regina
    import snappy

    from lkspace.knots.naming import one_based
    from lkspace.knots.tables import JONES_POINT, laurent_value

    pd = one_based(snappy.HTLinkExteriors["L13n4723"].link().PD_code())
    parent = {e: e for x in pd for e in x}

    def root(e):
        while parent[e] != e:
            e = parent[e]
        return e

    for i, j, k, ll in pd:
        parent[root(i)], parent[root(j)] = root(k), root(ll)
    comps = {}
    for e in parent:
        comps.setdefault(root(e), []).append(e)
    fps = parse_type("L13n4723").fingerprints
    values = {laurent_value(regina.Link.fromPD(pd).jones(), JONES_POINT)}
    for comp in comps.values():
        values.add(laurent_value(regina.Link.fromPD(reverse_component(pd, comp)).jones(), JONES_POINT))
    assert len(values) == 2 and values <= fps


def test_worker_processes_give_the_same_answers():
    one = solve_type("tetrahedron", "3_1", "-1..1", count=3)
    two = solve_type("tetrahedron", "3_1", "-1..1", count=3, processes=2)
    assert one.status == two.status == "found"
    assert [s.labels for s in one.solutions] == [s.labels for s in two.solutions]
    assert (
        atlas(load("dihedron:4"), np.arange(-1, 2), options=AtlasOptions(processes=2)).types
        == atlas(load("dihedron:4"), np.arange(-1, 2)).types
    )


def test_atlas_with_a_time_budget_is_partial_then_resumes(tmp_path):
    whole = atlas(load("dihedron:4"), np.arange(-2, 3)).to_json()
    part = atlas(load("dihedron:4"), np.arange(-2, 3), str(tmp_path), AtlasOptions(stop_after=1e-6)).to_json()
    assert not part["complete"]
    assert part["designs"] + part["skipped"] < whole["designs"] == 120
    again = atlas(load("dihedron:4"), np.arange(-2, 3), str(tmp_path)).to_json()
    assert again["complete"] and again["types"] == whole["types"]


def test_a_tetrahedron_design_is_named_from_htlinkexteriors(capsys):
    """A 12-crossing link past LinkInfo's 11, named with its table and chirality; its mirror design too."""
    code, out, err = run(capsys, "identify", "tetrahedron", "--twist", "-2,-2,-2,-2,2,2", "--json")
    assert code == 0, err
    data = json.loads(out)
    assert (data["name"], data["table"], data["status"], data["components"]) == (
        "L12n2205",
        "HTLinkExteriors",
        "identified",
        4,
    )
    mirror = identify("tetrahedron", [2, 2, 2, 2, -2, -2])  # every label negated: here the mirror image
    assert mirror.name == "L12n2205" and mirror.mirror == (not data["mirror"])


def test_solve_type_writes_its_design_for_identify(tmp_path, capsys):
    design = tmp_path / "trefoil.json"
    code, out, err = run(capsys, "solve", "dihedron:3", "--type", "m3_1", "--labels", "-1..1", "-o", design)
    assert code == 0 and "m3_1" in out, err
    code, out, err = run(capsys, "identify", design, "--json")
    assert code == 0, err
    assert json.loads(out)["chiral_name"] == "m3_1"


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["dodecahedron"], ["MAX_DESIGNS", "--stop-after"]),
        (["honeycomb:cP"], ["periodic"]),
        (["tetrahedron", "--labels", "-300..300"], ["-127..127"]),
    ],
)
def test_bad_atlas_requests_are_one_line_and_exit_2(capsys, args, words):
    code, out, err = run(capsys, "atlas", *args)
    assert code == 2 and err.count("\n") == 1 and err.startswith("lkspace: error: "), err
    for word in words:
        assert word in err


@pytest.mark.parametrize("name", ["3_1", "L2a1", "4_1"])
def test_the_screen_from_labels_never_contradicts_the_geometric_screen(name):
    # screen_batch works on diagrams from labels; screen realizes and projects each design
    from lkspace.knots.batch import Namer
    from lkspace.knots.key_names import KeyCache
    from lkspace.linktypes.screen import screen, screen_batch

    cube = load("cube")
    target = parse_type(name)
    rows = np.random.default_rng(5).integers(-1, 2, size=(200, 12))
    rows = np.array([r for r in rows if lkspace.trace(cube, r).components == target.components][:25])
    goal = Goal(target.components, target)
    with Namer(1, False, 60.0) as namer:
        fast = screen_batch(cube, rows, goal, 0, KeyCache(), namer, np.arange(-1, 2))
    for labels, verdict in zip(rows, fast, strict=True):
        slow = screen(cube, labels, goal, seed=3)
        assert {verdict.verdict, slow.verdict} != {"match", "other"}, labels.tolist()
        if verdict.reason != "determinant":  # decided before the diagram's linking numbers are read
            assert verdict.linking_matrix == slow.linking_matrix
    assert any(v.reason == "determinant" for v in fast)
