"""A catalog's identity holds: edited or stripped metadata, edited manifest totals and foreign parts are found.

Through the real writer and readers (``verify`` and ``enumerate --resume`` as the program).
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys

import pyarrow.parquet as pq
import pytest

import lkspace
from lkspace.catalog.transaction import MANIFEST, file_sha256
from lkspace.errors import CatalogError

TOTAL = 87
"""Designs of the tetrahedron with labels -1..1 up to rotation."""


def lk(*args, cwd):
    """Run ``python -m lkspace ARGS`` in ``cwd``; return ``(code, out, err)``."""
    proc = subprocess.run([sys.executable, "-m", "lkspace", *map(str, args)], capture_output=True, text=True, cwd=cwd,
                          timeout=300)  # fmt: skip
    return proc.returncode, proc.stdout, proc.stderr


def resumed(path):
    """Resume (finish) the sharded catalog ``path`` with the real writer; return what it wrote."""
    from lkspace.design.space import make_space

    space = make_space(lkspace.load("tetrahedron"), "-1..1")
    return lkspace.write_catalog(space, path, execution=lkspace.Execution(shards=3, resume=True))


def enumerate_json(folder, *args):
    """``lkspace enumerate tetrahedron --labels -1..1 ARGS --json`` in ``folder``: the JSON (exit 0 asserted)."""
    code, out, err = lk("enumerate", "tetrahedron", "--labels", "-1..1", *args, "--json", cwd=folder)
    assert code == 0, err
    return json.loads(out)


def footer_of(file):
    return json.loads(pq.read_metadata(file).metadata[b"lkspace"])


def with_footer(file, meta):
    """Write ``file`` again with its rows and the ``lkspace`` metadata ``meta`` (a dict), as another tool would."""
    table = pq.read_table(file)
    pq.write_table(
        table.replace_schema_metadata({b"lkspace": json.dumps(meta).encode()}), file, write_page_checksum=True
    )


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    from lkspace.design.space import make_space

    folder = tmp_path_factory.mktemp("written")
    space = make_space(lkspace.load("tetrahedron"), "-1..1")
    lkspace.write_catalog(space, folder / "one.parquet")
    lkspace.write_catalog(space, folder / "sh.parquet", execution=lkspace.Execution(shards=3))
    lkspace.write_catalog(space, folder / "again.parquet", execution=lkspace.Execution(shards=3))  # another run
    other = make_space(lkspace.load("tetrahedron"), "-1..1", no_zero=True)  # other settings
    lkspace.write_catalog(other, folder / "other.parquet", execution=lkspace.Execution(shards=3))
    return folder


def test_a_one_file_catalog_whose_metadata_lost_its_digest_is_not_intact(written, tmp_path):
    one = tmp_path / "one.parquet"
    shutil.copy(written / "one.parquet", one)
    meta = footer_of(one)
    edited = {k: v for k, v in meta.items() if k != "digest"}
    edited["by_components"] = {"1": TOTAL}
    with_footer(one, edited)
    code, out, err = lk("verify", one, cwd=tmp_path)
    assert code == 1 and out == "" and "intact" not in err
    assert err.count("\n") == 1 and "has no digest" in err and "not verified" in err, err
    code, _, err = lk("export", one, "--row", 1, "-o", tmp_path / "r.obj", cwd=tmp_path)  # read, with a warning
    assert code == 0 and err.startswith("lkspace: warning: ") and "has no digest" in err


@pytest.mark.parametrize("key", ["digest", "shard", "by_components", "rows", "label_set", "symmetry", "scaffold",
                                 "assignments_covered", "filters", "group_order", "canonical_rule"])  # fmt: skip
@pytest.mark.parametrize("how", ["removed", "changed", "removed with the digest", "changed with the digest"])
def test_every_metadata_edit_of_a_one_file_catalog_is_found_by_verify(written, tmp_path, key, how):
    one = tmp_path / "one.parquet"
    shutil.copy(written / "one.parquet", one)
    meta = footer_of(one)
    if "removed" in how:
        meta.pop(key)
    else:
        meta[key] = {"changed": True} if not isinstance(meta[key], int) else meta[key] + 1
    if "with the digest" in how:
        meta.pop("digest", None)
    with_footer(one, meta)
    with pytest.raises(CatalogError, match="one.parquet"):
        lkspace.verify_catalog(one)


def edit_manifest(folder, edit):
    """Apply ``edit(manifest)`` to the manifest of the catalog ``folder`` (JSON, written back)."""
    manifest = json.loads((folder / MANIFEST).read_text())
    edit(manifest)
    (folder / MANIFEST).write_text(json.dumps(manifest, indent=1))


@pytest.mark.parametrize(
    "edit",
    [
        lambda m: m["parts"]["0"]["by_components"].update({"1": m["parts"]["0"]["by_components"]["1"] + 1000}),
        lambda m: m["parts"]["1"].update(by_components={"1": m["parts"]["1"]["rows"]}),
        lambda m: m["parts"]["2"].update(assignments_covered=m["parts"]["2"]["assignments_covered"] * 2),
        lambda m: m["parts"]["0"].update(rows=m["parts"]["0"]["rows"] + 5),
    ],
)
def test_edited_manifest_totals_fail_verify_and_are_not_resumed(written, tmp_path, edit):
    sharded = tmp_path / "sh.parquet"
    shutil.copytree(written / "sh.parquet", sharded)
    truth = lkspace.read_catalog(sharded).frame.components.value_counts().to_dict()
    edit_manifest(sharded, edit)
    with pytest.raises(CatalogError, match="the manifest"):
        lkspace.verify_catalog(sharded)
    done = resumed(sharded)
    assert done.designs == TOTAL and done.shards_resumed == 2  # the part with edited totals: written again
    assert done.by_components == truth
    lkspace.verify_catalog(sharded)


def test_edited_manifest_totals_as_the_program_sees_them(written, tmp_path):
    sharded = tmp_path / "sh.parquet"
    shutil.copytree(written / "sh.parquet", sharded)
    edit_manifest(sharded, lambda m: m["parts"]["0"]["by_components"].update({"1": 1000}))
    code, out, err = lk("verify", sharded, cwd=tmp_path)
    assert code == 1 and "intact" not in out
    assert err.count("\n") == 1 and "the manifest's totals of part 0" in err, err
    done = enumerate_json(tmp_path, "--shards", "3", "-o", "sh.parquet", "--resume")
    assert done["designs"] == TOTAL and done["shards_resumed"] == 2 and "1000" not in json.dumps(done)


@pytest.mark.parametrize("donor", ["again.parquet", "other.parquet"])
@pytest.mark.parametrize("where", ["finished", "build"])
def test_a_foreign_part_is_not_resumed_even_with_its_checksum_in_the_manifest(written, tmp_path, donor, where):
    """Part 1 of another run (same settings) or of other settings, its SHA-256 written into the manifest."""
    sharded = tmp_path / ("sh.parquet" if where == "finished" else ".sh.parquet.lkspace-build")
    shutil.copytree(written / "sh.parquet", sharded)
    manifest = json.loads((sharded / MANIFEST).read_text())
    name = manifest["parts"]["1"]["file"]
    foreign = next(p for p in sorted((written / donor).glob("part-00001-*.parquet")))
    shutil.copy(foreign, sharded / name)
    theirs = footer_of(sharded / name)

    def forge(m):
        m["parts"]["1"].update(
            sha256=file_sha256(str(sharded / name)), rows=theirs["rows"], by_components=theirs["by_components"],
            assignments_covered=theirs["assignments_covered"],
        )  # fmt: skip
        if where == "build":
            m.pop("complete")

    edit_manifest(sharded, forge)
    if where == "finished":
        with pytest.raises(CatalogError, match="another catalog"):
            lkspace.verify_catalog(sharded)
    if donor == "other.parquet" and where == "build":  # once as the program
        done = enumerate_json(tmp_path, "--shards", "3", "-o", "sh.parquet", "--resume")
        assert done["designs"] == TOTAL and done["shards_resumed"] == 2
    else:
        written_again = resumed(tmp_path / "sh.parquet")
        assert written_again.designs == TOTAL and written_again.shards_resumed == 2
    assert lkspace.verify_catalog(tmp_path / "sh.parquet").rows == TOTAL


def manifest_edits():
    """One edit of each setting a manifest records beside its parts (every key but the parts' list)."""
    return [
        ("assignments", lambda m: m.update(assignments=m["assignments"] + 1)),  # a summary count
        ("group_order", lambda m: m.update(group_order=2 * m["group_order"])),
        ("acting_order", lambda m: m.update(acting_order=m["acting_order"] // 2)),
        ("symmetry_tolerance", lambda m: m.update(symmetry_tolerance=0.5)),
        ("canonical_rule", lambda m: m.update(canonical_rule="smallest first")),
        ("label_set", lambda m: m.update(label_set=[-2, 0, 2])),
        ("symmetry", lambda m: m.update(symmetry="none")),
        ("filters", lambda m: m["filters"].update(no_zero=True)),
        ("sample", lambda m: m.update(sample=5)),
        ("plan", lambda m: m.update(plan="0" * 16)),
        ("scaffold", lambda m: m["scaffold"].update(name="cube")),
        ("identify", lambda m: m.update(identify=True)),
    ]


@pytest.mark.parametrize(("key", "edit"), manifest_edits(), ids=[k for k, _ in manifest_edits()])
def test_every_edited_manifest_setting_fails_verify(written, tmp_path, key, edit):
    """Issue 35: a manifest's ``assignments`` (a summary count), group orders or canonical rule edited: 'intact'."""
    sharded = tmp_path / "sh.parquet"
    shutil.copytree(written / "sh.parquet", sharded)
    edit_manifest(sharded, edit)
    words = "not identified" if key == "identify" else "another catalog"
    with pytest.raises(CatalogError, match=words):
        lkspace.verify_catalog(sharded)
    if key != "identify":  # read_catalog reads a folder being identified: verify is the judge of that setting
        with pytest.raises(CatalogError, match=words):
            lkspace.read_catalog(sharded)
