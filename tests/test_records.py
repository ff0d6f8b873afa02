"""The atlas and lookup wire records (``lkspace.linktypes.records``): one reader and one writer each."""

import json

import pytest
from hypothesis import given
from hypothesis import strategies as st

from lkspace.errors import CatalogError
from lkspace.linktypes.answers import LookupAnswer, LookupDesign, TargetSolution
from lkspace.linktypes.records import INDEX_COLUMNS, AtlasType, ChiralityCounts, DesignRecord, Example, IndexRow

counts = st.integers(0, 10**12)
maybe = st.none() | st.integers(0, 200)
examples = st.builds(
    Example, st.lists(st.integers(-5, 5), max_size=12).map(tuple), counts, counts, maybe, st.none() | st.booleans()
)


@given(examples)
def test_example_round_trips(example):
    assert Example.from_json(json.loads(json.dumps(example.to_json()))) == example


@given(st.lists(examples, max_size=4).map(tuple), st.none() | st.text(max_size=8))
def test_atlas_type_round_trips(kept, picture):
    t = AtlasType("3_1", 1, "knotinfo", 3, 2, 48, (1, 1, 1), 3, 3, ChiralityCounts(1, 1, 0), kept, picture)
    out = t.to_json()
    assert AtlasType.from_json(json.loads(json.dumps(out))) == t
    assert ("picture" in out) == (picture is not None)  # written by the gallery only


def test_index_row_and_lookup_round_trip():
    ex = Example((1, 1, 1), 3, 3, 3, False)
    text = IndexRow.examples_text((ex,))
    row = IndexRow("3_1", "trefoil", 1, 3, 3, "knotinfo", "dihedron:3", "-1..1", 2, 12, 3, 1, 1, 0, text, True)
    written = row.to_row()
    assert isinstance(written["examples"], str) and IndexRow.from_row(written) == row
    assert IndexRow.from_row(written).examples == (ex,)
    assert list(written) == [name for name, _ in INDEX_COLUMNS]
    with pytest.raises(CatalogError, match="field 'designs' is '2', expected an integer"):
        IndexRow.from_row({**written, "designs": "2"})
    with pytest.raises(CatalogError, match=r"examples\[0\]: field 'labels'"):
        _ = IndexRow.from_row({**written, "examples": '[{"labels": "1,1,1"}]'}).examples
    assert (row.count("any"), row.count("table"), row.count("mirror")) == (2, 1, 1)
    design = LookupDesign("3_1", "trefoil", "dihedron:3", (1, 1, 1), "-1..1", 3, 3, 3, False, "3_1", 2, "lkspace ...")
    answer = LookupAnswer("trefoil", "3_1", "any", "trefoil", "/a.parquet", ("s",), ("s",), 2, 1, (design,))
    assert LookupAnswer.from_json(json.loads(json.dumps(answer.to_json()))) == answer
    assert DesignRecord.from_json(DesignRecord("L2a1", 2, "linkinfo").to_json()) == DesignRecord("L2a1", 2, "linkinfo")


@pytest.mark.parametrize(
    ("data", "words"),
    [
        ({"labels": [1, "2"], "sum_abs": 3, "nonzero": 2, "crossings": None, "mirror": None}, "field 'labels'"),
        ({"labels": [1], "sum_abs": True, "nonzero": 1, "crossings": None, "mirror": None}, "field 'sum_abs' is True"),
        ({"labels": [1], "sum_abs": 1, "nonzero": 1, "mirror": None}, "no field 'crossings'"),
        ({"labels": [1], "sum_abs": 1, "nonzero": 1, "crossings": None, "mirror": 1}, "field 'mirror' is 1"),
        ([1, 2], "is no JSON object"),
    ],
)
def test_example_reader_names_the_field(data, words):
    with pytest.raises(CatalogError, match="example") as caught:
        Example.from_json(data)
    assert words in str(caught.value)


def test_lookup_answer_refuses_an_unknown_chirality():
    design = LookupDesign("3_1", None, "s", (1,), "-1..1", 1, 1, None, None, "3_1", 1, "c")
    data = LookupAnswer("q", "3_1", "any", None, "a", (), (), 1, 1, (design,)).to_json()
    with pytest.raises(CatalogError, match="field 'chirality' is 'left'"):
        LookupAnswer.from_json({**data, "chirality": "left"})
    with pytest.raises(CatalogError, match=r"designs\[0\]: field 'labels'"):
        LookupAnswer.from_json({**data, "designs": [{**design.to_json(), "labels": "1,1"}]})


def test_target_solution_names_only_what_was_identified():
    plain = TargetSolution((0, 1), 2, 1, 1, 1, 2, ((0, 1), (1, 0)))
    assert "name" not in plain.to_json() and TargetSolution.from_json(plain.to_json()) == plain
    named = TargetSolution((1, 1, 1), 1, 3, 1, 3, 1, ((0,),), True, True, "3_1", "3_1", False, "knotinfo", 3)
    assert list(named.to_json())[-5:] == ["name", "chiral_name", "mirror", "table", "crossings"]
    assert TargetSolution.from_json(json.loads(json.dumps(named.to_json()))) == named
