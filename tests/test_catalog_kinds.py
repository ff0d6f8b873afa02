"""Every kind of catalog carries a verifiable identity: DNA and symmetric catalogs' settings, rows against keys.

verify recomputed the settings of a plain catalog only: a DNA catalog (``enumerate --dna``) or a
symmetric one (``--invariant``) with a count, a rule or the subgroup's summary edited and its
digest computed again read as intact, and so did a one-file catalog whose labels no longer
matched its keys.  Catalogs are written and verified by the command line.
"""

from __future__ import annotations

import json
import shutil

import pyarrow as pa
import pyarrow.parquet as pq
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from lkspace.catalog.metadata import metadata_digest
from tests.cli_calls import one_line_error, run


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    from lkspace.cli import main

    folder = tmp_path_factory.mktemp("kinds")
    for args in (["cube", "--dna", "6"], ["cube", "--labels", "-2..2", "--invariant", "C4"],
                 ["tetrahedron", "--labels", "-1..1"]):  # fmt: skip
        name = {"6": "dna", "C4": "inv", "-1..1": "one"}[args[-1]]
        assert main(["enumerate", *args, "-o", str(folder / f"{name}.parquet")]) == 0
    return folder


VALUES = st.one_of(st.none(), st.booleans(), st.integers(-3, 2**70), st.text(max_size=4), st.just([]), st.just({}))


def fields(meta):
    """The settings of a footer (not its totals or digest), with the entries of ``invariant`` and ``dna``."""
    out = [(k,) for k in meta if k not in ("digest", "rows", "by_components", "assignments_covered")]
    out += [(k, sub) for k in ("invariant", "dna") if isinstance(meta.get(k), dict) for sub in meta[k]]
    return out


@pytest.mark.parametrize("name", ["dna", "inv"])
@settings(max_examples=40, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])  # fmt: skip
@given(data=st.data())
def test_any_setting_of_a_dna_or_symmetric_catalog_edited_and_sealed_again_fails_verify(
    written, tmp_path, capsys, name, data
):
    meta = json.loads(pq.read_metadata(written / f"{name}.parquet").metadata[b"lkspace"])
    path = data.draw(st.sampled_from(fields(meta)), label="field")
    value = data.draw(VALUES, label="value")
    edited = json.loads(json.dumps(meta))
    inner = edited
    for key in path[:-1]:
        inner = inner[key]
    if inner.get(path[-1]) == value or (path == ("shard",) and value is None):
        return  # the same footer
    inner[path[-1]] = value
    edited["digest"] = metadata_digest(edited)
    out = tmp_path / "e.parquet"
    table = pq.read_table(written / f"{name}.parquet")
    pq.write_table(table.replace_schema_metadata({b"lkspace": json.dumps(edited)}), out)
    code, _, err = run(capsys, "verify", out)
    assert code == 1, (path, value)
    one_line_error(err, "e.parquet")


@pytest.mark.parametrize("name", ["dna", "inv"])
def test_a_shard_added_to_a_one_file_kind_fails_verify(written, tmp_path, capsys, name):
    meta = json.loads(pq.read_metadata(written / f"{name}.parquet").metadata[b"lkspace"])
    meta["shard"] = {"index": 0, "count": 1, "plan": "74234e98afe7498f"}
    meta["digest"] = metadata_digest(meta)
    out = tmp_path / "e.parquet"
    pq.write_table(
        pq.read_table(written / f"{name}.parquet").replace_schema_metadata({b"lkspace": json.dumps(meta)}), out
    )
    code, _, err = run(capsys, "verify", out)
    assert code == 1
    one_line_error(err, "e.parquet", "shard")


@pytest.mark.parametrize("how", ["swapped", "zeroed"])
def test_labels_that_are_not_the_rows_keys_fail_verify(written, tmp_path, capsys, how):
    """A file rewritten with its metadata kept and two rows' labels swapped (or one row's zeroed) had verified."""
    table = pq.read_table(written / "one.parquet")
    labels = table.column("labels").to_pylist()
    if how == "swapped":
        labels[3], labels[4] = labels[4], labels[3]
    else:
        labels[5] = [0] * len(labels[5])
    column = pa.array(labels, table.schema.field("labels").type)
    out = tmp_path / "e.parquet"
    shutil.copy(written / "one.parquet", out)
    changed = table.set_column(table.schema.get_field_index("labels"), "labels", column)
    footer = pq.read_metadata(written / "one.parquet").metadata
    pq.write_table(changed.replace_schema_metadata(footer), out, write_page_checksum=True)
    code, _, err = run(capsys, "verify", out)
    assert code == 1
    one_line_error(err, "e.parquet: damaged: a row's labels are not the ones its key holds")


@pytest.mark.parametrize(
    "args, words",
    [
        (
            ["enumerate", "cube", "--dna", "1e308"],
            ["nm per mesh unit", "past label 127", "use a scale of at most 111.6"],
        ),
        (["enumerate", "cube", "--dna", "120"], ["past label 127"]),
        (["enumerate", "cube", "--dna", "6", "--dna-window", "1e308"], ["--dna-window: 1e+308 half turns"]),
        (["solve", "cube", "--components", "2", "--dna", "1e308"], ["past label 127"]),
    ],
)
def test_a_dna_window_past_the_labels_a_catalog_holds_is_one_line(capsys, args, words):
    """``enumerate cube --dna 1e308`` was an internal error: window labels past int8 (an infinite natural twist)."""
    code, _, err = run(capsys, *args)
    assert code == 2
    one_line_error(err, *words)
