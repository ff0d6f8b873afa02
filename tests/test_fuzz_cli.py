"""Fuzzing the command line with bad input: never a traceback, a hang, or a silent success.

Generated bad OBJ files, scaffold files, twist files and option values (``tests/strategies.py``)
go through the real CLI in-process (``lkspace.cli.main``).  Every case must end with exit
status 1 (bad data in a file) or 2 (bad usage), exactly one ``lkspace: error:`` line on
stderr, under ``--json`` one ``{"error": ...}`` object on stdout, and no new file in the
output folder (not even a temporary one).  A case that runs past ``CASE_SECONDS`` is a hang.

``LKSPACE_FUZZ_CENSUS=FILE`` records every case's outcome in FILE (one JSON line each)
instead of failing, to count tracebacks, hangs and silent successes of a version; with
``LKSPACE_FUZZ_ISOLATE=1`` too, each case runs in its own process (an old version may
block in C code, where the alarm cannot stop it, or die of a signal).
"""

from __future__ import annotations

import json
import os
import signal
import tempfile

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from lkspace.cli import main

from .strategies import (
    BAD_LABEL_SETS,
    BAD_NAMES,
    BAD_NULLS,
    BAD_TWISTS,
    bad_obj_files,
    bad_scaffold_json,
    bad_twist_files,
    malformed_lists,
)

CASE_SECONDS = 20
CENSUS = os.environ.get("LKSPACE_FUZZ_CENSUS")
ISOLATE = bool(CENSUS and os.environ.get("LKSPACE_FUZZ_ISOLATE"))  # census only: every case in its own process
if CENSUS:  # an old version may try to build a huge scaffold: fail its allocation instead of the machine
    import resource

    resource.setrlimit(resource.RLIMIT_AS, (8 << 30, 8 << 30))


def fuzz(n: int) -> settings:
    """Hypothesis settings of one fuzz test: ``n`` derandomized examples, no database, no deadline."""
    return settings(
        max_examples=n,
        database=None,
        derandomize=True,
        deadline=None,
        suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow, HealthCheck.filter_too_much],
    )


class Hang(BaseException):
    """Raised by the alarm in a case that runs too long (a BaseException: nothing may swallow it)."""


def _alarm(_signum: int, _frame: object) -> None:
    raise Hang


def outcome(code: int | None, out: str, err: str, before: set[str], after: set[str], as_json: bool) -> str:
    """Classify one run: ``"ok"`` or what went wrong."""
    if code is None:
        return "hang"
    if code == 70 or "Traceback" in err:
        return "traceback"
    if code == 0:
        return "silent success"
    lines = err.splitlines()
    if code not in (1, 2) or [ln.startswith("lkspace: error:") for ln in lines].count(True) != 1:
        return f"exit {code}, stderr {err!r}"
    if any(not ln.startswith("lkspace: ") for ln in lines):
        return f"stray stderr {err!r}"
    if as_json:
        try:
            error = json.loads(out)["error"]
            assert error["exit_code"] == code and error["message"] and error["type"]
        except (ValueError, KeyError, TypeError, AssertionError):
            return f"no JSON error object on stdout: {out[:200]!r}"
    if after != before:
        return f"files left behind: {sorted(after - before)}"
    return "ok"


def run_in_process(capsys: pytest.CaptureFixture[str], args: list[str]) -> tuple[int | None, str, str]:
    """Run ``lkspace args`` in this process; exit status ``None`` for a hang."""
    old = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(CASE_SECONDS)
    code: int | None
    try:
        code = main(args)
    except Hang:
        code = None
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    out, err = capsys.readouterr()
    return code, out, err


def run_isolated(args: list[str]) -> tuple[int | None, str, str]:
    """Run ``python -m lkspace args`` in a child process (census of old versions that block in C code)."""
    import subprocess
    import sys

    try:
        proc = subprocess.run(
            [sys.executable, "-m", "lkspace", *args], capture_output=True, text=True, timeout=CASE_SECONDS
        )
    except subprocess.TimeoutExpired:
        return None, "", ""
    code = 70 if proc.returncode < 0 else proc.returncode  # killed by a signal: a crash
    return code, proc.stdout, proc.stderr


def check(capsys: pytest.CaptureFixture[str], folder: str, argv: list[str], codes: tuple[int, ...] = (1, 2)) -> None:
    """Run ``lkspace argv`` (twice: plain and ``--json``) and check it fails cleanly with one of ``codes``."""
    for as_json in (False, True):
        args = argv + (["--json"] if as_json else [])
        before = set(os.listdir(folder))
        capsys.readouterr()
        if ISOLATE:
            code, out, err = run_isolated(args)
        else:
            code, out, err = run_in_process(capsys, args)
        result = outcome(code, out, err, before, set(os.listdir(folder)), as_json)
        if result == "ok" and code not in codes:
            result = f"exit {code}, expected {codes}: {err.strip()}"
        if CENSUS:
            with open(CENSUS, "a") as fh:
                fh.write(json.dumps({"argv": [a[:80] for a in args], "outcome": result}) + "\n")
            continue
        assert result == "ok", f"lkspace {' '.join(a[:60] for a in args)}: {result}"


def _file(folder: str, name: str, data: bytes) -> str:
    path = os.path.join(folder, name)
    with open(path, "wb") as fh:
        fh.write(data)
    return path


MESH_COMMANDS = [
    ["info"],
    ["trace", "--twist", "1"],
    ["scaffold", "-o", "OUT.json"],
]


@fuzz(150)
@given(data=bad_obj_files(), command=st.sampled_from(MESH_COMMANDS), weld=st.booleans())
def test_bad_obj_files(capsys, data, command, weld):
    with tempfile.TemporaryDirectory() as folder:
        mesh = _file(folder, "m.obj", data)
        argv = [command[0], mesh, *[os.path.join(folder, a) if a == "OUT.json" else a for a in command[1:]]]
        check(capsys, folder, argv + (["--weld"] if weld else []), codes=(1,))


@fuzz(200)
@given(data=bad_scaffold_json(), command=st.sampled_from(MESH_COMMANDS))
def test_bad_scaffold_files(capsys, data, command):
    with tempfile.TemporaryDirectory() as folder:
        mesh = _file(folder, "m.json", data)
        argv = [command[0], mesh, *[os.path.join(folder, a) if a == "OUT.json" else a for a in command[1:]]]
        check(capsys, folder, argv, codes=(1,))


@fuzz(100)
@given(twist=bad_twist_files())
def test_bad_twist_files(capsys, twist):
    ext, data = twist
    with tempfile.TemporaryDirectory() as folder:
        check(capsys, folder, ["trace", "cube", "--twist", _file(folder, f"t{ext}", data)], codes=(1,))


@fuzz(80)
@given(spec=BAD_TWISTS)
def test_bad_twist_options(capsys, spec):
    with tempfile.TemporaryDirectory() as folder:
        check(capsys, folder, ["trace", "cube", f"--twist={spec}"], codes=(2,))


@fuzz(20)
@given(spec=BAD_NULLS)
def test_bad_null_options(capsys, spec):
    with tempfile.TemporaryDirectory() as folder:
        check(capsys, folder, ["trace", "cube", "--twist", "1", f"--null={spec}"], codes=(2,))


@fuzz(80)
@given(name=BAD_NAMES, command=st.sampled_from(MESH_COMMANDS))
def test_bad_builtin_names(capsys, name, command):
    with tempfile.TemporaryDirectory() as folder:
        argv = [command[0], name, *[os.path.join(folder, a) if a == "OUT.json" else a for a in command[1:]]]
        check(capsys, folder, argv, codes=(2,))


@fuzz(10)
@given(tol=st.sampled_from(["x", "-1", "nan", "inf", "1e999", "", "1,5"]))
def test_bad_weld_tolerance(capsys, tol):
    with tempfile.TemporaryDirectory() as folder:
        mesh = _file(folder, "m.obj", ("\n".join(["v 0 0 0", "v 1 0 0", "v 0 1 0", "f 1 2 3"]) + "\n").encode())
        check(capsys, folder, ["info", mesh, f"--weld={tol}"], codes=(2,))


# ---- commands owned elsewhere: argument fuzzing only ----------------------------------------

OTHER_COMMANDS = {
    "enumerate": lambda folder: ["enumerate", "cube", "-o", os.path.join(folder, "c.parquet")],
    "solve": lambda folder: ["solve", "cube", "--components", "1"],
    "export": lambda folder: ["export", "cube", "--twist", "1", "-o", os.path.join(folder, "s.obj")],
    "identify": lambda folder: ["identify", "cube", "--twist", "1"],
}


@pytest.mark.parametrize("command", ["enumerate", "solve"])
@fuzz(20)
@given(spec=BAD_LABEL_SETS)
def test_bad_label_sets(capsys, command, spec):
    with tempfile.TemporaryDirectory() as folder:
        check(capsys, folder, [*OTHER_COMMANDS[command](folder), f"--labels={spec}"], codes=(2,))


@pytest.mark.parametrize("command", ["export", "identify"])
@fuzz(25)
@given(spec=BAD_TWISTS)
def test_bad_twists_elsewhere(capsys, command, spec):
    with tempfile.TemporaryDirectory() as folder:
        argv = [a if a != "1" else spec for a in OTHER_COMMANDS[command](folder)]
        check(capsys, folder, [a if not a.startswith("--twist") else a for a in argv], codes=(2,))


@pytest.mark.parametrize("command", list(OTHER_COMMANDS))
@fuzz(20)
@given(name=BAD_NAMES)
def test_bad_names_elsewhere(capsys, command, name):
    with tempfile.TemporaryDirectory() as folder:
        argv = OTHER_COMMANDS[command](folder)
        check(capsys, folder, [argv[0], name, *argv[2:]], codes=(2,))


@pytest.mark.parametrize(
    "argv, codes",
    [
        (["export", "book:3", "--twist", str(2**62), "-o", "{folder}/s.obj"], (1,)),  # geometry: strands too close
        (["identify", "book:3", "--twist", str(2**62)], (2,)),
        (["solve", "cube", "--components", "1", "--fix", "0=" + "9" * 30], (2,)),
        (["solve", "cube", "--components", "1", "--fix", f"0={2**62 + 1}"], (2,)),
        (["enumerate", "cube", "--labels", f"0..{2**62}", "--count-only"], (2,)),
        (["enumerate", "cube", "--labels", "100..200", "--count-only"], (2,)),
    ],
)
def test_labels_at_the_bound_elsewhere(capsys, argv, codes):
    """Labels within (or just past) the bound that other commands must refuse cleanly, as usage."""
    with tempfile.TemporaryDirectory() as folder:
        check(capsys, folder, [a.format(folder=folder) for a in argv], codes=codes)


@pytest.mark.parametrize("option", ["--labels", "--twist"])
@fuzz(30)
@given(data=st.data())
def test_a_list_with_an_empty_item_or_non_ascii_digits_is_refused(capsys, option, data):
    """``--labels 1,,2`` was the label set [1, 2] and ``--twist`` of Arabic-Indic or full-width digits read as
    integers; a malformed item is now refused, naming it."""
    spec = data.draw(malformed_lists(12 if option == "--twist" else 3), label="spec")
    with tempfile.TemporaryDirectory() as folder:
        argv = (
            ["trace", "cube", f"--twist={spec}"] if option == "--twist" else ["enumerate", "cube", f"--labels={spec}"]
        )
        check(capsys, folder, [*argv, "--count-only"] if option == "--labels" else argv, codes=(2,))


NUMBER_FLAGS = [
    (["enumerate", "cube", "--labels", "-1..1", "--count-only", "--max-designs"], "1"),
    (["enumerate", "cube", "--labels", "-1..1", "--count-only", "--components"], "1"),
    (["export", "cube", "--twist", "1", "-o", "{folder}/x.obj", "--tube-radius"], "0.25"),
    (["export", "cube", "--twist", "4", "-o", "{folder}/x.oxdna", "--nm-per-unit"], "6"),
    (["identify", "cube", "--twist", "1", "--time-limit"], "5"),
    (["surfaces", "cube", "--per-edge"], "2"),
]


@pytest.mark.parametrize(("argv", "good"), NUMBER_FLAGS, ids=[a[-1] for a, _ in NUMBER_FLAGS])
@fuzz(10)
@given(data=st.data())
def test_a_number_flag_spelled_with_other_digits_or_separators_is_refused(capsys, argv, good, data):
    """``--max-designs ١`` ran as 1 and ``--tube-radius 1_000`` as 1000 (Python's int and float read them): a
    number flag now takes ASCII digits only, as the label lists do."""
    digits = data.draw(
        st.sampled_from(["\u0661", "\uff11", "\u00b9", "\u09e7"]), label="digit"
    )  # a 1 of another script
    spelled = data.draw(st.sampled_from([good.replace("1", digits) if "1" in good else digits + good,
                                         good[0] + "_" + good[1:] if len(good) > 1 else good + "_0",
                                         digits]), label="spelled")  # fmt: skip
    with tempfile.TemporaryDirectory() as folder:
        check(capsys, folder, [a.format(folder=folder) for a in argv] + [spelled], codes=(2,))
