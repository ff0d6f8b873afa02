"""Outputs never destroy what lkspace does not own (docs/cli.md, "Output files").

Through the command line: ``-o`` onto something lkspace did not write, onto one of the
command's inputs (by any name), a name that is only an extension or an unknown URL
protocol is refused with one line and exit status 2, and what was there is byte for
byte the same afterwards.
"""

from __future__ import annotations

import json
import os

import pandas as pd
import pytest

import lkspace
from lkspace.errors import ExportError
from tests.cli_calls import one_line_error, run


def snapshot(folder):
    """Every entry under ``folder``: symlinks by target, files by bytes, folders by name."""
    out = {}
    for root, dirs, files in os.walk(folder):
        for name in dirs + files:
            path = os.path.join(root, name)
            rel = os.path.relpath(path, folder)
            if os.path.islink(path):
                out[rel] = ("link", os.readlink(path))
            elif os.path.isdir(path):
                out[rel] = ("dir",)
            else:
                with open(path, "rb") as fh:
                    out[rel] = ("file", fh.read())
    return out


def refused(capsys, tmp_path, args, *words):
    """Run ``lkspace ARGS`` in ``tmp_path``; assert exit 2, one line with ``words``, nothing changed."""
    before = snapshot(tmp_path)
    code, _, err = run(capsys, *args)
    assert code == 2, err
    one_line_error(err, *words)
    assert snapshot(tmp_path) == before


@pytest.fixture
def things(tmp_path):
    """What a user may have where ``-o`` points: none of it written by lkspace."""
    (tmp_path / "empty").mkdir()
    (tmp_path / "notes.parquet").write_text("my notes\n")
    pd.DataFrame({"a": [1, 2]}).to_parquet(tmp_path / "pandas.parquet")
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "thesis.tex").write_text("\\begin{document}")
    os.symlink("mine", tmp_path / "link.parquet")
    os.symlink("empty", tmp_path / "to-empty.parquet")
    return tmp_path


@pytest.mark.parametrize(
    "name, words",
    [
        ("empty", ["empty folder"]),
        ("notes.parquet", ["not an lkspace catalog"]),
        ("pandas.parquet", ["no 'lkspace' metadata"]),
        ("mine", ["holds no lkspace catalog"]),
        ("link.parquet", ["symbolic link"]),
        ("to-empty.parquet", ["symbolic link"]),
    ],
)
def test_enumerate_replaces_only_its_own_catalogs(things, capsys, name, words):
    refused(capsys, things, ["enumerate", "tetrahedron", "--labels", "-1,1", "-o", things / name], name, *words)


def test_a_catalog_folder_holding_a_users_file_is_not_replaced(tmp_path, capsys):
    out = tmp_path / "cat.parquet"
    assert run(capsys, "enumerate", "tetrahedron", "--labels", "-2..2", "--shards", "2", "-o", out)[0] == 0
    (out / "results.csv").write_text("mine")
    refused(capsys, tmp_path, ["enumerate", "tetrahedron", "--shards", "2", "-o", out], "results.csv")


def test_own_catalogs_are_replaced(tmp_path, capsys):
    one, folder = tmp_path / "one.parquet", tmp_path / "real"
    for out, shards in ((one, "1"), (folder, "2"), (one, "2"), (folder, "1")):  # file <-> folder both ways
        code, out_text, err = run(capsys, "enumerate", "tetrahedron", "--labels", "-1..1", "--shards", shards,
                                  "-o", out, "--json")  # fmt: skip
        assert code == 0, err
        assert len(lkspace.read_catalog(out)) == json.loads(out_text)["designs"] == 87
    os.symlink("real", tmp_path / "link.parquet")  # a link, even to an lkspace catalog: refused, nothing replaced
    refused(capsys, tmp_path, ["enumerate", "tetrahedron", "--labels", "-2,2", "-o", tmp_path / "link.parquet"],
            "symbolic link (to real)")  # fmt: skip
    assert os.path.islink(tmp_path / "link.parquet") and len(lkspace.read_catalog(folder)) == 87


def test_write_catalog_refuses_too(things):
    with pytest.raises(ExportError, match="not an lkspace catalog"):
        lkspace.write_catalog("tetrahedron", things / "notes.parquet", label_set="-1,1")
    assert (things / "notes.parquet").read_text() == "my notes\n"


@pytest.fixture
def mesh(tmp_path, capsys):
    assert run(capsys, "scaffold", "cube", "-o", tmp_path / "m.obj")[0] == 0
    os.link(tmp_path / "m.obj", tmp_path / "hard.obj")
    os.symlink("m.obj", tmp_path / "soft.obj")
    assert run(capsys, "scaffold", "cube", "-o", tmp_path / "m.json")[0] == 0
    return tmp_path


@pytest.mark.parametrize(
    "output, words", [("m.obj", ["is the input"]), ("hard.obj", ["is the input"]), ("soft.obj", ["symbolic link"])]
)
def test_export_never_writes_over_its_input(mesh, capsys, output, words):
    """The input itself, a hard link to it, or a symbolic link (refused as every link is) is never written."""
    refused(capsys, mesh, ["export", mesh / "m.obj", "--twist", "1", "-o", mesh / output], *words)


def test_other_commands_never_write_over_their_input(mesh, capsys):
    refused(capsys, mesh, ["scaffold", mesh / "m.obj", "-o", mesh / "hard.obj"], "is the input")
    refused(capsys, mesh, ["scaffold", mesh / "m.json", "-o", mesh / "m.json"], "is the input")
    refused(capsys, mesh, ["solve", mesh / "m.json", "--components", "1", "-o", mesh / "m.json"], "is the input")
    refused(capsys, mesh, ["solve", mesh / "m.json", "--type", "3_1", "-o", mesh / "m.json"], "is the input")
    twist = mesh / "t.ply"
    twist.write_text("* 1\n")
    refused(capsys, mesh, ["export", "cube", "--twist", twist, "-o", twist], "is the input")


def test_atlas_writes_only_into_new_empty_or_atlas_folders(things, tmp_path, capsys):
    refused(capsys, things, ["atlas", "tetrahedron", "--labels", "-1,1", "-o", things / "mine"], "no lkspace atlas")
    catalog = things / "cat.parquet"
    assert run(capsys, "enumerate", "tetrahedron", "--labels", "-1,1", "-o", catalog)[0] == 0
    refused(capsys, things, ["atlas", catalog, "-o", things], "holds the input")


@pytest.mark.parametrize(
    "args",
    [
        ["enumerate", "tetrahedron", "-o", ".parquet"],
        ["enumerate", "tetrahedron", "-o", ".PARQUET"],
        ["export", "tetrahedron", "--twist", "1", "-o", ".obj"],
        ["scaffold", "cube", "-o", ".json"],
    ],
)
def test_a_name_that_is_only_an_extension(tmp_path, capsys, monkeypatch, args):
    monkeypatch.chdir(tmp_path)
    refused(capsys, tmp_path, args, "only an extension")
    assert os.listdir(tmp_path) == []


def test_unknown_url_protocol(tmp_path, capsys):
    refused(capsys, tmp_path, ["enumerate", "tetrahedron", "-o", "foo://x.parquet"], "unknown protocol 'foo'")


def test_url_replaces_only_its_own_catalogs(capsys):
    fsspec = pytest.importorskip("fsspec")
    fs = fsspec.filesystem("memory")
    fs.pipe("/outputs-test/notes.parquet", b"mine")
    code, _, err = run(
        capsys, "enumerate", "tetrahedron", "--labels", "-1,1", "-o", "memory://outputs-test/notes.parquet"
    )
    assert code == 2 and fs.cat("/outputs-test/notes.parquet") == b"mine"
    one_line_error(err, "not an lkspace catalog")
    fs.rm("/outputs-test", recursive=True)


def test_python_export_never_writes_over_its_input(mesh):
    before = (mesh / "m.obj").read_bytes()
    with pytest.raises(ExportError, match="is the input"):
        lkspace.export(mesh / "m.obj", mesh / "hard.obj", 1)
    assert (mesh / "m.obj").read_bytes() == before
