"""Parquet catalogs: schema, metadata, shards, resume, and the enumerate command."""

from __future__ import annotations

import json
import os
import signal

import numpy as np
import pandas as pd
import pyarrow.parquet as pq
import pytest

from lkspace import Execution, Selection, load, write_catalog
from lkspace.catalog import plan
from lkspace.catalog.metadata import FORMAT_VERSION
from lkspace.catalog.plan import CatalogTooLarge, split_classes
from lkspace.catalog.reader import read_catalog, read_metadata
from lkspace.catalog.records import Manifest, PartFooter
from lkspace.catalog.transaction import MANIFEST
from lkspace.design.space import make_space
from lkspace.errors import CatalogError, ExportError, UsageError

from .cli_calls import run


def test_single_file_catalog(tmp_path):
    space = make_space(load("tetrahedron"), "-2..2", "rotations")
    path = tmp_path / "t.parquet"
    totals = write_catalog(space, path)
    df = pd.read_parquet(path)
    assert len(df) == totals.designs == 1475
    assert df.orbit_size.sum() == totals.assignments == 5**6
    for col in ("labels", "components", "orbit_size", "n_zero", "strand_lengths"):
        assert col in df.columns
    assert all(isinstance(int(x), int) for x in df.labels.iloc[0]) and len(df.labels.iloc[0]) == 6
    assert sum(df.strand_lengths.iloc[0]) == 12
    meta = json.loads(pq.read_metadata(path).metadata[b"lkspace"])
    assert meta["format_version"] == FORMAT_VERSION
    assert (
        meta["scaffold"]["name"] == "tetrahedron" and meta["scaffold"]["content_hash"] == space.scaffold.content_hash()
    )
    assert meta["label_set"] == [-2, -1, 0, 1, 2] and meta["symmetry"] == "rotations" and meta["group_order"] == 12
    assert meta["rows"] == 1475
    assert [p for p in os.listdir(tmp_path)] == ["t.parquet"]  # no temporary files left
    assert pq.read_schema(path).field("labels").type.value_type.bit_width == 8


def test_sharded_catalog_and_resume(tmp_path):
    space = make_space(load("cube"), "-1..1", "rotations")
    single = tmp_path / "one.parquet"
    write_catalog(space, single)
    folder = tmp_path / "many"
    totals = write_catalog(space, folder, execution=Execution(shards=3))
    assert totals.shards == 3 and totals.designs == 22815
    a = pd.read_parquet(single).sort_values("key").reset_index(drop=True)
    b = pd.read_parquet(folder).sort_values("key").reset_index(drop=True)
    assert a.key.tolist() == b.key.tolist() and a.orbit_size.tolist() == b.orbit_size.tolist()
    parts = sorted(p for p in os.listdir(folder) if p.startswith("part-"))
    assert len(parts) == 3
    os.remove(folder / parts[1])  # a damaged finished catalog: --resume keeps the two good parts
    again = write_catalog(space, folder, execution=Execution(shards=3, resume=True))
    assert again.shards_resumed == 2 and again.designs == 22815
    assert len(read_catalog(folder)) == 22815
    other = write_catalog(
        make_space(load("cube"), "-1..1", "isometries"), folder, execution=Execution(shards=3, resume=True)
    )
    assert other.shards_resumed == 0 and read_metadata(folder)["symmetry"] == "isometries"
    assert read_metadata(folder)["shard"]["count"] == 3


def test_parallel_jobs(tmp_path):
    space = make_space(load("cube"), "-1..1", "isometries")
    totals = write_catalog(space, tmp_path / "p", execution=Execution(jobs=2, shards=4))
    df = pd.read_parquet(tmp_path / "p")
    assert len(df) == totals.designs and df.orbit_size.sum() == 3**12
    assert df.key.is_unique


def test_split_classes_balances_and_covers():
    w = np.array([5, 0, 1, 1, 7, 2, 0, 3], dtype=object)
    runs = split_classes(w, 3)
    assert sorted(c for r in runs for c in r) == [0, 2, 3, 4, 5, 7]


def test_not_a_catalog(tmp_path):
    path = tmp_path / "x.parquet"
    pd.DataFrame({"a": [1]}).to_parquet(path)
    with pytest.raises(CatalogError, match="not an lkspace catalog"):
        read_metadata(path)
    (tmp_path / "junk").mkdir()
    (tmp_path / "junk" / "f.txt").write_text("x")
    with pytest.raises(ExportError, match="holds no lkspace catalog"):
        write_catalog(make_space(load("tetrahedron"), "-1..1"), tmp_path / "junk", execution=Execution(shards=2))
    assert os.listdir(tmp_path / "junk") == ["f.txt"]


# ---- the command line ----------------------------------------------------------------------


def test_cli_default_scaffold_json(capsys):
    code, out, err = run(capsys, "enumerate", "--labels", "-2,2", "--json")
    assert code == 0 and "tetrahedron" in err
    data = json.loads(out)
    assert data["designs"] == 12 and data["assignments"] == 64 and data["group_order"] == 12
    assert data["by_components"] == {"4": 12}


def test_cli_writes_catalog(capsys, tmp_path):
    path = tmp_path / "c.parquet"
    code, out, _ = run(
        capsys,
        "enumerate",
        "tetrahedron",
        "--labels",
        "-2..2",
        "--symmetry",
        "isometries",
        "--components",
        "1",
        "--no-zero",
        "-o",
        str(path),
        "--json",
    )
    assert code == 0
    data = json.loads(out)
    df = pd.read_parquet(path)
    assert data["designs"] == len(df) > 0 and (df.components == 1).all() and (df.n_zero == 0).all()
    assert data["group_order"] == 24 and data["by_components"] == {"1": len(df)}


def test_cli_count_only_matches_walk(capsys, tmp_path):
    code, out, _ = run(capsys, "enumerate", "cube", "--labels", "-2..2", "--count-only", "--json")
    data = json.loads(out)
    assert data["designs"] == 10_194_250 and data["assignments"] == 244_140_625 and data["written"] is None
    code, out, _ = run(
        capsys,
        "enumerate",
        "book:3",
        "--labels",
        "-1..1",
        "--mode",
        "residues",
        "-o",
        str(tmp_path / "r.parquet"),
        "--json",
    )
    data = json.loads(out)
    df = pd.read_parquet(tmp_path / "r.parquet")
    assert data["designs"] == len(df) and df.orbit_size.sum() == 3**10


@pytest.mark.parametrize(
    "args, message",
    [
        (["cube", "--labels", "0..2", "--symmetry", "isometries"], "closed under negation"),
        (["cube", "--sample", "3"], "spanning-trees"),
        (["cube", "--labels", "2..1"], "empty range"),
        (["nosuchthing"], "neither a file nor a built-in"),
    ],
)
def test_cli_errors_are_one_line(capsys, args, message):
    code, out, err = run(capsys, "enumerate", *args, "--json")
    assert code == 2 and json.loads(out)["error"]["exit_code"] == 2
    assert message in err and len(err.strip().splitlines()) == 1


def test_interrupted_run_leaves_no_partial_part_and_resumes(tmp_path, monkeypatch):
    import lkspace.catalog.jobs as jobs
    from lkspace.catalog.transaction import CatalogInterrupted

    space = make_space(load("cube"), "-1..1", "rotations")
    folder = tmp_path / "run"
    real = jobs.space_batches
    calls = {"n": 0}

    def flaky(*args, **kwargs):
        calls["n"] += 1
        if calls["n"] == 2:  # the second shard dies after its first batch

            def broken():
                yield from list(real(*args, **kwargs))[:1]
                raise KeyboardInterrupt

            return broken()
        return real(*args, **kwargs)

    monkeypatch.setattr(jobs, "space_batches", flaky)
    with pytest.raises(CatalogInterrupted, match="1 of 3 parts are finished"):
        write_catalog(space, folder, execution=Execution(shards=3))
    assert not folder.exists()  # nothing at the final name
    build = tmp_path / ".run.lkspace-build"
    assert sorted(p.split("-")[0] for p in os.listdir(build)) == ["_lkspace.json", "part"]  # no temporary part
    monkeypatch.setattr(jobs, "space_batches", real)
    totals = write_catalog(space, folder, execution=Execution(shards=3, resume=True))
    assert totals.shards_resumed == 1 and totals.designs == 22815
    assert pd.read_parquet(folder).orbit_size.sum() == 3**12
    assert sorted(os.listdir(tmp_path)) == ["run"]


def test_library_errors_name_parameters_and_the_cli_names_flags(tmp_path, monkeypatch, capsys):
    out = tmp_path / "t.parquet"
    with pytest.raises(UsageError, match=r"^jobs 0: use 1\.\.256 worker processes$") as refused:
        write_catalog("tetrahedron", out, "-1..1", execution=Execution(jobs=0))
    assert refused.value.parameter == "jobs"
    with pytest.raises(CatalogError, match=r"^shards applies to full design walks \(not with max_designs") as refused:
        write_catalog("tetrahedron", out, "-1..1", selection=Selection(max_designs=5), execution=Execution(shards=2))
    assert refused.value.parameter == "shards" and refused.value.exit_code == 2
    code, _, err = run(
        capsys, "enumerate", "tetrahedron", "--labels", "-1..1", "-o", out, "--max-designs", 5, "--shards", 2
    )
    assert code == 2 and "error: --shards applies to full design walks (not with --max-designs or other modes)" in err
    monkeypatch.setattr(plan, "ROW_LIMIT", 10)  # the tetrahedron's 87 designs are now a large run
    with pytest.raises(CatalogTooLarge, match=r"pass Execution\(allow_large=True\) to go ahead") as refused:
        write_catalog("tetrahedron", out, "-1..1")
    assert refused.value.allowable and "--" not in str(refused.value) and not out.exists()
    code, _, err = run(capsys, "enumerate", "tetrahedron", "--labels", "-1..1", "-o", out)
    assert (
        code == 2
        and "past 10 rows" in err
        and err.rstrip().endswith("pass --yes to go ahead (or use --count-only, filters or a smaller label set)")
    )
    assert write_catalog("tetrahedron", out, "-1..1", execution=Execution(allow_large=True)).designs == 87
    assert run(capsys, "enumerate", "tetrahedron", "--labels", "-1..1", "-o", out, "--yes")[0] == 0


def test_write_catalog_leaves_the_callers_signal_handlers_alone(tmp_path):
    """The library installs no SIGTERM handler: the program (the command line) decides what SIGTERM does."""
    seen = []

    def progress(total):
        return lambda rows: seen.append(signal.getsignal(signal.SIGTERM))

    before = signal.getsignal(signal.SIGTERM)
    write_catalog("cube", tmp_path / "c", "-1..1", execution=Execution(shards=2), progress=progress)
    assert seen and all(handler is before for handler in seen)
    assert signal.getsignal(signal.SIGTERM) is before


def test_manifest_records_round_trip_byte_for_byte(tmp_path):
    """A manifest or a footer read into records and written back is the same text: builds of earlier versions resume."""
    write_catalog("cube", tmp_path / "c", "-1..1", selection=Selection(components=2), execution=Execution(shards=3))
    text = (tmp_path / "c" / MANIFEST).read_text()
    manifest = Manifest.from_json(json.loads(text), "manifest")
    assert manifest.complete and sorted(manifest.parts) == [0, 1, 2]
    assert manifest.encode() == text
    assert sum(p.rows for p in manifest.parts.values()) == len(pd.read_parquet(tmp_path / "c"))
    for part in manifest.parts.values():
        file = tmp_path / "c" / str(part.file)
        for raw in (pq.read_metadata(file).metadata[b"lkspace"], pq.read_schema(file).metadata[b"lkspace"]):
            assert PartFooter.from_json(json.loads(raw), str(file)).encode() == raw  # footer, and the schema's copy


def test_one_parser_of_the_manifest_for_reads_and_resumes(tmp_path):
    """What a read refuses a resume does not keep: a malformed entry is refused by both (the build starts over)."""
    out = tmp_path / "c"
    write_catalog("cube", out, "-1..1", execution=Execution(shards=3))
    data = json.loads((out / MANIFEST).read_text())
    with pytest.raises(CatalogError, match="the entry of part 0 is malformed"):
        Manifest.from_json({**data, "parts": {**data["parts"], "0": {"rows": "x"}}}, "manifest")
    with pytest.raises(CatalogError, match="not numbered 0..2"):
        Manifest.from_json({**data, "parts": {**data["parts"], "3": data["parts"]["0"]}}, "manifest")
    build = tmp_path / ".c.lkspace-build"
    out.rename(build)
    del data["complete"]
    data["parts"]["0"]["rows"] = "x"
    (build / MANIFEST).write_text(json.dumps(data, indent=1))
    again = write_catalog("cube", out, "-1..1", execution=Execution(shards=3, resume=True))
    assert again.shards_resumed == 0 and len(read_catalog(out).labels) == again.designs
