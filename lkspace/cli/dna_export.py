"""``lkspace export ... -o NAME.oxdna``: the command of :mod:`~lkspace.cli.export` with the DNA options.

The plain export command is extended here, not edited: its options gain ``--seed``,
``--bp-per-turn`` and ``--nm-per-unit``, and an output ending in ``.oxdna`` goes to
:mod:`lkspace.dna` (``docs/dna.md``), everything else to the plain command.
"""

from __future__ import annotations

import os
from typing import Any

import click

from ..errors import UsageError
from ..words import plural
from .common import Context, emit
from .export import export_cmd as plain_export
from .export import resolve_design
from .numbers import Count, Finite

DNA_KEEPS = {"mesh", "twist_spec", "null_spec", "row", "output", "as_json"}
"""Parameters of the plain export that a DNA export reads; any other one set is refused."""

DNA_OPTIONS = [
    click.Option(["--seed"], type=Count(0), default=None, help="DNA (.oxdna): seed of the random bases (default 0)."),
    click.Option(
        ["--sequence"],
        metavar="BASES",
        default=None,
        help="DNA (.oxdna): strand 0's bases 5' -> 3' (its partners get the complements; default: random from --seed).",
    ),
    click.Option(
        ["--bp-per-turn"],
        type=Finite(5, 20),
        default=None,
        help="DNA (.oxdna): base pairs per helical turn, t half turns = round(bp x t / 2) (default 10.5).",
    ),
    click.Option(
        ["--nm-per-unit"],
        type=Finite(0, low_open=True),
        default=None,
        help="DNA (.oxdna): nm per mesh unit (default: the smallest that fits every edge's helix).",
    ),
]


def export_dna(ctx: Context, kw: dict[str, Any], dna: dict[str, Any]) -> None:
    """Build the DNA of the design and write ``NAME.top``, ``NAME.dat`` and ``NAME.oxview``.

    ``kw`` holds the plain export's parameters, ``dna`` the DNA options (``None`` where not given).
    """
    from ..dna.build import build
    from ..dna.model import BP_PER_TURN
    from ..dna.oxdna import SUFFIXES, targets, write
    from ..io.paths import output_file

    output = kw["output"]
    inputs = (kw["mesh"], kw["twist_spec"], kw["null_spec"])
    for path, suffix in zip(targets(output), SUFFIXES, strict=True):
        output_file(path, (suffix,), inputs)
    scaffold, labels, nulls = resolve_design(ctx, kw["mesh"], kw["twist_spec"], kw["null_spec"], kw["row"])
    if nulls is not None and nulls.any():
        raise UsageError("--null: DNA strands are closed here; null edge-sides are not supported in .oxdna export")
    design = build(
        scaffold,
        labels,
        seed=dna["seed"] or 0,
        bp_per_turn=dna["bp_per_turn"] or BP_PER_TURN,
        nm_per_unit=dna["nm_per_unit"],
        sequence=dna["sequence"],
    )
    written = write(design, output)
    data = {
        "written": [os.path.abspath(p) for p in written],
        "format": "oxdna",
        "labels": labels.tolist(),
        "components": design.trace.components,
        **design.summary(),
    }
    summary = design.summary()
    human = (
        f"wrote {', '.join(written)}: {plural(int(summary['strands']), 'strand')} of {scaffold.name}, "  # type: ignore[call-overload]
        f"{summary['nucleotides']} nucleotides, {summary['unpaired']} unpaired, {design.nucleotides.scale:.4g} nm per unit"
    )
    emit(ctx, data, lambda: click.echo(human))


def dna_callback(**kw: Any) -> None:
    """Send ``.oxdna`` outputs to :func:`export_dna`, the rest to the plain export."""
    extra = {name: kw.pop(name) for name in ("seed", "sequence", "bp_per_turn", "nm_per_unit")}
    if os.path.splitext(kw["output"])[1].lower() != ".oxdna":
        given = [name for name, value in extra.items() if value is not None]
        if given:
            raise UsageError(f"--{given[0].replace('_', '-')} is for DNA export (-o NAME.oxdna)")
        assert plain_export.callback is not None
        plain_export.callback(**kw)
        return
    defaults = {p.name: p.default for p in plain_export.params}
    flags = {p.name: p.opts[0] for p in plain_export.params}
    for name, value in kw.items():
        if name not in DNA_KEEPS and value not in (None, False, (), defaults.get(name)):
            raise UsageError(f"{flags[name]} is not an option of DNA export (.oxdna)")
    export_dna(Context(kw["as_json"]), kw, extra)


for _param in plain_export.params:
    if _param.name == "output" and isinstance(_param, click.Option) and _param.help:
        _param.help = _param.help.replace(" or .svg (", ", .svg or .oxdna (DNA: NAME.top, NAME.dat, NAME.oxview; ")

export_cmd = click.Command(
    name=plain_export.name,
    params=[*plain_export.params[:-1], *DNA_OPTIONS, plain_export.params[-1]],
    callback=dna_callback,
    help=(plain_export.help or "").rstrip() + "\n      lkspace export cube --twist 4 -o dna-cube.oxdna\n",
    context_settings=plain_export.context_settings,
)
