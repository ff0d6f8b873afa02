"""solve and identify never crash and never run unbounded: bounds, time limits, statuses (export: test_export.py).

Every test goes through the real command line (``main``) or the installed ``lkspace``
command, with catalogs written by the real ``enumerate``.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np
import pytest

import lkspace

from .cli_calls import one_line_error, run

BIG_KNOT = "2,2,2,2,2,1,2,2,1,2,1,2,1,2,2,1,2,1,2,1,2,2,1,1,2,1,1,2,2,2,1,2,2,1,2,2"
"""A one-component design of the truncated octahedron: a 189-crossing projection, 81 after simplification."""


def lkspace_command() -> list[str]:
    """The installed ``lkspace`` console script of this interpreter."""
    script = shutil.which("lkspace", path=os.path.dirname(sys.executable)) or shutil.which("lkspace")
    assert script, "the lkspace console script is not installed"
    return [script]


def quad_obj(tmp_path):
    path = tmp_path / "quad.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n")
    return path


def unwelded_cube(tmp_path):
    """A cube whose six faces share no vertex: every edge is a boundary edge."""
    corners = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    faces = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
    lines = []
    for face in faces:
        lines += ["v {} {} {}".format(*corners[v]) for v in face]
    lines += ["f " + " ".join(str(4 * i + j + 1) for j in range(4)) for i in range(6)]
    path = tmp_path / "unwelded.obj"
    path.write_text("\n".join(lines) + "\n")
    return path


# --- solve -------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "mesh, n, status",
    [("quad", 1, "feasible"), ("quad", 2, "infeasible"), ("cube", 1, "infeasible"), ("cube", 6, "feasible")],
)
@pytest.mark.filterwarnings("ignore:.*share no edge:lkspace.errors.LkspaceWarning")
def test_solve_without_two_face_edges(tmp_path, capsys, mesh, n, status):
    path = quad_obj(tmp_path) if mesh == "quad" else unwelded_cube(tmp_path)
    code, out, err = run(capsys, "solve", str(path), "-n", str(n), "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data["status"] == status
    for sol in data["solutions"]:
        assert lkspace.trace(lkspace.load(str(path)), sol["labels"]).components == n
    if status == "infeasible":
        assert "component" in data["reason"]


@pytest.mark.parametrize(
    "args, words",
    [
        (["--time-limit", "nan"], ["--time-limit", "finite"]),
        (["--time-limit", "-5"], ["--time-limit", ">= 0"]),
        (["--time-limit", "inf"], ["--time-limit"]),
        (["--count", str(10**30)], ["--count", "10000"]),
        (["--count", "0"], ["--count"]),
        (["-n", "0"], ["--components"]),
        (["--workers", "-1"], ["--workers"]),
        (["--seed", "-1"], ["--seed"]),
        (["--seed", str(2**31)], ["--seed"]),
        (["--fix", f"0={10**21}"], ["--fix", "-1,000,000..1,000,000"]),
        (["-o", ""], ["empty"]),
        (["-o", "design.txt"], [".json"]),
        (["-o", "/no/such/folder/d.json"], ["does not exist"]),
    ],
)
def test_solve_bad_numbers_and_paths_are_one_line(capsys, args, words):
    code, out, err = run(capsys, "solve", "cube", "-n", "1", *args)
    assert code == 2 and out == ""
    one_line_error(err, *words)


def test_solve_huge_component_count_is_infeasible(capsys):
    code, out, err = run(capsys, "solve", "cube", "-n", str(10**30), "--json")
    assert code == 0, err
    assert json.loads(out)["status"] == "infeasible"


def test_solve_output_through_a_symlink_is_refused(tmp_path, capsys):
    real = tmp_path / "real.json"
    real.write_text("mine")
    link = tmp_path / "link.json"
    link.symlink_to(real)
    code, _, err = run(capsys, "solve", "cube", "-n", "1", "-o", str(link))
    assert code == 2 and "symbolic link" in err, err
    assert link.is_symlink() and real.read_text() == "mine"


def test_solve_library_bounds():
    from lkspace.errors import TooLargeError, UsageError

    with pytest.raises(TooLargeError, match="MAX_COUNT"):
        lkspace.solve("cube", 1, options=lkspace.SolveOptions(count=10**30))
    with pytest.raises(UsageError, match="^time_limit nan: "):
        lkspace.solve("cube", 1, options=lkspace.SolveOptions(time_limit=float("nan")))


def test_solve_time_limit_covers_every_stage_and_shows_progress(tmp_path):
    """The installed command on a 5,103-face mesh stops at its (wall-clock) limit with a status and progress lines.

    The bound on the reported time is a hang detector, not a speed test: it holds on a
    loaded machine, and a stage that ignored the limit would run for minutes.
    """
    limit = 3.0
    env = {**os.environ, "LKSPACE_PROGRESS": "1"}
    proc = subprocess.run(
        [*lkspace_command(), "solve", "honeycomb:cI@9x9x9", "-n", "7", "--time-limit", str(limit), "--json"],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
    )
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert data["status"] in ("unknown", "feasible") and data["wall_time"] < limit + 30
    if data["status"] == "unknown":
        assert "time limit" in data["reason"], data
    assert "lkspace: solving honeycomb:cI@9x9x9 for 7 components" in proc.stderr


# --- identify ----------------------------------------------------------------------------


def test_identify_huge_twist_is_refused_before_any_work(capsys):
    pytest.importorskip("spherogram")
    cpu = time.process_time()
    code, out, err = run(capsys, "identify", "dihedron:3", "--twist", "100000", "--json")
    assert time.process_time() - cpu < 5  # CPU seconds, whatever the load: building the diagram would take minutes
    assert code == 2
    one_line_error(err, "300,000 crossings", "MAX_CROSSINGS")
    assert json.loads(out)["error"]["type"] == "TooLargeError"


def test_identify_time_limit_ends_in_a_status(tmp_path):
    """The installed command: the naming child is killed at the limit; the status says so."""
    pytest.importorskip("spherogram")
    proc = subprocess.run(
        [*lkspace_command(), "identify", "truncated-octahedron", "--twist", BIG_KNOT, "--time-limit", "0.3", "--json"]
        + ["--geometric"],  # the path that names a 190-crossing projection (from the labels, a known key is instant)
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert data["status"].startswith("unknown: time limit 0.3 s reached (during ")
    assert data["name"] is None and data["projected_crossings"] > 30 and data["linking_matrix"] == [[0]]


def test_identify_reports_its_stages_and_answers_a_big_knot_within_the_default_limit(capsys, monkeypatch):
    """Plain progress lines (as in logs) name each stage, those of the naming child included."""
    pytest.importorskip("spherogram")
    from lkspace.runtime import progress

    monkeypatch.setenv("LKSPACE_PROGRESS", "1")
    monkeypatch.setattr(progress, "DELAY", 0.0)  # show every step at once, every note
    monkeypatch.setattr(progress, "PLAIN_EVERY", 0.0)
    code, out, err = run(capsys, "identify", "truncated-octahedron", "--twist", BIG_KNOT, "--json", "--geometric")
    assert code == 0, err
    data = json.loads(out)  # within the default limit (one call for both checks: naming it takes 10-30 s)
    assert data["status"].startswith("unknown: not in the tables") and data["crossings"] > 13
    for stage in ("tracing", "realizing", "diagram", "simplification (", "table lookup"):
        assert f"lkspace: identifying truncated-octahedron: {stage}" in err, err
    # the projected crossings depend on the geometry (about 190 for this design)
    assert re.search(r"simplification \(\d{3} crossings\)", err), err


def test_identify_diagram_too_large(capsys, monkeypatch):
    pytest.importorskip("spherogram")
    from lkspace.knots import recognition

    monkeypatch.setattr(recognition, "MAX_CROSSINGS", 100)
    code, out, err = run(capsys, "identify", "truncated-octahedron", "--twist", BIG_KNOT, "--json", "--geometric")
    assert code == 0, err
    data = json.loads(out)
    assert data["status"] == f"unknown: diagram too large: {data['projected_crossings']} crossings > 100"
    code, out, err = run(capsys, "identify", "truncated-octahedron", "--twist", BIG_KNOT, "--geometric")
    assert "unknown: diagram too large" in out and "crossings of the projection" in out


def test_identify_status_identified(capsys):
    pytest.importorskip("spherogram")
    code, out, err = run(capsys, "identify", "dihedron:3", "--twist", "1", "--json")
    assert code == 0, err
    assert json.loads(out)["status"] == "identified"


def test_identify_periodic_scaffold_is_refused(capsys):
    code, _, err = run(capsys, "identify", "honeycomb:cP", "--twist", "1")
    assert code == 2
    one_line_error(err, "periodic", "export", "--block")


@pytest.mark.parametrize(
    "args, words",
    [
        (["--time-limit", "nan"], ["--time-limit"]),
        (["--time-limit", "-1"], ["--time-limit"]),
        (["--radius", "0"], ["--radius", "> 0"]),
        (["--normal-offset", "nan"], ["--normal-offset"]),
        (["--tube-radius", "-inf"], ["--tube-radius"]),
        (["--row", "-1"], ["--row"]),
        (["--seed", "-5"], ["--seed"]),
    ],
)
def test_identify_bad_numbers(capsys, args, words):
    code, _, err = run(capsys, "identify", "dihedron:3", "--twist", "1", *args)
    assert code == 2
    one_line_error(err, *words)


def test_identify_batch_budget_per_design():
    pytest.importorskip("spherogram")
    from lkspace.knots.batch import NamerOptions, identify_batch

    scaffold = lkspace.load("truncated-octahedron")
    big = 3 * np.array(BIG_KNOT.split(","), np.int64)  # 3-4 s to name on an idle machine: 1 s never suffices
    # the unlink has no crossing: it is named at once, in this process, however loaded the machine is
    frame = identify_batch(scaffold, [big, np.zeros_like(big), np.full_like(big, 500)], NamerOptions(time_limit=1.0))
    assert frame["status"][0].startswith("unknown: time limit 1 s") and frame["error"][0].startswith("time limit")
    assert frame["status"][1] == "identified" and frame["error"].isna()[1]  # an unlink of 14 circles
    assert "MAX_CROSSINGS" in frame["error"][2] and frame["status"][2].startswith("unknown: ")
    with pytest.raises(lkspace.errors.UsageError, match="periodic"):
        identify_batch(lkspace.load("honeycomb:cP"), [[1] * 3])
