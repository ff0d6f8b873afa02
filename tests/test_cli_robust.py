"""The command line under bad input and odd files, run as the program (``python -m lkspace``)."""

from __future__ import annotations

import subprocess
import sys

import pytest


def lk(*args, cwd=None, timeout=120):
    """Run ``python -m lkspace ARGS`` as a process; return ``(code, out, err)``."""
    proc = subprocess.run(
        [sys.executable, "-m", "lkspace", *map(str, args)], capture_output=True, text=True, cwd=cwd, timeout=timeout
    )
    return proc.returncode, proc.stdout, proc.stderr


def one_line(err: str, *words: str) -> None:
    """Assert that ``err`` is one ``lkspace: error:`` line holding every word of ``words``."""
    assert err.count("\n") == 1 and err.startswith("lkspace: error: "), err
    assert "Traceback" not in err and "internal error" not in err, err
    for word in words:
        assert word in err, err


def test_bare_command_prints_the_help_and_a_typo_gets_a_suggestion():
    code, out, err = lk()
    assert code == 2 and out.startswith("Usage: lkspace") and "Commands:" in out and "\n  enumerate " in out
    assert "error" not in err
    code, _, err = lk("enumrate")
    assert code == 2
    one_line(err, "'enumrate'", "did you mean 'enumerate'?")
    code, _, err = lk("frobnicate")
    assert code == 2
    one_line(err, "no such command 'frobnicate'")


def test_a_clearance_past_any_gap_is_one_line_with_a_fix(tmp_path):
    """``--clearance 1e308`` overflowed in the advice (an internal error); now: the gap measured and a clearance that fits."""
    for ext in ("stl", "3mf", "glb"):
        code, _, err = lk("export", "cube", "--twist", "2", "--clearance", "1e308", "-o", tmp_path / f"x.{ext}")
        assert code == 1
        one_line(err, "< clearance 1e+308", "no --scale up to 1e+09 reaches clearance 1e+308", "use --clearance 0.")
        assert not (tmp_path / f"x.{ext}").exists()
        gap = float(err.split("leave a gap of ")[1].split()[0])
        assert 0.05 < gap < 0.3  # the cube's strands, 0.12 thick, are ~0.23 apart: measured, not -3e306


@pytest.mark.parametrize("ext", ["obj", "ply"])
def test_a_clearance_on_curves_is_refused_not_dropped(tmp_path, ext):
    """``--clearance`` on a curves file was accepted and never checked; with ``--tubes`` it is checked."""
    out = tmp_path / f"x.{ext}"
    code, _, err = lk("export", "cube", "--twist", "2", "--clearance", "0.1", "-o", out)
    assert code == 2
    one_line(err, "--clearance", "add --tubes")
    assert not out.exists()
    code, _, err = lk("export", "cube", "--twist", "2", "--clearance", "5", "--tubes", "-o", out)
    assert code == 1 and "clearance 5" in err and not out.exists()


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--supercell", "4x4", "--block", "2x2", "--offsets", "x"], ["--offsets 'x'", "integers"]),
        (["--supercell", "4x4", "--block", "2x2", "--offsets", "9" * 20], ["--offsets", "within"]),
        (["--supercell", "2x2", "--block", "1x2", "--offsets", ",,"], ["--offsets ',,'"]),
        (["--supercell", "2x2", "--block", "9" * 20 + "x1"], ["--block", "within"]),
        (["--supercell", "2x2", "--gradient", "1,0:" + "9" * 23], ["--gradient", "within"]),
        (["--supercell", "2x2", "--gradient", "9" * 20 + ",0:1"], ["--gradient", "within"]),
        (["--supercell", "2x2", "--gradient", "1,0"], ["--gradient '1,0'", "DIRECTION:VALUES"]),
        (["--supercell", "2x2", "--gradient", "1,0:1,,2"], ["--gradient"]),
    ],
)
def test_a_malformed_motif_is_one_usage_line(args, words):
    code, _, err = lk("motifs", "tiling:square", *args)
    assert code == 2
    one_line(err, *words)


def test_an_output_through_a_symlink_is_refused_and_its_target_kept(tmp_path):
    """``-o LINK`` replaced the file the link points to; now refused (one line), the link and its target as they were."""
    (tmp_path / "precious.obj").write_text("mine\n")
    (tmp_path / "precious.parquet").write_text("mine\n")
    cases = [
        (["export", "cube", "--twist", "1", "-o", "link.obj"], "precious.obj"),
        (["scaffold", "cube", "-o", "link.obj"], "precious.obj"),
        (["solve", "cube", "-n", "1", "-o", "link.json"], "precious.obj"),
        (["enumerate", "tetrahedron", "--labels", "-1,1", "-o", "link.parquet"], "precious.parquet"),
        (["export", "cube", "--twist", "1", "-o", "dangling.obj"], "nowhere/x.obj"),
    ]
    for args, target in cases:
        link = tmp_path / args[-1]
        link.unlink(missing_ok=True)
        link.symlink_to(target)
        code, _, err = lk(*args, cwd=tmp_path)
        assert code == 2, (args, err)
        one_line(err, "is a symbolic link", target)
        assert link.is_symlink()
    assert (tmp_path / "precious.obj").read_text() == (tmp_path / "precious.parquet").read_text() == "mine\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "dangling.obj", "link.json", "link.obj", "link.parquet", "precious.obj", "precious.parquet"
    ]  # fmt: skip


def test_a_second_writer_of_the_same_catalog_stops_before_any_work(tmp_path):
    """The lock is taken at start: a run held by another process is refused before planning, not at write."""
    import json
    import socket

    holder = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(120)"])
    try:
        lock = tmp_path / ".same.parquet.lkspace-lock"
        lock.write_text(json.dumps({"pid": holder.pid, "host": socket.gethostname(), "started": "now"}))
        # planned, this run is refused as too large ("pass --yes"); locked, it must not get that far
        code, _, err = lk("enumerate", "cube", "--labels", "-3..3", "-o", "same.parquet", cwd=tmp_path)
        assert code == 1
        one_line(err, "another lkspace run is writing this catalog", f"pid {holder.pid}")
        code, _, err = lk("enumerate", "cube", "--labels", "-3..3", "--invariant", "C3:vertex=0", "-o", "same.parquet",
                          cwd=tmp_path)  # fmt: skip
        assert code == 1
        one_line(err, "another lkspace run is writing this catalog")
        assert sorted(p.name for p in tmp_path.iterdir()) == [lock.name] and str(holder.pid) in lock.read_text()
    finally:
        holder.kill()
        holder.wait()
    code, _, err = lk("enumerate", "tetrahedron", "--labels", "-1,1", "-o", "same.parquet", cwd=tmp_path)
    assert code == 0, err  # the holder is gone: its lock is stale, taken over, and removed after the run
    assert sorted(p.name for p in tmp_path.iterdir()) == ["same.parquet"]


def catalogs(folder):
    """Write a one-file and a sharded catalog of the tetrahedron (labels -1..1, 87 designs) into ``folder``."""
    assert lk("enumerate", "tetrahedron", "--labels", "-1..1", "-o", "one.parquet", cwd=folder)[0] == 0
    assert lk("enumerate", "tetrahedron", "--labels", "-1..1", "--shards", "3", "-o", "sh.parquet", cwd=folder)[0] == 0
    return folder / "one.parquet", folder / "sh.parquet"


def readers(path):
    """Every reader of a catalog, as the program: ``(name, argv)``; ``read_catalog`` through ``python -c``."""
    code = f"import lkspace; lkspace.read_catalog({str(path)!r})"
    return [
        ("verify", ["-m", "lkspace", "verify", str(path)]),
        ("atlas", ["-m", "lkspace", "atlas", str(path)]),
        ("export --row", ["-m", "lkspace", "export", str(path), "--row", "1", "-o", str(path) + "-row.obj"]),
        ("read_catalog", ["-c", code]),
    ]


def refused_by_every_reader(path, *words, every=True):
    """Assert that every reader of ``path`` ends at once (no hang) with one error line holding ``words``.

    ``every=False``: ``verify`` and ``read_catalog`` only (the others open catalogs with the same function).
    """
    for name, argv in readers(path):
        if not every and name not in ("verify", "read_catalog"):
            continue
        proc = subprocess.run([sys.executable, *argv], capture_output=True, text=True, timeout=60)
        assert proc.returncode == 1, (name, proc.stderr[-600:])
        if name == "read_catalog":
            assert proc.stderr.strip().splitlines()[-1].startswith("lkspace.errors.CatalogError: "), proc.stderr
            assert all(w in proc.stderr for w in words), (name, proc.stderr)
        else:
            one_line(proc.stderr, *words)


def test_a_fifo_in_place_of_a_catalog_file_is_refused_not_waited_on(tmp_path):
    """A part, a manifest or a one-file catalog replaced by a FIFO hung verify, read_catalog and atlas."""
    import os

    one, sharded = catalogs(tmp_path)
    part = sorted(sharded.glob("part-*.parquet"))[1]
    part.unlink()
    os.mkfifo(part)
    refused_by_every_reader(sharded, part.name, "not a regular file")
    one.unlink()
    os.mkfifo(one)
    refused_by_every_reader(one, "one.parquet", "not a regular file", every=False)
    manifest = sharded / "_lkspace.json"
    manifest.unlink()
    os.mkfifo(manifest)
    refused_by_every_reader(sharded, "_lkspace.json", "not a regular file", every=False)


def test_big_counts_are_whole_whatever_the_width():
    """A table sized to an 80- or 40-column terminal cut 10^69 designs with '…'."""
    import os

    for columns in ("40", "80"):
        proc = subprocess.run(
            [sys.executable, "-m", "lkspace", "enumerate", "dodecahedron", "--labels", "-100..100", "--count-only"],
            capture_output=True, text=True, timeout=120, env={**os.environ, "COLUMNS": columns},
        )  # fmt: skip
        assert proc.returncode == 0, proc.stderr
        code, out, _ = lk("enumerate", "dodecahedron", "--labels", "-100..100", "--count-only", "--json")
        import json

        data = json.loads(out)
        assert "…" not in proc.stdout
        assert f" designs      {data['designs']:,}\n" in proc.stdout
        assert f" assignments  {data['assignments']:,}\n" in proc.stdout


def test_a_census_past_any_machine_is_refused_up_front_and_a_feasible_one_says_its_cost():
    """--jobs 2 on 5.9e48 residue vectors ran silently for ever (its shard list never finished); now: one line."""
    code, _, err = lk("enumerate", "honeycomb:cP@3x3x3", "--labels", "-1..2", "--jobs", "2", timeout=60)
    assert code == 2
    one_line(err, "a census of 5.85e+48 residue vectors", "past what lkspace runs", "leave out --jobs")


@pytest.mark.slow
def test_a_feasible_census_says_its_cost_first():
    import json

    code, out, err = lk("enumerate", "dihedron:22", "--labels", "0,1", "--jobs", "2", "--json")
    assert code == 0, err  # 2^22 residue classes (> MAX_CLASSES): a census in parts, its cost said first
    assert err.startswith("lkspace: note: counting by a census of") and "2 workers share it" in err
    code, whole, _ = lk("enumerate", "dihedron:22", "--labels", "0,1", "--json")  # Burnside, no census
    assert json.loads(out)["designs"] == json.loads(whole)["designs"] == sum(json.loads(out)["by_components"].values())


def limited_memory():
    """In the child: at most 2 GB of address space, so a regression fails the test instead of the machine."""
    import resource

    resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))


@pytest.mark.parametrize(
    ("graph", "words"),
    [
        ("ring.obj", ["100,000 vertices", "at most 10,000"]),  # listing its 2 x 10^5 automorphisms took 16 GB
        ("ring.obj --own-faces", ["100,000 vertices"]),
        ("book:12", ["958,003,200 automorphisms", "too many to list"]),  # ran out of memory
        ("book:12 --own-faces", ["automorphisms", "too many to list"]),
    ],
)
def test_surfaces_refuses_a_graph_too_big_to_list_before_memory_grows(tmp_path, graph, words):
    import math

    n = 100_000
    with open(tmp_path / "ring.obj", "w") as fh:  # one face on a cycle of 10^5 vertices
        fh.writelines(f"v {math.cos(2 * math.pi * i / n)} {math.sin(2 * math.pi * i / n)} 0\n" for i in range(n))
        fh.write("f " + " ".join(str(i + 1) for i in range(n)) + "\n")
    proc = subprocess.run([sys.executable, "-m", "lkspace", "surfaces", *graph.split()], capture_output=True,
                          text=True, timeout=300, cwd=tmp_path, preexec_fn=limited_memory)  # fmt: skip
    assert proc.returncode == 2, proc.stderr
    progress = [line for line in proc.stderr.splitlines(keepends=True) if line.startswith("lkspace: reading")]
    one_line(proc.stderr.replace("".join(progress), ""), *words)  # a progress line of the slow read may come first


def time_options():
    """``(command, option)`` of every option of every command that limits time (its name says so)."""
    import click

    from lkspace.cli import COMMANDS, cli

    ctx = click.Context(cli)
    found = []
    for name in COMMANDS:
        command = cli.get_command(ctx, name)
        groups = command.commands.values() if isinstance(command, click.Group) else [command]
        for cmd in groups:
            for param in cmd.params:
                if isinstance(param, click.Option) and any(w in param.name for w in ("time", "stop_after", "deadline")):
                    found.append((f"{name} {cmd.name}" if cmd.name != name else name, param))
    return found


def test_every_time_limit_says_whether_it_counts_cpu_or_wall_clock_time():
    """Issue 35: identify's limit was wall-clock time (a busy machine answered 'unknown' after 9 s of work);
    each limit now counts CPU time or says it is wall-clock time, in its help."""
    options = time_options()
    assert {"identify", "solve", "atlas"} <= {command for command, _ in options}
    for command, option in options:
        words = option.help or ""
        assert ("CPU" in words) != ("wall-clock" in words), f"{command} {option.opts[0]}: {words}"


@pytest.mark.parametrize("extra", [[], ["--dna", "8"]], ids=["plain", "dna"])
def test_a_held_lock_stops_a_writer_before_it_reads_its_mesh(tmp_path, extra):
    """Issue 35: the lock before any work; a --dna run took it only to write, after reading the mesh and its rows."""
    import json
    import socket

    (tmp_path / "broken.obj").write_text("v 0 0 0\nf 1 2 3\n")  # read, it is refused; locked, it is never read
    holder = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(120)"])
    try:
        lock = tmp_path / ".same.parquet.lkspace-lock"
        lock.write_text(json.dumps({"pid": holder.pid, "host": socket.gethostname(), "started": "now"}))
        code, _, err = lk("enumerate", "broken.obj", *extra, "-o", "same.parquet", cwd=tmp_path)
        assert code == 1
        one_line(err, "another lkspace run is writing this catalog", f"pid {holder.pid}")
    finally:
        holder.kill()
        holder.wait()


@pytest.mark.parametrize(
    "args",
    [
        ["solve", "icosahedron", "--type", "10_123", "--labels", "-1..1"],  # named enumerate's --mode
        ["export", "cube", "--twist", "4", "--nm-per-unit", "5.2", "-o", "x.oxdna"],  # named the geometry's --scale
        ["export", "cube", "--twist", "4", "--nm-per-unit", "1e9", "-o", "x.oxdna"],
        ["enumerate", "icosahedron", "--labels", "-1..1", "-o", "x.parquet"],
        ["atlas", "icosahedron", "--labels", "-1..1"],
    ],
)
def test_a_refusal_names_only_flags_its_command_has(tmp_path, args):
    """The advice of a refusal is something the user can type: every ``--flag`` it names is one of the command's."""
    import re

    import click

    from lkspace.cli import cli

    code, _, err = lk(*args, cwd=tmp_path)
    assert code == 2
    one_line(err)
    command = cli.get_command(click.Context(cli), args[0])
    own = {opt for param in command.params for opt in param.opts}
    assert set(re.findall(r"--[a-z][a-z-]*", err)) <= own, err
    assert list(tmp_path.iterdir()) == []
