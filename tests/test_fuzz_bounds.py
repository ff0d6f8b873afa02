"""Hostile sizes through the real command line: every bound checked first, no hang, no traceback.

Each class of input that once crashed or hung lkspace has a generator in
``tests/strategies.py``: huge polygons, unused vertices, oversized built-in parameters
and supercells, design spaces past the count bound, extreme floats for every numeric
option, broken mathtext titles, and stdout on a full disk.  Every case runs
``python -m lkspace`` as a child process and must end with an exit status in the
documented set (0 success, 1 bad data, 2 bad usage), exactly one ``lkspace: error:``
line on stderr when it fails, and no traceback, within ``CASE_SECONDS``: a hang
detector generous enough for a loaded machine, not a performance assertion.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from .strategies import (
    EXTREME_FLOATS,
    LENGTH_OPTIONS,
    mathtext_titles,
    oversized_families,
    oversized_supercells,
    polygon_obj,
    strip_obj,
    unused_vertices_obj,
)

CASE_SECONDS = 60
ENV = {**os.environ, "LKSPACE_PROGRESS": "0"}


def examples(n: int) -> settings:
    """Hypothesis settings: ``n`` derandomized examples, no database, no deadline (each runs a process)."""
    return settings(
        max_examples=n,
        database=None,
        derandomize=True,
        deadline=None,
        suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
    )


def lkspace(folder: str, *args: str, stdout: int | None = None) -> tuple[int, str]:
    """Run ``python -m lkspace ARGS`` in ``folder``; return ``(exit status, stderr)`` (a hang fails the test)."""
    try:
        proc = subprocess.run(
            [sys.executable, "-m", "lkspace", *args],
            cwd=folder,
            env=ENV,
            stdout=subprocess.DEVNULL if stdout is None else stdout,
            stderr=subprocess.PIPE,
            text=True,
            timeout=CASE_SECONDS,
        )
    except subprocess.TimeoutExpired:
        pytest.fail(f"lkspace {' '.join(a[:40] for a in args)}: no answer in {CASE_SECONDS} s (a hang)")
    return proc.returncode, proc.stderr


def check(folder: str, args: list[str], codes: tuple[int, ...], stdout: int | None = None) -> int:
    """Run lkspace and check the outcome: an exit status in ``codes``, one error line on failure."""
    code, err = lkspace(folder, *args, stdout=stdout)
    where = f"lkspace {' '.join(a[:40] for a in args)}"
    assert "Traceback" not in err, f"{where}: {err[-2000:]}"
    assert code in codes, f"{where}: exit {code}, expected {codes}: {err[-500:]}"
    if code != 0:
        lines = err.splitlines()
        assert len(lines) == 1 and lines[0].startswith("lkspace: error: "), f"{where}: stderr {err[-1000:]!r}"
    return code


def write(folder: str, name: str, data: bytes) -> str:
    path = os.path.join(folder, name)
    with open(path, "wb") as fh:
        fh.write(data)
    return path


# ---- titles -------------------------------------------------------------------------------


@examples(60)
@given(title=mathtext_titles())
def test_title_check_agrees_with_matplotlib(title):
    """check_title refuses exactly the titles matplotlib cannot draw (drawing is the independent judge)."""
    pytest.importorskip("matplotlib")
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    from lkspace.errors import UsageError
    from lkspace.formats.render import check_title

    fig = Figure(figsize=(2, 1))
    FigureCanvasAgg(fig)
    fig.suptitle(title)
    try:
        fig.canvas.draw()
        drawable = True
    except ValueError:
        drawable = False
    try:
        check_title(title)
        accepted = True
    except UsageError:
        accepted = False
    assert accepted == drawable, f"title {title!r}: check_title accepted={accepted}, matplotlib drew={drawable}"


@pytest.mark.parametrize("ext", [".svg", ".png"])
def test_broken_title_is_a_usage_error(tmp_path, ext):
    pytest.importorskip("matplotlib")
    check(str(tmp_path), ["export", "cube", "--twist", "1", "--title", "$\\frac{$", "-o", f"t{ext}"], (2,))
    assert os.listdir(tmp_path) == []


# ---- stdout on a full disk ----------------------------------------------------------------


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full")
@pytest.mark.parametrize(
    "args",
    [["trace", "cube", "--twist", "1", "--json"], ["info", "dodecahedron", "--edges"], ["info", "cube", "--json"]],
)
def test_stdout_on_a_full_disk(tmp_path, args):
    """Writing the answer to a full disk (stdout is /dev/full) is one error line and exit 1."""
    with open("/dev/full", "w") as full:
        check(str(tmp_path), args, (1,), stdout=full.fileno())


# ---- built-in parameters past their bounds ------------------------------------------------


@examples(2)
@given(name=st.one_of(oversized_supercells(), oversized_families()))
def test_oversized_builtins_are_usage_errors(tmp_path_factory, name):
    check(str(tmp_path_factory.mktemp("b")), ["info", name], (2,))


# ---- design spaces past the count bound ---------------------------------------------------


@examples(1)
@given(labels=st.sampled_from([("-2..2", 5), ("0,1", 2), ("-127..127", 255)]), extra=st.integers(0, 100_000))
def test_space_past_the_count_bound_is_refused(tmp_path_factory, labels, extra):
    """|SET|^edges past 10^4000 is refused up front (exit 2), never counted nor written out in digits."""
    spec, n_labels = labels
    n_quads = math.ceil(4000 / math.log10(n_labels) / 3) + extra  # a strip of n quads has 3 n + 1 edges
    assert (3 * n_quads + 1) * math.log10(n_labels) > 4000
    folder = str(tmp_path_factory.mktemp("s"))
    mesh = write(folder, "strip.obj", strip_obj(n_quads))
    check(folder, ["enumerate", mesh, f"--labels={spec}", "--count-only", "--json"], (2,))


def test_space_just_under_the_count_bound_is_counted_exactly(tmp_path):
    """5^5701 assignments (3,985 digits): counted, and the JSON holds the exact integers."""
    import json

    mesh = write(str(tmp_path), "strip.obj", strip_obj(1900))
    proc = subprocess.run(
        [sys.executable, "-m", "lkspace", "enumerate", mesh, "--symmetry", "none", "--count-only", "--json"],
        env=ENV,
        capture_output=True,
        text=True,
        timeout=CASE_SECONDS,
    )
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert data["assignments"] == 5**5701 and data["designs"] == 5**5701  # no symmetry: every assignment


# ---- extreme floats -----------------------------------------------------------------------


def float_case(option: str, value: str) -> list[str]:
    """An export of the cube with ``option value`` (to .stl for the printing options, else .obj)."""
    out = "x.stl" if option in ("--thickness", "--clearance", "--scale") else "x.obj"
    return ["export", "cube", "--twist", "1", option, value, "-o", out]


@examples(5)
@given(option=st.sampled_from(LENGTH_OPTIONS), value=st.sampled_from(EXTREME_FLOATS))
def test_extreme_floats(tmp_path_factory, option, value):
    check(str(tmp_path_factory.mktemp("f")), float_case(option, value), (0, 1, 2))


@pytest.mark.slow
@pytest.mark.parametrize("option", LENGTH_OPTIONS)
@pytest.mark.parametrize("value", EXTREME_FLOATS)
def test_extreme_floats_all(tmp_path, option, value):
    check(str(tmp_path), float_case(option, value), (0, 1, 2))


@pytest.mark.slow
@pytest.mark.parametrize("value", ["5e-324", "1e-300", "1e300"])
def test_tiny_tubes_in_pictures(tmp_path, value):
    pytest.importorskip("matplotlib")
    check(str(tmp_path), ["export", "cube", "--twist", "1", "--tube-radius", value, "-o", "x.png"], (0, 1, 2))


# ---- big polygons and unused vertices -----------------------------------------------------


def test_hundred_thousand_gon_export(tmp_path):
    """One face of 100,000 sides: refused before the embedding check would take 2 x 10^7 samples."""
    mesh = write(str(tmp_path), "gon.obj", polygon_obj(100_000, two_sided=False))
    check(str(tmp_path), ["export", mesh, "--twist", "0", "-o", "g.obj"], (2,))


def test_many_unused_coincident_vertices(tmp_path):
    mesh = write(str(tmp_path), "m.obj", unused_vertices_obj(200_000, coincident=True))
    check(str(tmp_path), ["info", mesh], (0,))


@pytest.mark.slow
@pytest.mark.parametrize("n_sides", [20_000, 100_000, 300_000])
@pytest.mark.parametrize("two_sided", [False, True])
def test_big_polygons(tmp_path, n_sides, two_sided):
    mesh = write(str(tmp_path), "gon.obj", polygon_obj(n_sides, two_sided))
    for args in (["info", mesh], ["export", mesh, "--twist", "0", "-o", "g.obj"], ["trace", mesh, "--twist", "1"]):
        check(str(tmp_path), args, (0, 1, 2))


@pytest.mark.slow
@pytest.mark.parametrize("coincident", [False, True])
def test_million_unused_vertices(tmp_path, coincident):
    mesh = write(str(tmp_path), "m.obj", unused_vertices_obj(1_000_000, coincident))
    for args in (["info", mesh], ["export", mesh, "--twist", "1", "-o", "u.obj"]):
        check(str(tmp_path), args, (0,))


# ---- built-ins at their bounds (slow) -----------------------------------------------------


@pytest.mark.slow
@pytest.mark.parametrize(
    "args",
    [
        ["info", "kaleidocycle:1000"],
        ["info", "dihedron:1000"],
        ["info", "book:1000"],
        ["enumerate", "kaleidocycle:1000", "--labels", "0,1", "--count-only"],
        ["export", "dihedron:1000", "--twist", "0", "-o", "x.obj"],
        ["info", "honeycomb:cP@40x41x40"],
        ["info", "tiling:hexagonal@300x300"],
        ["trace", "honeycomb:cP@40x40x40", "--twist", "1"],
    ],
)
def test_builtins_at_their_bounds(tmp_path, args):
    check(str(tmp_path), args, (0, 1, 2))
