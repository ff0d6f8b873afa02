"""The docs stay true: every ``console`` example in README.md and docs/*.md runs as written.

Each ```` ```console ```` block is a list of ``$ command`` lines, each followed by the output it
prints (stdout and stderr together, as on a terminal).  The block runs in a fresh temporary
folder through ``bash`` with the installed ``lkspace`` first on ``PATH``; its commands run in
order, so a later one reads what an earlier one wrote, and ``echo $?`` shows the status of the
command before it.  Markers for what varies:

- a line ``...`` alone stands for any number of lines (none included);
- ``[...]`` inside a line stands for any text on that line (timings, paths, long JSON);
- a command with no output lines below it must succeed; what it prints is not compared;
- progress lines are off (``LKSPACE_PROGRESS=0``): they depend on the machine's speed.

HTML comments on the lines before a block's fence steer it:

- ``<!-- console: skip (why) -->``: not run (a network, a long run, a Blender install, …);
  the reason shows in the test report;
- ``<!-- console: setup: COMMAND -->``: a shell command run first in the block's folder
  (files the example reads); several may follow one another.

A file the reader is shown is the file the example reads: ``<!-- console: file NAME -->``
on the line before any other fenced block (```` ```text ````, ```` ```json ````, …) writes
that block's text to ``NAME`` in the folder of every later console block of the same page
whose commands name it.

A block that is the start of another (same files, same setup, the same first commands and outputs)
is skipped with that reason: the other block runs the same commands in the same order.
"""

import os
import pathlib
import re
import shutil
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
BLOCK = re.compile(r"((?:[ ]*<!-- console: [^\n]*-->\n)*)([ ]*)```console\n(.*?)```", re.S)
SKIP = re.compile(r"<!-- console: skip \((.*?)\) -->")
SETUP = re.compile(r"<!-- console: setup: (.*?) -->")
FILE = re.compile(r"<!-- console: file (\S+) -->\n([ ]*)```[^\n]*\n(.*?)```", re.S)
SEPARATOR = "@@console-example@@"
STATUS = "@@console-status@@"


def _unindent(text, indent):
    return "\n".join(line.removeprefix(indent) for line in text.split("\n"))


def _blocks():
    """One pytest param per console block: (files, setup commands, body).

    A block whose files, setup and commands with their output are the first commands of another
    block's (README's copies of docs/ examples) is skipped: that block runs them, in the same order.
    """
    blocks = list(_page_blocks())
    for i, block in enumerate(blocks):
        files, setup, body = block.values
        mine = _commands(body)
        for j, other in enumerate(blocks):
            theirs = _commands(other.values[2])
            longer = len(theirs) > len(mine) or (len(theirs) == len(mine) and j < i)
            if (
                j != i
                and not block.marks
                and not other.marks
                and (other.values[0], other.values[1]) == (files, setup)
                and longer
            ):
                if theirs[: len(mine)] == mine:
                    reason = f"its commands are the first {len(mine)} of {other.id}, which runs them"
                    block = pytest.param(*block.values, marks=[pytest.mark.skip(reason=reason)], id=block.id)
                    break
        yield block


def _page_blocks():
    for page in PAGES:
        text = page.read_text()
        shown = [(m.start(), m[1], _unindent(m[3], m[2])) for m in FILE.finditer(text)]
        for i, match in enumerate(BLOCK.finditer(text)):
            comments, body = match[1], _unindent(match[3], match[2])
            commands = " ".join(c for c, _ in _commands(body))
            files = {name: content for at, name, content in shown if at < match.start() and name in commands}
            skip = SKIP.search(comments)
            marks = [pytest.mark.skip(reason=skip[1])] if skip else []
            yield pytest.param(files, SETUP.findall(comments), body, marks=marks, id=f"{page.name}[{i}]")


def _commands(body):
    """The ``(command, expected output lines)`` pairs of a block's text."""
    pairs: list[tuple[str, list[str]]] = []
    for line in body.splitlines():
        if line.startswith("$ "):
            pairs.append((line[2:], []))
        elif pairs:
            pairs[-1][1].append(line.rstrip())
    return pairs


def _pattern(expected):
    """A regex for the whole output: ``...`` lines are any lines, ``[...]`` is any text."""
    parts = []
    for line in expected:
        if line.strip() == "...":
            parts.append(r"(?:[^\n]*\n)*?")
        else:
            text = r"[^\n]*?".join(re.escape(p) for p in line.split("[...]"))
            parts.append(text + r"\n")
    return re.compile("".join(parts))


def _run(setup, commands, folder):
    """Run the block in ``folder``; return ``(output, exit status)`` of each command."""
    lines = ["exec 2>&1", *setup, "__status=0"]
    for command, _ in commands:  # ``(exit $__status)``: ``echo $?`` shows the command before
        lines += [f"echo {SEPARATOR}", "(exit $__status)", command, "__status=$?", f"echo {STATUS} $__status"]
    env = {
        **os.environ,
        "PATH": f"{pathlib.Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}",
        "COLUMNS": "100",
        "PYTHONUNBUFFERED": "1",
        "NO_COLOR": "1",
        "LKSPACE_PROGRESS": "0",
    }
    done = subprocess.run(
        ["bash", "-c", "\n".join(lines)],
        cwd=folder,
        env=env,
        capture_output=True,
        text=True,
        check=False,
        timeout=300,  # a hung example (a server, a prompt) fails instead of stalling the suite
    )
    results = []
    for chunk in done.stdout.split(SEPARATOR + "\n")[1:]:
        text, _, status = chunk.rpartition(STATUS + " ")
        output = "\n".join(line.rstrip() for line in text.rstrip("\n").split("\n"))
        results.append((output + "\n" if output else "", int(status)))
    return results


@pytest.mark.parametrize(("files", "setup", "body"), list(_blocks()))
def test_console_example(files, setup, body, tmp_path):
    for name, content in files.items():
        (tmp_path / name).write_text(content)
    commands = _commands(body)
    assert commands, "a console block without a $ command"
    if any(re.search(r"\|\s*jq\b", c) for c, _ in commands) and shutil.which("jq") is None:
        pytest.skip("the example pipes into jq, which is not installed")
    results = _run(setup, commands, tmp_path)
    assert len(results) == len(commands), results
    for (command, expected), (output, status) in zip(commands, results, strict=True):
        if not expected:
            assert status == 0, f"$ {command}\nexit {status}:\n{output}"
        else:
            assert _pattern(expected).fullmatch(output), (
                f"$ {command}\n--- documented:\n" + "\n".join(expected) + f"\n--- printed:\n{output}"
            )
