"""The Jones polynomial's bound on crossing numbers that spares regina's simplification of most designs.

References: the crossing numbers of the table names (KnotInfo/LinkInfo, by name), and
regina's own simplification of each design's diagram, which can never go below a true
lower bound.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from lkspace import load
from lkspace.knots.crossing_bound import crossing_bound, jones_terms, linked_groups
from lkspace.knots.key_names import _simplified
from lkspace.knots.keyed import keys_of
from lkspace.knots.naming import name_key
from lkspace.knots.shipped_keys import shipped_keys

pytest.importorskip("regina")

NON_ALTERNATING_KNOTS = {"8_19", "8_20", "8_21"}
"""The knots of at most 8 crossings without an alternating diagram."""


def test_jones_text_is_read_term_by_term():
    assert jones_terms("-x^4 + 3 x^2 - 4 + 6 x^-2") == ((4, -1), (2, 3), (0, -4), (-2, 6))
    assert jones_terms("-x^-1 - x") == ((-1, -1), (1, -1))
    assert jones_terms("1") == ((0, 1),)
    assert jones_terms("x^2 + x") is None  # mixed parity: no Jones polynomial
    assert jones_terms("t^2") is None


def test_the_unlink_and_split_links_get_their_pieces():
    assert crossing_bound("-x^-1 - x", [[0, 0], [0, 0]]) == 0  # two circles: span 1, two pieces
    assert crossing_bound("x^2 + x^6 - x^8", [[0]]) == 3  # the trefoil
    assert linked_groups([[0, 1, 0], [1, 0, 0], [0, 0, 0]]) == 2
    assert linked_groups([[0, 0, 2], [0, 0, 0], [2, 0, 0]]) == 2


def test_the_bound_never_passes_a_table_types_crossing_number():
    checked = equal = 0
    for line in shipped_keys().lines().values():
        fields = json.loads(line)["fields"]
        if not fields or fields["table"] not in ("knotinfo", "linkinfo") or "#" in (fields["knot_name"] or ""):
            continue
        name, jones = fields["knot_name"], fields["jones"]
        crossings = name_key(name)[0]
        bound = crossing_bound(jones, [[0]])  # a prime table type is not split: one piece
        assert bound is not None and bound <= crossings, (name, jones)
        alternating = ("a" in name) if name.startswith("L") else (crossings <= 8 and name not in NON_ALTERNATING_KNOTS)
        if alternating:
            assert bound == crossings, (name, jones)
            equal += 1
        checked += 1
    assert checked > 300 and equal > 150


@pytest.mark.parametrize(("scaffold", "labels"), [("cube", (-1, 0, 1)), ("tetrahedron", (-2, -1, 0, 1, 2))])
def test_regina_never_simplifies_a_design_below_its_bound(scaffold, labels):
    sc = load(scaffold)
    rng = np.random.default_rng(7)
    designs = rng.choice(np.array(labels), size=(1500, sc.n_edges))
    found = keys_of(sc, designs)
    cache = shipped_keys()
    tried = 0
    for d, ((a, b), keyed) in enumerate(zip(found.keys.tolist(), found.keyed, strict=True)):
        line = cache.get((int(a), int(b))) if keyed else None
        fields = json.loads(line)["fields"] if line else None
        if not fields or not fields["jones"]:
            continue
        bound = crossing_bound(fields["jones"], found.linking_matrix(d))
        if bound is None or bound < 3:
            continue
        pd = found.diagram(d)[0]
        assert int(_simplified(pd).size()) >= bound, (designs[d].tolist(), fields["knot_name"], bound)
        tried += 1
    assert tried > 100
