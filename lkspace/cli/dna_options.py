"""The ``--dna NM`` and ``--dna-window W`` options that ``solve`` and ``enumerate`` add (docs/dna.md)."""

from __future__ import annotations

import click

from .numbers import Finite

DNA_OPTIONS = [
    click.Option(
        ["--dna", "dna_scale"],
        type=Finite(0, low_open=True),
        default=None,
        metavar="NM",
        help="Only designs buildable as B-DNA with the mesh at NM nm per unit (docs/dna.md).",
    ),
    click.Option(
        ["--dna-window"],
        type=Finite(0),
        default=None,
        metavar="W",
        help="With --dna: labels within W half turns of each edge's natural twist (default 1).",
    ),
]
"""The options, shared by ``solve --dna`` and ``enumerate --dna``."""
