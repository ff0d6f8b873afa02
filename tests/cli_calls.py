"""Calling the command line in-process from tests: its exit status, stdout and stderr."""

from __future__ import annotations

import re

from lkspace.cli import main


def run(capsys, *args):
    """Run ``lkspace ARGS`` (each argument as text) in this process; return ``(code, out, err)``."""
    code = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


PROGRESS = re.compile(r"lkspace: (?!error:)[^\n]*\(\d+ s\)\n")
"""A progress line (``lkspace: STEP: ... (N s)``): a slow machine prints some before a refusal."""


def one_line_error(err: str, *words: str) -> None:
    """Assert that ``err`` is one ``lkspace: error:`` line holding every word of ``words`` (progress lines aside)."""
    err = PROGRESS.sub("", err)
    assert err.count("\n") == 1 and err.startswith("lkspace: error: "), err
    for word in words:
        assert word in err, err
