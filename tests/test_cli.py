"""The command line: JSON contract, defaults, and one-line errors for bad input."""

from __future__ import annotations

import json
import subprocess
import sys

import click
import pytest

from lkspace.cli import COMMANDS, SUMMARIES, cli, main

from .cli_calls import run


def run_json(capsys, *args):
    code, out, err = run(capsys, *args, "--json")
    assert code == 0, err
    return json.loads(out), err


def test_trace_default_scaffold(capsys):
    data, err = run_json(capsys, "trace", "--twist", "1")
    assert "tetrahedron" in err
    assert data["default_scaffold"] is True
    assert data["components"] == 3 and data["holds_together"] is True
    assert sum(len(s["faces"]) for s in data["strands"]) == 12


@pytest.mark.parametrize("spec, components", [("-1,0,1,1,1,1", 2), ("-1", 3), ("0", 4), ("2", 4)])
def test_trace_negative_values_work_as_typed(capsys, spec, components):
    data, _ = run_json(capsys, "trace", "tetrahedron", "--twist", spec)
    assert data["components"] == components


def test_trace_twist_file(capsys, tmp_path):
    f = tmp_path / "tw.txt"
    f.write_text("# labels\n0-1 1\n2 3 -1\n* 0\n")
    data, _ = run_json(capsys, "trace", "tetrahedron", "--twist", str(f))
    assert data["labels"] == [1, 0, 0, 0, 0, -1]


def test_trace_null(capsys):
    data, _ = run_json(capsys, "trace", "tetrahedron", "--twist", "1", "--null", "0.0")
    assert data["n_open"] == 1
    assert sum(not s["closed"] for s in data["strands"]) == 1


def test_trace_labels_from_scaffold_file(capsys, tmp_path):
    path = tmp_path / "d.json"
    assert run(capsys, "scaffold", "tetrahedron", "-o", str(path))[0] == 0
    doc = json.loads(path.read_text())
    doc["labels"] = [1] * 6
    path.write_text(json.dumps(doc))
    data, _ = run_json(capsys, "trace", str(path))
    assert data["components"] == 3


def test_info(capsys):
    data, _ = run_json(capsys, "info", "book:3")
    assert data["edges"] == 10 and data["edge_degrees"] == {"1": 9, "3": 1}
    assert data["boundary_edges"] == 9 and data["non_manifold_edges"] == 1


def test_scaffold_writes_file(capsys, tmp_path):
    data, _ = run_json(capsys, "scaffold", "cube", "-o", str(tmp_path / "c.obj"))
    assert data["faces"] == 6
    assert (tmp_path / "c.obj").read_text().count("\nf ") == 6


def test_human_output(capsys):
    code, out, _ = run(capsys, "trace", "cube", "--twist", "1")
    assert code == 0 and "4 components" in out


@pytest.mark.parametrize(
    "args, message",
    [
        (["trace", "nope.obj", "--twist", "1"], "nope.obj: no such scaffold file"),
        (["trace", "cube", "--twist", "1,2"], "expected 12 twist labels"),
        (["trace", "cube", "--twist", "1.5"], "neither an integer"),
        (["trace", "cube", "--twist", "1,x,1,1,1,1,1,1,1,1,1,1"], "'x' is not an integer"),
        (["trace", "cube"], "no --twist given"),
        (["trace", "cube", "--twist", "1", "--null", "9.0"], "face 9 out of range"),
        (["info", "dodecahedronx"], "neither a file nor a built-in"),
        (["scaffold", "pyramid"], "'pyramid' is neither a file nor a built-in scaffold name"),
        (["frobnicate"], "no such command"),
        (["trace", "--bogus"], "No such option"),
    ],
)
def test_bad_input_is_one_line(capsys, args, message):
    code, out, err = run(capsys, *args, "--json")
    assert code == 2  # every case is an option, argument or name given on the command line
    error = json.loads(out)["error"]
    assert error["exit_code"] == 2 and message in error["message"]
    lines = [line for line in err.splitlines() if line.strip() and "no MESH given" not in line]
    assert len(lines) == 1, err
    assert message in lines[0]
    assert "Traceback" not in err


def test_bad_obj_file_names_line(capsys, tmp_path):
    p = tmp_path / "bad.obj"
    p.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
    code, _, err = run(capsys, "trace", str(p), "--twist", "1")
    assert code == 1 and "bad.obj line 4" in err  # bad data in a file


def test_ambiguous_radial_order_cli(capsys, tmp_path):
    p = tmp_path / "amb.obj"
    p.write_text("v 0 0 0\nv 0 0 1\nv 1 0 .5\nv 2 0 .5\nv -1 0 .5\nf 1 2 3\nf 1 2 4\nf 1 2 5\n")
    code, _, err = run(capsys, "trace", str(p), "--twist", "1")
    assert code == 1 and "ambiguous radial order at edge 0 (0-1)" in err


def test_python_dash_m_entry_point():
    proc = subprocess.run(
        [sys.executable, "-m", "lkspace", "trace", "cube", "--twist", "2", "--json"],
        capture_output=True,
        text=True,
        check=True,
    )
    assert json.loads(proc.stdout)["components"] == 6


def imported_modules(*args):
    """Names of the modules ``python -m lkspace ARGS`` imports (from ``-X importtime``), and its stdout."""
    proc = subprocess.run([sys.executable, "-X", "importtime", "-m", "lkspace", *args], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr[-2000:]
    lines = [line.split("|") for line in proc.stderr.splitlines() if line.startswith("import time:")]
    return {cells[2].strip() for cells in lines if len(cells) == 3}, proc.stdout


def test_help_lists_every_command_without_importing_numpy():
    modules, out = imported_modules("--help")
    assert "click" in modules and "lkspace.cli" in modules  # the list is read right
    assert not {m for m in modules if m.split(".")[0] in ("numpy", "scipy", "numba", "pandas", "pyarrow")}
    assert not {m for m in modules if m.startswith("lkspace.cli.") and m != "lkspace.cli.flags"}
    listed = [line.split()[0] for line in out.split("Commands:")[1].splitlines() if line.strip()]
    assert listed == list(COMMANDS)


def test_help_summaries_are_the_commands_own():
    ctx = click.Context(cli)
    for name in COMMANDS:
        command = cli.get_command(ctx, name)
        for limit in (20, 45, 80, 200):
            assert click.Command(name, help=SUMMARIES[name]).get_short_help_str(limit) == command.get_short_help_str(
                limit
            )


def test_count_only_loads_no_pandas_or_pyarrow():
    modules, out = imported_modules("enumerate", "cube", "--labels", "-1..1", "--count-only", "--json")
    assert json.loads(out)["designs"] == 22815 and "numba" in modules
    assert not {m for m in modules if m.split(".")[0] in ("pandas", "pyarrow")}


def test_writing_a_catalog_loads_no_pandas(tmp_path):
    out = tmp_path / "c.parquet"
    modules, _ = imported_modules("enumerate", "honeycomb:cP", "--labels", "-1..1", "-o", str(out))
    assert "pyarrow.parquet" in modules and not {m for m in modules if m.split(".")[0] == "pandas"}
    import pyarrow.parquet as pq

    table = pq.read_table(out)
    assert table.num_rows == 10 and sum(table.column("orbit_size").to_pylist()) == 3**3


def test_naming_a_space_by_key_loads_no_scipy_spatial_or_matplotlib(tmp_path):
    """What names designs by key needs no KD-tree (scipy.spatial); igraph comes without matplotlib."""
    out = tmp_path / "c.parquet"
    modules, _ = imported_modules("enumerate", "cube", "--labels", "-1..1", "--identify", "-o", str(out))
    assert "regina.engine" in modules and "lkspace.knots.keys_ahead" in modules  # names were made by key
    assert not {m for m in modules if m.startswith(("scipy.spatial", "pandas", "matplotlib."))}
    modules, _ = imported_modules("atlas", "cube", "--labels", "-1..1")
    assert not {m for m in modules if m.startswith(("scipy.spatial", "matplotlib."))}
    modules, out_text = imported_modules("solve", "cube", "--type", "10_1", "--labels", "-1..1")
    assert "igraph" in modules and "exhausted" in out_text
    assert not {m for m in modules if m.startswith("matplotlib.")}  # (a bare "matplotlib" is igraph's refused try)


def test_igraph_comes_without_matplotlib_which_still_imports_after():
    code = (
        "import sys\n"
        "from lkspace.runtime.graphs import igraph_module\n"
        "ig = igraph_module()\n"
        "assert 'matplotlib' not in sys.modules, 'matplotlib came with igraph'\n"
        "assert ig.Graph.Ring(5).count_automorphisms() == 10\n"
        "import matplotlib.pyplot\n"
        "print(matplotlib.pyplot.figure is not None)\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.returncode == 0 and proc.stdout.strip() == "True", proc.stderr[-2000:]


def test_trace_json_matches_reference_on_random_meshes(capsys, tmp_path):
    """The CLI's JSON, on random non-manifold OBJ files, against the independent tracer."""
    import warnings
    from collections import Counter

    import numpy as np

    import lkspace
    from lkspace.errors import LkspaceWarning, RadialOrderError

    from .reference import reference_trace

    rng = np.random.default_rng(7)
    checked = 0
    for trial in range(150):
        n = int(rng.integers(4, 9))
        vertices = rng.normal(size=(n, 3))
        faces = [
            rng.permutation(n)[: int(rng.integers(3, min(n, 6) + 1))].tolist() for _ in range(int(rng.integers(1, 7)))
        ]
        path = tmp_path / f"m{trial}.obj"
        path.write_text(
            "".join(f"v {x} {y} {z}\n" for x, y, z in vertices)
            + "".join("f " + " ".join(str(v + 1) for v in f) + "\n" for f in faces)
        )
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", LkspaceWarning)  # random faces may share no edge
            s = lkspace.load(str(path))
        try:
            s.radial
        except RadialOrderError:
            continue
        twists = rng.integers(-4, 5, s.n_edges)
        code, out, err = run(capsys, "trace", str(path), "--twist", ",".join(map(str, twists)), "--json")
        assert code == 0, err
        data = json.loads(out)
        ref = reference_trace(
            vertices.tolist(), faces, {tuple(e): int(t) for e, t in zip(s.edge_vertices.tolist(), twists)}
        )
        assert data["components"] == len(ref)
        mine = Counter(tuple(sorted(Counter(st["faces"]).items())) for st in data["strands"])
        theirs = Counter(tuple(sorted(Counter(f).items())) for _, f in ref)
        assert mine == theirs
        checked += 1
    assert checked >= 100


def test_installed_command_never_dies_on_huge_labels_or_fifos(tmp_path):
    """The journeys that crashed or hung: a label at the int64 limit, a FIFO as input (real processes)."""
    import os

    fifo = tmp_path / "pipe.obj"
    os.mkfifo(fifo)
    cases = [
        (["trace", "book:3", "--twist", "9223372036854775808"], 2, "out of range"),
        (["trace", "book:3", "--twist", "9223372036854775807", "--json"], 0, '"components"'),
        (["trace", "book:3", "--twist", "4611686018427387904", "--json"], 0, '"components": 1'),
        (["info", str(fifo)], 2, "not a regular file"),
        (["trace", "cube", "--twist", str(fifo)], 2, "not a regular file"),
        (["info", "book:999999999999"], 2, "book:K is limited to K <= 1000"),
    ]
    for args, code, text in cases:
        proc = subprocess.run(["lkspace", *args], capture_output=True, text=True, timeout=60)
        assert proc.returncode == code, (args, proc.stderr)
        assert text in (proc.stdout if code == 0 else proc.stderr)
        if code:
            assert proc.stderr.count("\n") == 1 and "Traceback" not in proc.stderr


def test_scaffold_converts_files_and_checks_the_output_first(capsys, tmp_path):
    src = tmp_path / "c.obj"
    assert main(["scaffold", "cube", "-o", str(src)]) == 0
    out = tmp_path / "c.json"
    code, _, err = run(capsys, "scaffold", str(src), "-o", str(out))
    assert code == 0 and json.loads(out.read_text())["name"] == "c.obj"
    for bad, message in [(tmp_path / "x.stl", "extension '.stl'"), (tmp_path / "no" / "x.json", "does not exist")]:
        code, _, err = run(capsys, "scaffold", "cube", "-o", str(bad))
        assert code == 2 and message in err
    code, _, err = run(capsys, "scaffold", "honeycomb:cP", "-o", str(tmp_path / "p.obj"))
    assert code == 2 and "OBJ cannot hold a periodic scaffold" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.json", "c.obj"]
