"""The public API: one way in for every stage, each taking a scaffold, a path or a name."""

import json
import os
import re
import subprocess
import sys

import networkx as nx
import numpy as np
import pytest

import lkspace
from lkspace.cli import main


@pytest.fixture(scope="module")
def sources(tmp_path_factory):
    """The tetrahedron as a Scaffold, as an OBJ path and as a built-in name."""
    path = tmp_path_factory.mktemp("api") / "tetra.obj"
    from lkspace import io

    io.write(lkspace.load("tetrahedron"), path)
    return [lkspace.load("tetrahedron"), path, str(path), "tetrahedron"]


def test_every_function_takes_a_scaffold_a_path_or_a_name(sources, tmp_path):
    for source in sources:
        assert lkspace.load(source).n_edges == 6
        assert lkspace.trace(source, 1).components == 3
        assert len(pd_concat(lkspace.designs(source, "-2,2"))) == 12
        assert lkspace.count_designs(source, "-2,2").designs == 12
        assert lkspace.solve(source, 1, no_zero=True).solutions[0].components == 1
        assert lkspace.realize(source, 1).n_curves == 3
        assert lkspace.export(source, tmp_path / "t.ply", 1) == "ply"
        written = lkspace.write_catalog(source, tmp_path / "t.parquet", "-2,2")
        assert written.designs == 12 and len(lkspace.read_catalog(tmp_path / "t.parquet")) == 12


def test_paths_and_names_are_loaded_at_the_boundary():
    import inspect

    from lkspace import api
    from lkspace.strands import tracing

    assert lkspace.trace.__wrapped__ is tracing.trace
    assert lkspace.trace(scaffold="cube", labels=1).components == 4  # the first argument by keyword too
    for name in lkspace.__all__:
        value = getattr(lkspace, name)
        if not inspect.isfunction(value) or name == "load":
            continue
        first = next(iter(inspect.signature(value).parameters.values()))
        assert ("Scaffold" in str(first.annotation)) == (name in api.SCAFFOLD_FIRST), name
        if name in api.SCAFFOLD_FIRST:
            inner = next(iter(inspect.signature(value.__wrapped__).parameters.values()))
            assert "ScaffoldSource" in first.annotation and "ScaffoldSource" not in inner.annotation, name
            assert value.__doc__ == value.__wrapped__.__doc__ and value.__name__ == name


def test_write_catalog_never_writes_over_its_scaffold_file(tmp_path):
    path = tmp_path / "t.json"
    lkspace.io.write(lkspace.load("tetrahedron"), path)
    before = path.read_bytes()
    with pytest.raises(lkspace.LkspaceError, match="is the input"):
        lkspace.write_catalog(path, path, "-1,1")
    assert path.read_bytes() == before


def pd_concat(frames):
    import pandas as pd

    return pd.concat(list(frames))


def test_identify_takes_a_name():
    pytest.importorskip("snappy")
    result = lkspace.identify("tetrahedron", 1)
    assert (result.name, result.components) == ("L6a4", 3)
    assert result.to_dict()["name"] == "L6a4"


def test_reprs_are_short():
    scaffold = lkspace.load("honeycomb:cP@4x4x4")
    results = [
        scaffold,
        scaffold.lattice,
        lkspace.trace(scaffold, 1),
        lkspace.realize("tetrahedron", 1),
        lkspace.solve("cube", 1),
        lkspace.solve("cube", 1).solutions[0],
        lkspace.count_designs("cube", "-1..1"),
    ]
    for value in results:
        assert len(repr(value)) < 200, repr(value)
    assert repr(lkspace.trace("cube", 1)) == "Trace(cube: 4 components, holds together, lengths [6, 6, 6, 6])"


def test_enumerate_is_a_deprecated_alias_and_star_import_keeps_the_builtin():
    with pytest.warns(DeprecationWarning, match="lkspace.designs"):
        frames = lkspace.enumerate("tetrahedron", "-2,2")
    assert len(pd_concat(frames)) == 12
    assert "enumerate" not in lkspace.__all__
    namespace: dict = {}
    exec("from lkspace import *", namespace)
    assert "enumerate" not in namespace and "trace" in namespace
    with pytest.raises(AttributeError):
        lkspace.no_such_name  # noqa: B018
    assert lkspace.io.read is lkspace.io.files.read and "builtin" in dir(lkspace.scaffolds)


def test_import_loads_no_heavy_library():
    code = (
        "import sys, lkspace; lkspace.trace('tetrahedron', 1).to_dict();"
        "print(sorted(m for m in ('numba', 'scipy', 'pyarrow', 'pandas', 'ortools', 'igraph', 'matplotlib')"
        " if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_read_catalog_of_what_enumerate_writes(tmp_path, capsys):
    for name, shards in (("one.parquet", []), ("parts", ["--shards", "3"])):
        out = tmp_path / name
        assert main(["enumerate", "cube", "--labels", "-1..1", "-o", str(out), *shards]) == 0
        capsys.readouterr()
        catalog = lkspace.read_catalog(out)
        assert catalog.labels.shape == (22815, 12) and catalog.labels.dtype == np.int8
        assert int(catalog.frame.orbit_size.sum()) == 3**12
        assert catalog.metadata["label_set"] == [-1, 0, 1] and catalog.scaffold.name == "cube"
        one = catalog[catalog.frame.components == 1]
        assert len(one) == 8800 == int((catalog.frame.components == 1).sum())
        for row in (0, len(one) // 2, len(one) - 1):
            trace = one.trace(row)
            assert trace.components == 1 and np.array_equal(trace.labels, one.labels[row])
        import pyarrow.parquet as pq

        part = out if out.is_file() else sorted(out.glob("part-*.parquet"))[0]
        schema_meta = json.loads(pq.read_schema(part).metadata[b"lkspace"])
        assert schema_meta["label_set"] == [-1, 0, 1] and schema_meta["scaffold"]["name"] == "cube"


def test_read_catalog_columns_and_residue_mode(tmp_path, capsys):
    out = tmp_path / "r.parquet"
    assert main(["enumerate", "tetrahedron", "--labels", "-1..1", "--mode", "residues", "-o", str(out)]) == 0
    capsys.readouterr()
    catalog = lkspace.read_catalog(out, columns=["components"])
    assert list(catalog.frame.columns) == ["components"] and catalog.labels.shape == (len(catalog), 6)
    with pytest.raises(lkspace.CatalogError, match="no column"):
        lkspace.read_catalog(out, columns=["nope"])


def test_networkx_views():
    dual = lkspace.load("cube").dual_graph()
    assert isinstance(dual, nx.MultiGraph) and nx.is_connected(dual)
    assert sorted(d for _, d in dual.degree()) == [4] * 6
    assert {data["edge"] for *_, data in dual.edges(data=True)} == set(range(12))
    together = lkspace.trace("cube", 2)
    assert nx.is_connected(together.winding_graph()) == together.holds_together
    apart = lkspace.trace("cube", 0)
    assert apart.winding_graph().number_of_edges() == 0 and not apart.holds_together


def test_info_lists_edges_as_twist_files_name_them(capsys):
    assert main(["info", "cube", "--edges", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["n_edges"] == 12 == len(data["edges"])
    first = data["edges"][0]
    assert (first["index"], first["a"], first["b"], first["a_obj"], first["b_obj"], first["degree"]) == (
        0,
        0,
        1,
        1,
        2,
        2,
    )
    assert main(["info", "honeycomb:cP", "--edges", "--json"]) == 0
    edges = json.loads(capsys.readouterr().out)["edges"]
    assert [e["offset"] for e in edges] == [[1, 0, 0], [0, 1, 0], [0, 0, 1]]


def test_labels_and_label_set_words_in_json(capsys):
    assert main(["trace", "tetrahedron", "--twist", "1", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["labels"] == [1] * 6
    assert main(["enumerate", "tetrahedron", "--label-set", "-2,2", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["label_set"] == [-2, 2] and data["designs"] == 12
    assert main(["solve", "tetrahedron", "-n", "1", "--labels", "-1..1", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["label_set"] == [-1, 0, 1] and len(data["solutions"][0]["labels"]) == 6


@pytest.mark.parametrize(
    "fields, words",
    [
        ({"components": 0}, "components: must be an integer of at least 1, got 0"),
        ({"max_designs": -3}, "max_designs: must be an integer of at least 1, got -3"),  # had written every row
        ({"sample": 0, "mode": "spanning-trees"}, "sample: must be an integer of at least 1"),
        ({"seed": -1, "sample": 3, "mode": "spanning-trees"}, "seed: must be an integer of at least 0"),  # ValueError
        ({"mode": "bogus"}, "mode 'bogus': use one of designs, residues, spanning-trees"),  # had walked designs
        ({"components": True}, "components: must be an integer"),
    ],
)
def test_a_selection_out_of_range_is_refused_where_it_is_made(fields, words):
    with pytest.raises(lkspace.LkspaceError, match=re.escape(words)):
        lkspace.Selection(**fields)


def test_enumerate_seed_below_zero_is_a_usage_line(capsys, tmp_path):
    """``enumerate --seed -1 --sample 3`` was an internal error (numpy's ValueError)."""
    from tests.cli_calls import run

    args = ["enumerate", "cube", "--labels", "-1..1", "--mode", "spanning-trees", "--sample", "3", "--seed", "-1"]
    code, _, err = run(capsys, *args, "-o", tmp_path / "x.parquet")
    assert code == 2
    assert "--seed" in err
    assert os.listdir(tmp_path) == []
