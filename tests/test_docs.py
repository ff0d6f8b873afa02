"""The docs stay true: every ``>>>`` example in docs/*.md and the README runs as a doctest.

Examples start with ``lkspace`` and ``np`` imported.  A page makes the files its examples
read with ``<!-- run: lkspace ... -->`` comments (run through the real CLI first); a block
that needs what no page makes is marked ``<!-- not tested -->`` on the line before its fence.
"""

import doctest
import pathlib
import re
import shlex

import numpy as np
import pytest

import lkspace
from lkspace.cli import main

ROOT = pathlib.Path(__file__).resolve().parents[1]
PAGES = sorted((ROOT / "docs").glob("*.md")) + [ROOT / "README.md"]
FENCE = re.compile(r"(<!-- not tested -->\n)?```(?:python|pycon)\n(.*?)```", re.S)
RUN = re.compile(r"<!-- run: lkspace (.*?) -->")


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_examples_run(page, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    text = page.read_text()
    for command in RUN.findall(text):
        assert main(shlex.split(command)) == 0, command
    capsys.readouterr()
    blocks = [m[2] for m in FENCE.finditer(text) if not m[1] and ">>>" in m[2]]
    parser, runner = (
        doctest.DocTestParser(),
        doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE),
    )
    namespace: dict = {"lkspace": lkspace, "np": np}
    for i, block in enumerate(blocks):
        test = parser.get_doctest(block, namespace, f"{page.name}[{i}]", str(page), 0)
        runner.run(test, clear_globs=False)
        namespace.update(test.globs)  # DocTest copies its globals: carry names to the next block
    assert runner.failures == 0, f"{runner.failures} failing example(s) in {page.name}; run pytest -s to see them"
