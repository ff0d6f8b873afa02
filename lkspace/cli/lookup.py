"""``lkspace lookup``: the simplest designs of a knot or link type, from the atlas lkspace ships.

Imports nothing heavy until it runs (``lkspace lookup --help`` loads click only), and then
pyarrow alone: no pandas, no knot libraries.
"""

from __future__ import annotations

import click

from .numbers import Count


@click.command("lookup")
@click.argument("name")
@click.option("--limit", type=Count(1, 10_000), default=10, show_default=True, help="Designs to list, simplest first.")
@click.option("--scaffold", metavar="S", default=None, help="Only designs on the scaffold S (a built-in name).")
@click.option(
    "--atlas",
    "atlas_file",
    type=click.Path(dir_okay=False),
    default=None,
    metavar="FILE",
    help="An atlas index built by experiments/build_atlas.py (default: the one shipped with lkspace).",
)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout and nothing else.")
def lookup_cmd(name: str, limit: int, scaffold: str | None, atlas_file: str | None, as_json: bool) -> None:
    """Find the simplest designs of the knot or link type NAME in the shipped atlas.

    NAME is a table name (5_2, L6a4; m3_1 asks for the mirror image only, 3_1 for both)
    or a common name ("Borromean rings", "Whitehead link", trefoil, "left-handed
    trefoil").  Each design is listed with its scaffold, label set, sum |t|, crossings
    and the command that identifies it again.  A table type the atlas does not hold is
    answered by its constructed design (scaffold knot:NAME or link:NAME, label set
    "constructed"; `constructed: true` in --json); any other type the atlas does not
    hold exits with status 1 and names the spaces searched.

    \b
    Examples:
      lkspace lookup 5_2
      lkspace lookup "Borromean rings" --limit 3
      lkspace lookup m3_1 --scaffold tetrahedron --json
    """
    from ..linktypes.lookup import lookup
    from ..words import plural
    from .common import Context, emit

    ctx = Context(as_json)
    answer = lookup(name, atlas_file, limit=limit, scaffold=scaffold)  # none found: TypeNotFound, exit 1

    def human() -> None:
        common = f" ({answer.common_name})" if answer.common_name else ""
        spaces = f"{len(answer.found_in)} of {plural(len(answer.searched), 'space')}"
        shown = len(answer.designs)
        if all(d.constructed for d in answer.designs):
            click.echo(
                f"{answer.asked}{common}: no design in the {plural(len(answer.searched), 'space')} of the atlas; "
                "made from its diagram (lkspace construct):"
            )
        else:
            click.echo(
                f"{answer.asked}{common}: {plural(answer.designs_total, 'design')} in {spaces}; "
                + (f"the simplest {shown}:" if shown > 1 else "the simplest:")
            )
        rows = [("type", "scaffold", "labels", "sum|t|", "crossings", "identify again")]
        for d in answer.designs:
            crossings = "?" if d.crossings is None else str(d.crossings)
            rows.append((d.chiral_name, d.scaffold, d.label_set, str(d.sum_abs), crossings, d.command))
        widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]) - 1)]
        for r in rows:
            click.echo("  " + "  ".join(c.ljust(w) for c, w in zip(r, widths, strict=False)) + "  " + r[-1])
        shape = answer.ideal_shape
        if shape is not None:
            click.echo(
                f"ideal shape ({shape.chiral_name}: ropelength {shape.ropelength:.1f}, "
                f"{shape.ratio:.3f} x KnotInfo's {shape.ideal:.1f}):"
            )
            click.echo(f"  {shape.command()}")

    emit(ctx, answer.to_json(), human)
