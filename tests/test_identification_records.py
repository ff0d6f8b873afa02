"""The records identification hands on: one from_json and one to_json each, round trips, refusals."""

from __future__ import annotations

import json

import pytest

from lkspace.knots.identification import Identification, NameFields, Naming, RecordError

TREFOIL = (
    '{"status": "identified", "components": 1, "name": "3_1", "linking_matrix": [[0]], "mirror": true, '
    '"split": false, "crossings": 3, "projected_crossings": 6, "table_name": "3_1", "candidates": ["3_1 (mirror)"], '
    '"jones": "x^-2 + x^-6 - x^-8", "volume": 0.0, "homfly": "-x^4 + x^2 y^2 + 2 x^2", "table": "knotinfo", '
    '"chiral_name": "m3_1", "knot_floer": {"seifert_genus": 1, "fibered": true, "tau": -1, "total_rank": 3, '
    '"L_space_knot": true}, "min_distance": 0.316031308274}'
)
FIELDS = (
    '{"knot_name": null, "split": true, "mirror": null, "crossings": 0, "jones": "1", "status": "identified", '
    '"error": null, "pieces": ["0_1", "0_1"], "table": null, "chiral_name": null, "candidates": null}'
)


def test_identify_json_round_trips_to_the_same_text():
    found = Identification.from_json(json.loads(TREFOIL))
    assert json.dumps(found.to_json()) == TREFOIL
    assert (found.name, found.mirror, found.details["chiral_name"]) == ("3_1", True, "m3_1")
    assert found.naming.candidates == ("3_1 (mirror)",) and found.naming.knot_floer == {
        "seifert_genus": 1,
        "fibered": True,
        "tau": -1,
        "total_rank": 3,
        "L_space_knot": True,
    }


def test_key_cache_fields_round_trip_and_refusals_carry_the_reason():
    fields = NameFields.from_json(json.loads(FIELDS))
    assert json.dumps(fields.to_json()) == FIELDS and fields.pieces == ("0_1", "0_1")
    refused = NameFields.refused("unknown: time limit 1 s reached (during simplification)")
    assert refused.error == "time limit 1 s reached (during simplification)" and refused.knot_name is None
    assert list(NameFields.from_json(refused.to_json()).to_json()) == list(NameFields.KEYS)


def test_a_naming_keeps_the_keys_it_found_in_order():
    unlink = Naming.of(name=None, table=None, crossings=0).updated(split=True, mirror=None, jones="1")
    unlink = unlink.updated(pieces=("0_1", "0_1"), note="unlink of 2 components")
    text = json.dumps(unlink.to_json())
    assert text == (
        '{"name": null, "table": null, "crossings": 0, "split": true, "mirror": null, "jones": "1", '
        '"pieces": ["0_1", "0_1"], "note": "unlink of 2 components"}'
    )
    assert json.dumps(Naming.from_json(json.loads(text)).to_json()) == text
    assert unlink.updated(name="x").keys[0] == "name"  # a key held keeps its place


@pytest.mark.parametrize(
    "reader, data, match",
    [
        (Naming.from_json, {"name": 3}, "name: expected str"),
        (Naming.from_json, {"nmae": "3_1"}, "unknown key 'nmae'"),
        (Naming.from_json, {"crossings": True}, "crossings: expected int"),
        (Naming.from_json, [], "expected a JSON object"),
        (NameFields.from_json, {"knot_name": "3_1"}, "missing key"),
        (
            Identification.from_json,
            {"status": "identified", "components": 1, "linking_matrix": "[[0]]"},
            "linking_matrix",
        ),
        (Identification.from_json, {**json.loads(TREFOIL), "volume": "big"}, "volume: expected float"),
    ],
)
def test_records_refuse_what_they_cannot_hold(reader, data, match):
    with pytest.raises(RecordError, match=match):
        reader(data)
