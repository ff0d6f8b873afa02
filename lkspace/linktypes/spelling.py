"""How knot and link names are spelled: the one canonicaliser every caller uses.

Names follow KnotInfo/LinkInfo, as ``identify`` reports them (SPEC section 2): Rolfsen's
``3_1`` ... ``10_165`` for knots to 10 crossings, KnotInfo's ``11a_1`` ... ``13n_5110``
beyond, Thistlethwaite's ``L2a1`` ... ``L11n459`` for links, SnapPy's ``K14n10910`` /
``L13n4723`` past the tables; ``m`` in front for the mirror image of the table's diagram.
:func:`canonical_name` turns what a user or a table wrote into that spelling:

==============  ==============  ========================================================
typed           canonical       why
==============  ==============  ========================================================
``L6a4{0,1}``   ``L6a4``        an orientation suffix names no other type: dropped
``l6a4{0}``     ``L6a4``        the ``K``/``L`` prefix upper case, the rest lower case
``K14N1``       ``K14n1``       (so ``k14n10910`` is ``K14n10910``)
``K11a1``       ``11a_1``       11 to 13 crossings: KnotInfo writes SnapPy's ``K11a1`` so
``k11a1``       ``11a_1``       (the numbering is the same, Dowker-Thistlethwaite's)
``K5a1``        ``5_2``         to 10 crossings the DT numbering is not Rolfsen's: KnotInfo's
``5a_1``        ``5_2``         ``dt_name`` column maps it (:data:`ROLFSEN`); ``5a_1`` is
                                no KnotInfo name, so it is never an answer
==============  ==============  ========================================================

Anything else (``3_1``, ``split: 0_1 + 0_1``, a misspelling) comes back unchanged, for
the caller to accept or refuse.  :func:`chiral_parts` reads the mirror mark.
"""

from __future__ import annotations

import re
from typing import Literal, TypeAlias, get_args

Chirality: TypeAlias = Literal["any", "table", "mirror"]
"""Which chirality a name asks for: either, the table's diagram, or its mirror image."""
CHIRALITIES: tuple[Chirality, ...] = get_args(Chirality)

TABLE_NAME = re.compile(r"(?:\d+_\d+|\d+[an]_\d+|K\d+[an]\d+|L\d+[an]\d+)(?:\{[\d,]*\})?", re.I)
"""One prime table name as typed: ``3_1``, ``11a_1``, ``K14n10910``, ``L6a4``, ``L6a4{0,1}`` (any case)."""

_HT = re.compile(r"([KL])(\d+)([AN])(\d+)", re.I)
_DT = re.compile(r"(\d+)([AN])_(\d+)", re.I)

_ROLFSEN_TEXT = """
3a_1=3_1 4a_1=4_1 5a_2=5_1 5a_1=5_2 6a_3=6_1 6a_2=6_2 6a_1=6_3 7a_7=7_1 7a_4=7_2 7a_5=7_3
7a_6=7_4 7a_3=7_5 7a_2=7_6 7a_1=7_7 8a_11=8_1 8a_8=8_2 8a_18=8_3 8a_17=8_4 8a_13=8_5
8a_10=8_6 8a_6=8_7 8a_4=8_8 8a_16=8_9 8a_3=8_10 8a_9=8_11 8a_5=8_12 8a_7=8_13 8a_1=8_14
8a_2=8_15 8a_15=8_16 8a_14=8_17 8a_12=8_18 8n_3=8_19 8n_1=8_20 8n_2=8_21 9a_41=9_1 9a_27=9_2
9a_38=9_3 9a_35=9_4 9a_36=9_5 9a_23=9_6 9a_26=9_7 9a_8=9_8 9a_33=9_9 9a_39=9_10 9a_20=9_11
9a_22=9_12 9a_34=9_13 9a_17=9_14 9a_10=9_15 9a_25=9_16 9a_14=9_17 9a_24=9_18 9a_3=9_19
9a_19=9_20 9a_21=9_21 9a_2=9_22 9a_16=9_23 9a_7=9_24 9a_4=9_25 9a_15=9_26 9a_12=9_27
9a_5=9_28 9a_31=9_29 9a_1=9_30 9a_13=9_31 9a_6=9_32 9a_11=9_33 9a_28=9_34 9a_40=9_35
9a_9=9_36 9a_18=9_37 9a_30=9_38 9a_32=9_39 9a_37=9_40 9a_29=9_41 9n_4=9_42 9n_3=9_43
9n_1=9_44 9n_2=9_45 9n_5=9_46 9n_7=9_47 9n_6=9_48 9n_8=9_49 10a_75=10_1 10a_59=10_2
10a_117=10_3 10a_113=10_4 10a_56=10_5 10a_70=10_6 10a_65=10_7 10a_114=10_8 10a_110=10_9
10a_64=10_10 10a_116=10_11 10a_43=10_12 10a_54=10_13 10a_33=10_14 10a_68=10_15 10a_115=10_16
10a_107=10_17 10a_63=10_18 10a_108=10_19 10a_74=10_20 10a_60=10_21 10a_112=10_22
10a_57=10_23 10a_71=10_24 10a_61=10_25 10a_111=10_26 10a_58=10_27 10a_44=10_28 10a_53=10_29
10a_34=10_30 10a_69=10_31 10a_55=10_32 10a_109=10_33 10a_19=10_34 10a_23=10_35 10a_5=10_36
10a_49=10_37 10a_29=10_38 10a_26=10_39 10a_30=10_40 10a_35=10_41 10a_31=10_42 10a_52=10_43
10a_32=10_44 10a_25=10_45 10a_81=10_46 10a_15=10_47 10a_79=10_48 10a_13=10_49 10a_82=10_50
10a_16=10_51 10a_80=10_52 10a_14=10_53 10a_48=10_54 10a_9=10_55 10a_28=10_56 10a_6=10_57
10a_20=10_58 10a_2=10_59 10a_1=10_60 10a_123=10_61 10a_41=10_62 10a_51=10_63 10a_122=10_64
10a_42=10_65 10a_40=10_66 10a_37=10_67 10a_67=10_68 10a_38=10_69 10a_22=10_70 10a_10=10_71
10a_4=10_72 10a_3=10_73 10a_62=10_74 10a_27=10_75 10a_73=10_76 10a_18=10_77 10a_17=10_78
10a_78=10_79 10a_8=10_80 10a_7=10_81 10a_83=10_82 10a_87=10_83 10a_50=10_84 10a_86=10_85
10a_84=10_86 10a_39=10_87 10a_11=10_88 10a_21=10_89 10a_92=10_90 10a_106=10_91 10a_46=10_92
10a_101=10_93 10a_91=10_94 10a_47=10_95 10a_24=10_96 10a_12=10_97 10a_96=10_98 10a_103=10_99
10a_104=10_100 10a_45=10_101 10a_97=10_102 10a_105=10_103 10a_118=10_104 10a_72=10_105
10a_95=10_106 10a_66=10_107 10a_119=10_108 10a_93=10_109 10a_100=10_110 10a_98=10_111
10a_76=10_112 10a_36=10_113 10a_77=10_114 10a_94=10_115 10a_120=10_116 10a_99=10_117
10a_88=10_118 10a_85=10_119 10a_102=10_120 10a_90=10_121 10a_89=10_122 10a_121=10_123
10n_21=10_124 10n_15=10_125 10n_17=10_126 10n_16=10_127 10n_22=10_128 10n_18=10_129
10n_20=10_130 10n_19=10_131 10n_13=10_132 10n_4=10_133 10n_6=10_134 10n_5=10_135
10n_3=10_136 10n_2=10_137 10n_1=10_138 10n_27=10_139 10n_29=10_140 10n_25=10_141
10n_30=10_142 10n_26=10_143 10n_28=10_144 10n_14=10_145 10n_23=10_146 10n_24=10_147
10n_12=10_148 10n_11=10_149 10n_9=10_150 10n_8=10_151 10n_36=10_152 10n_10=10_153
10n_7=10_154 10n_39=10_155 10n_32=10_156 10n_42=10_157 10n_41=10_158 10n_34=10_159
10n_33=10_160 10n_31=10_161 10n_40=10_162 10n_35=10_163 10n_38=10_164 10n_37=10_165
"""
ROLFSEN: dict[str, str] = dict(pair.split("=", 1) for pair in _ROLFSEN_TEXT.split())
"""KnotInfo's ``dt_name`` -> ``name`` of the 249 non-trivial knots to 10 crossings (``5a_1`` -> ``5_2``).

Written from ``database_knotinfo`` (``tests/test_lookup.py`` checks it against the installed one)."""


def canonical_name(name: str) -> str:
    """Return one prime table name (no mirror mark) in KnotInfo/LinkInfo spelling (table in the module docstring).

    Examples
    --------
    >>> [canonical_name(n) for n in ("K5a1", "k11a1", "K14N1", "l6a4{0}", "3_1", "K13n5110")]
    ['5_2', '11a_1', 'K14n1', 'L6a4', '3_1', '13n_5110']
    """
    name = name.split("{")[0]
    m = _HT.fullmatch(name)
    if m:
        kind, crossings, alternating, index = m[1].upper(), int(m[2]), m[3].lower(), int(m[4])
        if kind == "K" and crossings <= 13:
            return _knotinfo(crossings, alternating, index, f"K{crossings}{alternating}{index}")
        return f"{kind}{crossings}{alternating}{index}"
    m = _DT.fullmatch(name)
    if m:
        crossings, alternating, index = int(m[1]), m[2].lower(), int(m[3])
        return _knotinfo(crossings, alternating, index, f"{crossings}{alternating}_{index}")
    return name


def _knotinfo(crossings: int, alternating: str, index: int, unknown: str) -> str:
    """KnotInfo's name of the knot with DT name ``{crossings}{alternating}_{index}`` (``unknown`` if none to 10)."""
    dt = f"{crossings}{alternating}_{index}"
    return dt if crossings > 10 else ROLFSEN.get(dt, unknown)


def chiral_parts(text: str) -> tuple[str, bool]:
    """Return ``(canonical name, mirror)`` of one prime name with or without ``m`` in front.

    Examples
    --------
    >>> chiral_parts("m3_1"), chiral_parts("mK11a1"), chiral_parts("L6a4{0,1}")
    (('3_1', True), ('11a_1', True), ('L6a4', False))
    """
    mirror = text.startswith("m") and len(text) > 1
    return canonical_name(text[1:] if mirror else text), mirror


def chiral_name(text: str) -> str:
    """Return one prime name in canonical spelling, keeping an ``m`` in front (``"mk11a1"`` -> ``"m11a_1"``)."""
    name, mirror = chiral_parts(text)
    return f"m{name}" if mirror else name


def is_table_name(text: str) -> bool:
    """Whether ``text`` is spelled as one prime table name, with or without ``m`` in front."""
    body = text[1:] if text.startswith("m") and len(text) > 1 else text
    return bool(TABLE_NAME.fullmatch(body))
