"""Messages in the user's words: plurals, hints that say what to do, no repeated or raw numbers."""

import json
import re
from functools import partial

import pytest

import lkspace
from lkspace.geometry.fabrication import gap_fixes
from lkspace.linktypes.lookup import lookup
from lkspace.linktypes.names import parse_type
from lkspace.model.specs import parse_labels
from lkspace.words import plural, rounded

from .cli_calls import run


def test_plural_and_rounded():
    assert [plural(n, "component") for n in (0, 1, 2, 1234)] == [
        "0 components", "1 component", "2 components", "1,234 components",
    ]  # fmt: skip
    assert plural(1, "component is", "components are") == "1 component is"
    assert rounded({"a": [0.041999999999999996, 2], "b": "x", "c": 1e-20 / 3}) == {
        "a": [0.042, 2], "b": "x", "c": 3.33333333333e-21,
    }  # fmt: skip


def test_trace_and_solve_count_in_words(capsys):
    code, out, _ = run(capsys, "trace", "dihedron:3", "--twist", "1")
    assert code == 0 and out.startswith("dihedron:3: 1 component, holds together"), out
    code, out, _ = run(capsys, "solve", "tetrahedron", "--components", "1")
    assert code == 0 and "— 1 design with 1 component [" in out, out
    assert "(s)" not in out


def test_info_shows_each_count_once(capsys):
    code, out, _ = run(capsys, "info", "cube")
    assert code == 0
    assert re.search(r"^ edges +12 *$", out, re.M), out
    assert "n edges" not in out and "symmetry group order" not in out
    code, out, _ = run(capsys, "info", "cube", "--json")
    assert json.loads(out)["n_edges"] == 12  # the JSON keeps its fields


@pytest.mark.parametrize(
    ("centre", "thickness", "clearance", "scale", "want"),
    [  # the gap is centre - thickness and centre grows with the scale
        (0.3, 0.1, 0.5, 1.0, ["no `thickness`", "`scale` 2 or more", "`clearance` 0.2 or less"]),
        (0.6, 0.3, 0.1, 1.0, ["`thickness` 0.5 or less", "`scale` 0.67 or more", "`clearance` 0.3 or less"]),
    ],
)
def test_gap_fixes_name_what_can_work(centre, thickness, clearance, scale, want):
    text = gap_fixes(centre, thickness, clearance, scale)
    for part in want:
        assert part in text, text


def test_clearance_refusal_names_a_fix_that_works(capsys, tmp_path):
    args = ["export", "cube", "--twist", "2", "-o", tmp_path / "c.stl", "--thickness", "0.1", "--clearance", "0.5"]
    code, _, err = run(capsys, *args)
    assert code == 1 and "no --thickness reaches clearance 0.5" in err, err
    scale = re.search(r"--scale ([0-9.]+) or more", err)
    assert scale, err
    code, out, err = run(capsys, *args, "--scale", scale[1])  # the scale it names is enough
    assert code == 0, err
    assert "6 pieces of cube" in out


def test_one_strand_has_no_distance_between_strands(capsys, tmp_path):
    code, out, err = run(capsys, "export", "dihedron:3", "--twist", "1", "-o", tmp_path / "k.obj")
    assert code == 0, err
    assert "1 strand of dihedron:3" in out and "between strands" not in out, out


def test_identify_time_limit_says_what_to_raise(capsys):
    pytest.importorskip("spherogram")
    from .test_budgets import BIG_KNOT

    code, out, _ = run(capsys, "identify", "truncated-octahedron", "--twist", BIG_KNOT, "--time-limit", "0.3")
    assert code == 0
    assert "unknown: time limit 0.3 s reached (during " in out, out
    assert "raise --time-limit (now 0.3 s; 0: no limit)" in out, out


def test_library_errors_name_parameters_and_the_cli_names_flags():
    from lkspace.cli.flags import flag, in_flags
    from lkspace.errors import UsageError

    exc = UsageError("max_designs: must be at least 1, got 0", parameter="max_designs")
    assert str(exc) == "max_designs: must be at least 1, got 0"
    assert in_flags(exc) == "--max-designs: must be at least 1, got 0"
    assert flag("label_set") == "--labels"
    assert in_flags(UsageError("no parameter here")) == "no parameter here"
    quoted = UsageError(
        "cube: `thickness` 2 folds (use a smaller `thickness` or a larger `scale`)", parameter="thickness"
    )
    assert in_flags(quoted) == "cube: --thickness 2 folds (use a smaller --thickness or a larger --scale)"
    assert (
        in_flags(UsageError("max_points: 5 > 1", parameter="max_points")) == "MAX_POINTS: 5 > 1"
    )  # no flag: the bound


def test_export_tube_bound_names_the_bound(capsys, tmp_path):
    """The point bound of tubes is refused before the block is built, naming the bound (not ``max_points``)."""
    args = ["export", "honeycomb:cP", "--twist", "1", "--block", "10x10x10", "-o", tmp_path / "b.glb"]
    code, _, err = run(capsys, *args)
    assert code == 2
    assert err.startswith("lkspace: error: MAX_TUBE_VERTICES / 12 for tubes (polylines allow more): "), err
    assert "points > 500,000" in err and err.count("\n") == 1, err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    ("call", "args", "python", "cli"),
    [
        (
            partial(lkspace.solve, "cube", 1, no_zero=True, fixes={0: 0}),
            ["solve", "cube", "-n", "1", "--no-zero", "--fix", "0=0"],
            "fixes 0-1=0 contradicts `no_zero`",
            "--fix 0-1=0 contradicts --no-zero",
        ),
        (
            partial(lkspace.solve, "cube", 1, options=lkspace.SolveOptions(distinct_up_to="mirrors")),
            ["solve", "cube", "-n", "1", "--distinct-up-to", "mirrors"],
            "distinct_up_to 'mirrors': expected rotations, isometries or none",
            None,  # click checks the choice on the command line
        ),
        (
            partial(lkspace.count_designs, "tetrahedron", "0..1", "isometries"),
            ["enumerate", "tetrahedron", "--labels", "0..1", "--symmetry", "isometries", "--count-only"],
            "symmetry='isometries' maps label t to -t under reflections, but the label set [0, 1] lacks [-1]; "
            "use a set closed under negation or `symmetry='rotations'`",
            "--symmetry isometries maps label t to -t under reflections, but the label set [0, 1] lacks [-1]; "
            "use a set closed under negation or --symmetry rotations",
        ),
        (
            partial(parse_type, "m3_1", "table"),
            ["solve", "cube", "--type", "m3_1", "--chirality", "table"],
            "type_name 'm3_1' asks for the mirror image but `chirality` is table",
            "--type 'm3_1' asks for the mirror image but --chirality is table",
        ),
        (
            partial(lookup, "hopf lnk"),
            ["lookup", "hopf lnk"],
            "name 'hopf lnk': not a knot or link name (table names like 3_1, m3_1, 5_2, L6a4, 3_1#4_1, or common "
            "names like 'trefoil', 'Borromean rings', 'Whitehead link'); did you mean 'Hopf link'?",
            "NAME 'hopf lnk': not a knot or link name (table names like 3_1, m3_1, 5_2, L6a4, 3_1#4_1, or common "
            "names like 'trefoil', 'Borromean rings', 'Whitehead link'); did you mean 'Hopf link'?",
        ),
        (
            lambda: parse_labels(lkspace.load("cube"), "1,2"),
            ["trace", "cube", "--twist", "1,2"],
            "labels '1,2': expected 12 twist labels (one per edge of cube), got 2",
            "--twist '1,2': expected 12 twist labels (one per edge of cube), got 2",
        ),
        (
            lambda: next(lkspace.designs("tetrahedron", "2", selection=lkspace.Selection(mode="spanning-trees"))),
            ["enumerate", "tetrahedron", "--labels", "2", "--mode", "spanning-trees", "-o", "-"],
            "mode='spanning-trees' needs odd labels; [2] has none",
            "--mode spanning-trees needs odd labels; [2] has none",
        ),
    ],
)
def test_errors_name_parameters_in_python_and_flags_on_the_command_line(capsys, call, args, python, cli):
    from lkspace.errors import LkspaceError

    with pytest.raises(LkspaceError) as caught:
        call()
    assert str(caught.value) == python
    assert caught.value.parameter == python.split(" ")[0].split("=")[0].split(":")[0]
    if cli is None:
        return
    code, _, err = run(capsys, *args)
    assert code != 0
    assert err.strip().splitlines()[-1] == f"lkspace: error: {cli}"


def test_parameters_in_backquotes_become_flags():
    from lkspace.cli.flags import in_flags
    from lkspace.errors import UsageError

    exc = UsageError(
        "subgroup 'C5': no rotation; use `symmetry='none'`, `weld=TOL` or `count_only=True` (not symmetry_x)",
        parameter="subgroup",
    )
    assert (
        in_flags(exc)
        == "--invariant 'C5': no rotation; use --symmetry none, --weld TOL or --count-only (not symmetry_x)"
    )
    assert in_flags(UsageError("counts: x", parameter="count")) == "counts: x"  # a word, not a prefix
    assert in_flags(UsageError("pathological.parquet: x", parameter="path")) == "pathological.parquet: x"


def _user_strings():
    """Every string constant in lkspace's code (f-string parts included, docstrings left out), with where it is."""
    import ast
    import pathlib

    root = pathlib.Path(lkspace.__file__).parent
    for path in sorted(root.rglob("*.py")):
        tree = ast.parse(path.read_text(), str(path))
        docs = {id(n.value) for n in ast.walk(tree) if isinstance(n, ast.Expr) and isinstance(n.value, ast.Constant)}
        for node in ast.walk(tree):
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docs:
                yield f"{path.relative_to(root)}:{node.lineno}", node.value


def test_no_word_is_pluralized_with_s_in_brackets():
    """``solution(s)``, ``design(s)``: every count says ``1 design`` or ``2 designs`` (words.plural, words.noun)."""
    bad = [(where, text) for where, text in _user_strings() if re.search(r"[a-z]\(s\)", text)]
    assert bad == []


def test_results_count_in_words():
    result = lkspace.solve("tetrahedron", 3)
    assert re.fullmatch(r"SolveResult\(feasible, 1 solution by fast-path in \S+s\)", repr(result)), repr(result)
    assert lkspace.words.noun(1, "key") == "key" and lkspace.words.noun(0.5, "turn") == "turns"


def test_unknown_keys_are_named_with_the_keys_there_are(tmp_path):
    path = tmp_path / "bad.json"
    path.write_text(json.dumps({"vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "faces": [[0, 1, 2]], "colour": 1}))
    with pytest.raises(lkspace.ScaffoldError, match=r"unknown key 'colour'; the keys are comment, edges, faces") as e:
        lkspace.load(str(path))
    assert "(s)" not in str(e.value)


def test_a_misspelt_builtin_name_gets_a_suggestion(capsys):
    with pytest.raises(lkspace.ScaffoldError, match=r"did you mean 'cube'"):
        lkspace.load("cubee")
    code, _, err = run(capsys, "info", "zzz")
    assert code == 2 and "the built-in names are tetrahedron, cube," in err and "--help" not in err, err


def test_periodic_identify_names_the_block_parameter_in_python_and_the_flag_on_the_command_line(capsys):
    with pytest.raises(lkspace.LkspaceError) as e:
        lkspace.identify("honeycomb:cP", [1, 1, 1])
    assert "`block`" in str(e.value) and "--" not in str(e.value), str(e.value)
    code, _, err = run(capsys, "identify", "honeycomb:cP", "--twist", "1")
    assert code == 2 and "export one with --block" in err, err


def test_library_messages_name_no_command_line_flag():
    """A Python caller never reads ``--flag``: library layers name parameters (in backquotes), cli/ maps them."""
    programs = ("cli/", "studio/", "blender/", "__main__.py")
    bad = [
        (where, text)
        for where, text in _user_strings()
        if not where.startswith(programs)
        and re.search(r"(?<![\w`-])--[a-z]", text)
        and not (where.startswith("linktypes/lookup.py") and ("lkspace " in text or text == " --twist "))
        and not (
            where.startswith("linktypes/ideal_shapes.py")
            and (text.startswith("lkspace export ") or text in (" --twist ", " --relax"))
        )
    ]  # lookup's answers hold pasteable commands: each design's, `lkspace solve` (its type search has no Python
    # API) and the export that draws a knot's ideal shape
    assert bad == []
