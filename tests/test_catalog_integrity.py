"""Catalogs that cannot lie: every reader refuses a damaged, swapped, foreign, missing or extra part.

Catalogs are written by the real writer (``lkspace enumerate ... -o``), damaged on disk
as a user or a file system might, and read by the real readers: ``export --row``,
``verify``, ``atlas CATALOG``, ``read_catalog`` and the studio's browser.  Each refusal is
one line naming the file, with exit status 1; an intact catalog reads as pyarrow reads it.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import lkspace
from lkspace.errors import CatalogError, LkspaceWarning
from lkspace.studio.browse import Browser
from tests.cli_calls import one_line_error, run

ROW_IN_PART_1 = 400
"""A row of part 1 of the three-part catalog (part 0 holds 357 rows)."""


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    """Two three-part catalogs of the same space (two runs) and a one-file catalog, by the CLI."""
    folder = tmp_path_factory.mktemp("written")
    for name in ("a", "b"):
        code = lkspace.cli.main(["enumerate", "tetrahedron", "--labels", "-2..2", "--shards", "3",
                                 "-o", str(folder / f"{name}.parquet"), "--json"])  # fmt: skip
        assert code == 0
    assert lkspace.cli.main(["enumerate", "tetrahedron", "--labels", "-1..1", "-o", str(folder / "one.parquet")]) == 0
    return folder


@pytest.fixture
def cat(written, tmp_path):
    """A fresh copy of the three-part catalog ``a`` to damage."""
    return shutil.copytree(written / "a.parquet", tmp_path / "cat.parquet")


def parts(folder):
    return sorted(p for p in os.listdir(folder) if p.endswith(".parquet"))


def pyarrow_labels(path):
    """Labels of every row decoded from the ``key`` column with plain pyarrow (files in name order)."""
    files = [os.path.join(path, p) for p in parts(path)] if os.path.isdir(path) else [path]
    keys = [pq.read_table(f, columns=["key"]).column("key").combine_chunks() for f in files]
    return np.concatenate([np.frombuffer(k.buffers()[1], np.int8).reshape(len(k), -1) for k in keys])


def flip_key_bytes(file):
    """Flip a byte in the middle of the ``key`` column's data of the first row group."""
    meta = pq.read_metadata(file).row_group(0)
    column = next(meta.column(i) for i in range(meta.num_columns) if meta.column(i).path_in_schema == "key")
    start = column.dictionary_page_offset if column.has_dictionary_page else column.data_page_offset
    at = start + column.total_compressed_size * 2 // 3
    data = bytearray(file.read_bytes())
    data[at] ^= 0xFF
    file.write_bytes(bytes(data))


def refused_everywhere(capsys, tmp_path, catalog, *words, row=ROW_IN_PART_1):
    """Assert that export --row, verify, atlas and read_catalog refuse ``catalog`` with one line."""
    out = tmp_path / "x.obj"
    for args in (["export", catalog, "--row", row, "-o", out], ["verify", catalog], ["atlas", catalog]):
        code, _, err = run(capsys, *args)
        assert code == 1, (args, err)
        one_line_error(err, *words)
    assert not out.exists()
    with pytest.raises(CatalogError) as caught:
        lkspace.read_catalog(catalog)
    for word in words:
        assert word in str(caught.value)


def test_intact_catalog_reads_as_pyarrow_reads_it(written, capsys, tmp_path):
    path = written / "a.parquet"
    assert np.array_equal(lkspace.read_catalog(path).labels, pyarrow_labels(path))
    code, out, _ = run(capsys, "verify", path, "--json")
    assert code == 0 and json.loads(out)["rows"] == 1475 and json.loads(out)["parts"] == 3
    code, out, _ = run(capsys, "export", path, "--row", ROW_IN_PART_1, "-o", tmp_path / "x.obj", "--json")
    assert code == 0 and json.loads(out)["labels"] == pyarrow_labels(path)[ROW_IN_PART_1].tolist()
    one = written / "one.parquet"
    assert run(capsys, "verify", one)[0] == 0
    assert np.array_equal(lkspace.read_catalog(one).labels, pyarrow_labels(one))


def test_swapped_parts(cat, capsys, tmp_path):
    first, second = (cat / p for p in parts(cat)[:2])
    first.rename(tmp_path / "tmp")
    second.rename(first)
    (tmp_path / "tmp").rename(second)
    refused_everywhere(capsys, tmp_path, cat, first.name, "swapped")
    code, _, err = run(capsys, "identify", cat, "--row", ROW_IN_PART_1)
    assert code == 1
    one_line_error(err, first.name, "swapped")


def test_part_of_another_catalog(cat, written, capsys, tmp_path):
    mine, theirs = parts(cat)[1], parts(written / "b.parquet")[1]
    shutil.copy(written / "b.parquet" / theirs, cat / mine)  # same space, same part number, another run
    refused_everywhere(capsys, tmp_path, cat, mine, "another catalog")


def test_truncated_part(cat, capsys, tmp_path):
    victim = cat / parts(cat)[2]
    data = victim.read_bytes()
    victim.write_bytes(data[: len(data) // 2])
    refused_everywhere(capsys, tmp_path, cat, victim.name, "truncated")


def test_flipped_bytes(cat, capsys, tmp_path):
    victim = cat / parts(cat)[1]
    flip_key_bytes(victim)
    refused_everywhere(capsys, tmp_path, cat, victim.name, "damaged", "SHA-256")
    browser = Browser(str(cat))  # the structure is intact: the browser finds the flip as it reads
    assert browser.wait(60)
    assert victim.name in browser.info()["error"] and "SHA-256" in browser.info()["error"]
    with pytest.raises(CatalogError, match="SHA-256"):
        browser.query()


def test_missing_part(cat, capsys, tmp_path):
    victim = cat / parts(cat)[1]
    victim.unlink()
    refused_everywhere(capsys, tmp_path, cat, victim.name, "missing")
    with pytest.raises(CatalogError, match="missing"):
        Browser(str(cat))
    studio = [sys.executable, "-m", "lkspace", "studio", str(cat), "--no-browser", "--port", "0"]
    done = subprocess.run(studio, capture_output=True, text=True, timeout=120)  # refused before serving
    assert done.returncode == 1
    one_line_error(done.stderr, victim.name, "missing")


def test_extra_part(cat, written, capsys, tmp_path):
    shutil.copy(written / "b.parquet" / parts(written / "b.parquet")[0], cat / "more.parquet")
    refused_everywhere(capsys, tmp_path, cat, "more.parquet", "not a part of this catalog")


@pytest.mark.parametrize(
    "change, words",
    [
        (lambda m: {**m, "format_version": 99}, ["format_version 99"]),
        (lambda m: {**m, "parts": {k: {**v, "rows": v["rows"] + 1} for k, v in m["parts"].items()}}, ["manifest says"]),
        (lambda m: "{not json", ["not valid JSON"]),
        (lambda m: [1, 2], ["not a JSON object"]),
        (lambda m: {**m, "parts": {"0": m["parts"]["0"]}}, ["unfinished"]),
        (lambda m: {**m, "parts": {k: {**v, "file": "../x.parquet"} for k, v in m["parts"].items()}}, ["malformed"]),
        (lambda m: "[" * 100_000, ["not valid JSON"]),  # was an internal error (RecursionError)
    ],
)
def test_altered_manifest(cat, capsys, tmp_path, change, words):
    manifest = cat / "_lkspace.json"
    new = change(json.loads(manifest.read_text()))
    manifest.write_text(new if isinstance(new, str) else json.dumps(new))
    refused_everywhere(capsys, tmp_path, cat, *words)


def test_missing_manifest(cat, capsys, tmp_path):
    (cat / "_lkspace.json").unlink()
    refused_everywhere(capsys, tmp_path, cat, "no manifest")


def rewrite_footer(file, meta):
    """Write ``file`` again with its rows and the ``lkspace`` metadata ``meta`` (bytes)."""
    table = pq.read_table(file)
    pq.write_table(table.replace_schema_metadata({b"lkspace": meta}), file)


@pytest.mark.parametrize(
    "meta, words",
    [
        (b"\xff\xfe garbage", ["not valid JSON"]),
        (b'"a string"', ["not a JSON object"]),
        (b'{"format_version": 2, "scaffold": {}, "label_set": []}', ["format_version 2"]),
        (b'{"format_version": 1, "scaffold": "cube", "label_set": []}', ["no scaffold"]),
        (b"[" * 100_000, ["not valid JSON"]),  # was an internal error (RecursionError)
    ],
)
def test_garbage_metadata_of_a_part(cat, capsys, tmp_path, meta, words):
    victim = cat / parts(cat)[0]
    rewrite_footer(victim, meta)
    refused_everywhere(capsys, tmp_path, cat, victim.name, *words)


def test_one_file_catalog_truncated_flipped_or_foreign(written, capsys, tmp_path):
    one = tmp_path / "one.parquet"
    data = (written / "one.parquet").read_bytes()
    one.write_bytes(data[:-100])
    refused_everywhere(capsys, tmp_path, one, "truncated", row=3)
    one.write_bytes(data)
    flip_key_bytes(one)  # no manifest: the page checksums find it
    refused_everywhere(capsys, tmp_path, one, "damaged", row=3)
    one.write_bytes(data)
    rewrite_footer(one, b"{'lkspace': 1}")
    refused_everywhere(capsys, tmp_path, one, "not valid JSON", row=3)
    shutil.copy(written / "a.parquet" / parts(written / "a.parquet")[1], one)  # a part taken out of its folder
    refused_everywhere(capsys, tmp_path, one, "not a whole catalog", row=3)


def test_footer_rows_must_match_the_file(written, tmp_path, capsys):
    one = tmp_path / "one.parquet"
    shutil.copy(written / "one.parquet", one)
    meta = json.loads(pq.read_metadata(one).metadata[b"lkspace"])
    table = pq.read_table(one).slice(0, 10)  # rows cut, metadata kept: a file that lies about its size
    pq.write_table(table.replace_schema_metadata({b"lkspace": json.dumps(meta).encode()}), one)
    refused_everywhere(capsys, tmp_path, one, "87 rows", row=3)


def test_parts_name_their_run_index_and_count(written):
    folder = written / "a.parquet"
    manifest = json.loads((folder / "_lkspace.json").read_text())
    for i, name in enumerate(parts(folder)):
        shard = json.loads(pq.read_schema(folder / name).metadata[b"lkspace"])["shard"]
        assert (shard["index"], shard["count"], shard["run"]) == (i, 3, manifest["run"])
        assert pq.ParquetFile(folder / name).metadata.num_rows == manifest["parts"][str(i)]["rows"]


def test_resume_keeps_the_run_id_its_parts_name(written, tmp_path, capsys):
    out = tmp_path / "a.parquet"
    shutil.copytree(written / "a.parquet", out)
    flip_key_bytes(out / parts(out)[2])
    code, _, _ = run(capsys, "enumerate", "tetrahedron", "--labels", "-2..2", "--shards", "3", "-o", out, "--resume")
    assert code == 0
    assert run(capsys, "verify", out)[0] == 0  # the redone part names the same run as the two kept
    assert np.array_equal(lkspace.read_catalog(out).labels, pyarrow_labels(written / "a.parquet"))


def test_verify_on_a_plain_parquet_file(tmp_path, capsys):
    plain = tmp_path / "plain.parquet"
    pq.write_table(pa.table({"a": [1]}), plain)
    code, _, err = run(capsys, "verify", plain)
    assert code == 1
    one_line_error(err, "not an lkspace catalog")


@settings(max_examples=40, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])  # fmt: skip
@given(part=st.integers(0, 2), where=st.floats(0, 1, exclude_max=True), bit=st.integers(0, 7), cut=st.booleans())
def test_any_flipped_bit_or_cut_of_a_part_is_refused(written, tmp_path, part, where, bit, cut):
    """Property: one changed bit anywhere in a part (or a part cut short there) never reads."""
    cat = tmp_path / f"{part}-{where}-{bit}-{cut}.parquet"
    shutil.copytree(written / "a.parquet", cat)
    victim = cat / parts(cat)[part]
    data = bytearray(victim.read_bytes())
    at = int(where * len(data))
    if cut:
        del data[at:]
    else:
        data[at] ^= 1 << bit
    victim.write_bytes(bytes(data))
    with pytest.raises(CatalogError, match=victim.name):
        lkspace.read_catalog(cat)
    with pytest.raises(CatalogError, match=victim.name):
        lkspace.verify_catalog(cat)


@settings(max_examples=40, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])  # fmt: skip
@given(where=st.floats(0, 1, exclude_max=True), bit=st.integers(0, 7))
def test_a_flipped_bit_of_a_one_file_catalog_never_reads_as_other_rows(written, tmp_path, where, bit):
    """Property: without a manifest, a changed bit is refused or changes nothing that is read."""
    one = tmp_path / f"{where}-{bit}.parquet"
    data = bytearray((written / "one.parquet").read_bytes())
    data[int(where * len(data))] ^= 1 << bit
    one.write_bytes(bytes(data))
    original = lkspace.read_catalog(written / "one.parquet")
    try:
        cat = lkspace.read_catalog(one)
    except CatalogError as exc:
        refusal = str(exc)
    else:
        refusal = None
    if refusal is not None:
        assert one.name in refusal
        return
    assert np.array_equal(cat.labels, original.labels)
    assert cat.frame.equals(original.frame)


@pytest.mark.parametrize(
    "edit, words",
    [
        (lambda m: {**m, "scaffold": {**m["scaffold"], "data": [1, 2]}}, ["scaffold in its 'lkspace' metadata"]),
        (lambda m: {**m, "scaffold": {"name": 5, "edges": 6}}, ["scaffold in its 'lkspace' metadata"]),
        (lambda m: {**m, "scaffold": {**m["scaffold"], "edges": "6"}}, ["no usable scaffold edges"]),
        (lambda m: {**m, "scaffold": {**m["scaffold"], "content_hash": "0"}}, ["differs from the one"]),
        (lambda m: {**m, "rows": 86}, ["says 86 rows"]),
        (lambda m: {**m, "label_set": [-1, 0, 2]}, ["digest"]),  # edited, digest kept
    ],
)
def test_edited_metadata_of_a_one_file_catalog(written, tmp_path, capsys, edit, words):
    one = tmp_path / "one.parquet"
    meta = json.loads(pq.read_metadata(written / "one.parquet").metadata[b"lkspace"])
    changed = edit(meta)
    if "digest" not in words:  # edited and sealed again: the checks behind the digest find it
        from lkspace.catalog.metadata import metadata_digest

        changed["digest"] = metadata_digest(changed)
    shutil.copy(written / "one.parquet", one)
    rewrite_footer(one, json.dumps(changed).encode())
    code, _, err = run(capsys, "export", one, "--row", 3, "-o", tmp_path / "x.obj")
    assert code == 1
    one_line_error(err, one.name, *words)


JSON_VALUES = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(-(2**70), 2**70),
    st.floats(allow_nan=False),
    st.text(max_size=8),
    st.lists(st.integers(-3, 3), max_size=3),
    st.dictionaries(st.sampled_from(["a", "1", "name"]), st.integers(0, 3), max_size=2),
)
"""A JSON value of every kind, put in place of a field of the ``lkspace`` metadata or a manifest."""

REMOVED = object()
"""Stands for a field removed instead of changed."""


def fields(data, path=()):
    """Every field of the JSON object ``data`` as a key path (a list's first two items too; a scaffold's geometry: its keys)."""
    out = []
    for key, value in data.items():
        here = (*path, key)
        out.append(here)
        if isinstance(value, dict):
            out += fields(value, here)
        elif isinstance(value, list) and path[-1:] != ("data",):
            out += [(*here, i) for i in range(min(2, len(value)))]
    return out


def edited(data, path, value):
    """A copy of the JSON ``data`` with the field at ``path`` set to ``value`` (or removed: :data:`REMOVED`)."""
    data = json.loads(json.dumps(data))
    inner = data
    for key in path[:-1]:
        inner = inner[key]
    if value is REMOVED:
        del inner[path[-1]]
    else:
        inner[path[-1]] = value
    return data


ONE_FILE_META = ("format_version", "scaffold", "label_set", "symmetry", "group_order", "acting_order", "assignments",
                 "mode", "filters", "sample", "seed", "canonical_rule", "by_components", "assignments_covered", "rows",
                 "shard", "symmetry_tolerance")  # fmt: skip
"""The fields of a one-file catalog's metadata that verify checks against its scaffold and rows.

The shard's plan (a fingerprint of the walk) is computed again, and a footer with a digest
must record ``symmetry_tolerance`` (every lkspace that sealed footers recorded it; its
removal had verified, issue 35).  Left out by the test: a ``max_designs`` the rows stay
under, a tolerance that gives the same group (both the same catalog).
"""


def same_catalog(path, value):
    """Whether the edit of ``path`` to ``value`` describes the same catalog (a limit not reached, the same group)."""
    if path == ("filters", "max_designs"):
        return isinstance(value, int) and not isinstance(value, bool) and value >= 87
    if path == ("symmetry_tolerance",) and isinstance(value, float):
        from lkspace.design.space import make_space

        try:
            return make_space(lkspace.load("tetrahedron"), "-1..1", tolerance=value).group_order == 12
        except lkspace.LkspaceError:
            return False
    return False


@settings(max_examples=150, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])  # fmt: skip
@given(data=st.data())
def test_any_field_of_a_one_file_catalog_changed_and_sealed_again_is_refused_by_verify(written, tmp_path, capsys, data):
    """Property: a setting, count or the scaffold changed (the digest computed again) never verifies as intact."""
    from lkspace.catalog.metadata import metadata_digest

    meta = json.loads(pq.read_metadata(written / "one.parquet").metadata[b"lkspace"])
    path = data.draw(st.sampled_from([p for p in fields(meta) if p[0] in ONE_FILE_META]), label="field")
    value = data.draw(st.one_of(st.just(REMOVED), JSON_VALUES), label="value")
    changed = edited(meta, path, value)
    if changed == meta or same_catalog(path, value):
        return
    changed["digest"] = metadata_digest(changed)
    one = tmp_path / "one.parquet"
    pq.write_table(
        pq.read_table(written / "one.parquet").replace_schema_metadata({b"lkspace": json.dumps(changed)}), one
    )
    code, _, err = run(capsys, "verify", one)
    assert code == 1, (path, value)
    one_line_error(err, one.name)


@pytest.mark.parametrize(
    "edit, words",
    [
        (lambda m: m["shard"].update(plan="0" * 16), ["recorded plan '0000000000000000'"]),
        (lambda m: m["shard"].update(plan=""), ["recorded plan ''"]),
        (lambda m: m.pop("shard"), ["has no shard"]),
        (lambda m: m.pop("symmetry_tolerance"), ["has a digest but no symmetry_tolerance"]),
    ],
    ids=["plan", "empty-plan", "no-shard", "no-tolerance"],
)
def test_a_one_file_catalogs_plan_and_tolerance_sealed_again_are_checked(written, tmp_path, capsys, edit, words):
    """The plan edited or the shard or tolerance removed, the digest computed again: verify had said intact."""
    from lkspace.catalog.metadata import metadata_digest

    meta = json.loads(pq.read_metadata(written / "one.parquet").metadata[b"lkspace"])
    edit(meta)
    meta["digest"] = metadata_digest(meta)
    one = tmp_path / "one.parquet"
    pq.write_table(pq.read_table(written / "one.parquet").replace_schema_metadata({b"lkspace": json.dumps(meta)}), one)
    code, out, err = run(capsys, "verify", one)
    assert code == 1, out
    one_line_error(err, one.name, *words)


def test_a_footer_without_digest_or_tolerance_reads_as_an_older_catalog(written, tmp_path):
    """A catalog written before the tolerance was recorded has no digest either: it reads (with a warning)."""
    meta = json.loads(pq.read_metadata(written / "one.parquet").metadata[b"lkspace"])
    old = {k: v for k, v in meta.items() if k not in ("digest", "symmetry_tolerance")}
    one = tmp_path / "one.parquet"
    pq.write_table(pq.read_table(written / "one.parquet").replace_schema_metadata({b"lkspace": json.dumps(old)}), one)
    with pytest.warns(LkspaceWarning, match="has no digest"):
        assert len(lkspace.read_catalog(one)) == 87


@settings(max_examples=150, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])  # fmt: skip
@given(data=st.data())
def test_any_field_of_a_manifest_changed_or_removed_is_refused(written, tmp_path, capsys, data):
    """Property: a manifest with any field changed to any JSON value, or removed, never verifies or reads.

    (A malformed SHA-256 of part 0 was read as intact by ``export --row`` of a row in part 1.)
    """
    manifest = json.loads((written / "a.parquet" / "_lkspace.json").read_text())
    path = data.draw(st.sampled_from(fields(manifest)), label="field")
    value = data.draw(st.one_of(st.just(REMOVED), JSON_VALUES), label="value")
    changed = edited(manifest, path, value)
    if changed == manifest:
        return
    cat = tmp_path / "cat.parquet"
    shutil.rmtree(cat, ignore_errors=True)
    shutil.copytree(written / "a.parquet", cat)
    (cat / "_lkspace.json").write_text(json.dumps(changed))
    code, _, err = run(capsys, "verify", cat)
    assert code == 1, (path, value)
    one_line_error(err, "cat.parquet")
    if path != ("identify",):  # a manifest saying every part is identified is verify's to check
        with pytest.raises(CatalogError):
            lkspace.read_catalog(cat)
        code, _, err = run(capsys, "export", cat, "--row", ROW_IN_PART_1, "-o", tmp_path / "x.obj")
        assert code == 1, (path, value)
        assert not (tmp_path / "x.obj").exists()


@pytest.mark.parametrize(
    "put, words",
    [
        (lambda p: p.mkdir(), ["not a regular file (a folder)"]),  # was called "a FIFO, socket or device"
        (lambda p: os.mkfifo(p), ["not a regular file (a FIFO)"]),
        (lambda p: p.symlink_to(p.parent / "nowhere.bin"), ["a symbolic link to", "does not exist"]),  # said only
        (lambda p: p.symlink_to(p), ["cannot read", "symbolic links"]),  # "No such file or directory"
        (lambda p: p.write_bytes(b""), ["damaged or not Parquet"]),
    ],
    ids=["folder", "fifo", "dangling-link", "link-loop", "empty"],
)
def test_something_else_in_place_of_a_part(cat, capsys, tmp_path, put, words):
    """A part replaced by a folder, a FIFO, a link to nothing, a loop of links or an empty file: one line saying which."""
    victim = cat / parts(cat)[1]
    victim.unlink()
    put(victim)
    refused_everywhere(capsys, tmp_path, cat, victim.name, *words)
