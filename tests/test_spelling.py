"""The one spelling of knot and link names (``lkspace.linktypes.spelling``), and every reader agreeing on it.

``names.py`` (``solve --type``) and ``common_names.py`` (``lookup``, the studio, ``identify``'s
common names) each had a canonicaliser, and they disagreed on the four names marked below.
"""

import pytest

from lkspace.linktypes.common_names import common_name, resolve_name, resolve_type
from lkspace.linktypes.spelling import ROLFSEN, canonical_name, chiral_name, chiral_parts

SPELLINGS = [
    ("K5a1", "5_2"),  # disagreed: common_names said 5a_1 (no KnotInfo name), names refused it
    ("k11a1", "11a_1"),  # disagreed: names kept k11a1 (no such type)
    ("K14N1", "K14n1"),  # disagreed: names kept K14N1
    ("l6a4{0}", "L6a4"),  # disagreed: names kept l6a4
    ("K11a1", "11a_1"),
    ("K13n5110", "13n_5110"),
    ("11A_1", "11a_1"),
    ("5a_1", "5_2"),
    ("K3a1", "3_1"),
    ("K10n37", "10_165"),  # KnotInfo's numbering of 10_162 ... 10_165 (the Perko pair removed)
    ("K14n10910", "K14n10910"),
    ("L13N4723", "L13n4723"),
    ("L6a4{0,1}", "L6a4"),
    ("3_1", "3_1"),
    ("0_1", "0_1"),
    ("K5a9", "K5a9"),  # no such knot: left for the caller to refuse
]


@pytest.mark.parametrize(("typed", "name"), SPELLINGS)
def test_canonical_name(typed, name):
    assert canonical_name(typed) == name
    assert resolve_name(typed) == name
    assert resolve_name(f"m{typed}") == f"m{name}" and resolve_type(f"m{typed}") == (name, "mirror")
    assert chiral_parts(f"m{typed}") == (name, True) and chiral_name(f"m{typed}") == f"m{name}"


def test_parse_type_spells_like_lookup():
    """``solve --type`` and ``lookup`` read a name the same way (they used two canonicalisers)."""
    pytest.importorskip("database_knotinfo")
    pytest.importorskip("snappy")
    from lkspace.linktypes.names import parse_type

    for typed in ("K5a1", "k11a1", "l6a4{0}", "mK5a1"):
        t = parse_type(typed)
        assert t.name == resolve_type(typed)[0], typed
    assert parse_type("mK5a1").chirality == "mirror"
    assert parse_type("K14N1").name == "K14n1"


def test_common_name_reads_every_spelling():
    assert common_name("l6a4{0}") == common_name("L6a4") == "Borromean rings"
    assert common_name("mK3a1") == "left-handed trefoil"


def test_rolfsen_table_is_knotinfos():
    dki = pytest.importorskip("database_knotinfo")
    want = {}
    for r in dki.link_list()[1:]:
        digits = "".join(c for c in r["name"].split("_")[0] if c.isdigit())
        if r["name"] != "0_1" and int(digits) <= 10:
            want[r["dt_name"]] = r["name"]
    assert ROLFSEN == want
