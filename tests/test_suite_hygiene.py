"""Assertions that can fail: a mechanical review of every test file (and of the package's asserts).

Each pattern below once made a test check less than it seemed to:

* ``assert x == y if t else k`` is ``assert (x == y) if t else k``: when ``t`` is falsy it
  asserts only ``k`` (a non-zero number passes);
* ``assert a and b or c`` passes on ``c`` alone, whatever ``a`` and ``b``;
* ``assert (x, "message")`` and ``assert "text"`` are always true.

Ruff covers the neighbours (``F631`` assert on a tuple, ``B011``, ``B015`` a comparison
whose result is unused, ``PLW0129`` assert on a string, ``PLR0133``, ``PT015``, ``PT017``;
see ``pyproject.toml``).  A test must also check something: an ``assert``, a
``pytest.raises``/``warns``, or a call to a helper of the suite that asserts.
"""

from __future__ import annotations

import ast
import pathlib

TESTS = pathlib.Path(__file__).parent
CHECKS = ("raises", "warns", "fail", "importorskip")
"""Calls (``pytest.X``) that check something by themselves."""


def suite_files() -> dict[str, ast.Module]:
    return {p.name: ast.parse(p.read_text(), str(p)) for p in sorted(TESTS.glob("*.py"))}


def mixed_bool(node: ast.expr) -> bool:
    """Whether ``node`` is an ``and`` inside an ``or`` (or the reverse) with no parentheses to say which binds."""
    if not isinstance(node, ast.BoolOp):
        return False
    return any(isinstance(v, ast.BoolOp) and type(v.op) is not type(node.op) for v in node.values)


def weak_asserts(tree: ast.Module, source: str) -> list[str]:
    """Asserts in ``tree`` that check less than they read."""
    found = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Assert):
            continue
        test = node.test
        what = None
        if isinstance(test, ast.IfExp):
            what = "a conditional expression (`a == b if c else d` asserts only d when c is falsy)"
        elif mixed_bool(test) and not parenthesized(test, source):
            what = "and/or mixed without parentheses (`a and b or c` passes on c alone)"
        elif isinstance(test, ast.Tuple):
            what = "a tuple (always true)"
        elif isinstance(test, ast.Constant) and test.value:
            what = "a true constant"
        if what:
            found.append(f"line {node.lineno}: assert on {what}")
    return found


def parenthesized(node: ast.BoolOp, source: str) -> bool:
    """Whether every inner and/or of ``node`` is written in parentheses."""
    lines = source.splitlines()
    for v in node.values:
        if isinstance(v, ast.BoolOp) and type(v.op) is not type(node.op):
            before = lines[v.lineno - 1][: v.col_offset].rstrip()
            if not before.endswith("("):
                return False
    return True


def calls(func: ast.FunctionDef) -> set[str]:
    """Names ``func`` calls, with ``assert`` for an assert statement."""
    names = set()
    for node in ast.walk(func):
        if isinstance(node, ast.Assert):
            names.add("assert")
        elif isinstance(node, ast.Call):
            names.add(node.func.attr if isinstance(node.func, ast.Attribute) else getattr(node.func, "id", ""))
    return names


def checks(func: ast.FunctionDef, helpers: set[str]) -> bool:
    """Whether ``func`` asserts, expects an error or calls a helper that does."""
    return bool(calls(func) & {"assert", *CHECKS, *helpers})


def asserting_helpers(trees: dict[str, ast.Module]) -> set[str]:
    """Names of the suite's functions that check something, directly or through another (a fixed point)."""
    called: dict[str, set[str]] = {}
    for node in (n for t in trees.values() for n in ast.walk(t) if isinstance(n, ast.FunctionDef)):
        called.setdefault(node.name, set()).update(calls(node))  # a name defined twice: either may be meant
    helpers: set[str] = set()
    while more := {
        name for name, names in called.items() if name not in helpers and names & {"assert", *CHECKS, *helpers}
    }:
        helpers |= more
    return helpers


def test_no_assert_checks_less_than_it_reads():
    """In the tests, and in the package and the experiments too (their asserts state invariants)."""
    root = TESTS.parent
    paths = [*TESTS.glob("*.py"), *(root / "lkspace").rglob("*.py"), *(root / "experiments").glob("*.py")]
    found = {}
    for path in paths:
        source = path.read_text()
        if bad := weak_asserts(ast.parse(source, str(path)), source):
            found[str(path.relative_to(root))] = bad
    assert found == {}


def test_every_test_checks_something():
    trees = suite_files()
    helpers = asserting_helpers(trees)
    empty = [
        f"{name}:{node.lineno} {node.name}"
        for name, tree in trees.items()
        for node in tree.body
        if isinstance(node, ast.FunctionDef) and node.name.startswith("test_") and not checks(node, helpers)
    ]
    assert empty == []


def test_the_review_catches_each_pattern():
    """The patterns above, written out, are each caught (the check itself can fail)."""
    source = (
        "def test_a(t):\n    assert f(t) == g(t) if t else 3\n"
        "def test_b():\n    assert x and y or z\n"
        "def test_c():\n    assert (x == 1, 'message')\n"
        "def test_d():\n    assert 'always'\n"
        "def test_e():\n    assert x or (y and z)\n"
        "def test_f():\n    x == 1\n"
    )
    tree = ast.parse(source)
    assert weak_asserts(tree, source) == [
        "line 2: assert on a conditional expression (`a == b if c else d` asserts only d when c is falsy)",
        "line 4: assert on and/or mixed without parentheses (`a and b or c` passes on c alone)",
        "line 6: assert on a tuple (always true)",
        "line 8: assert on a true constant",
    ]
    funcs = [n for n in tree.body if isinstance(n, ast.FunctionDef)]
    assert [f.name for f in funcs if not checks(f, set())] == ["test_f"]
