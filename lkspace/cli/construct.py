"""``lkspace construct``: a scaffold file with twist labels whose strands are a given type (docs/construct.md)."""

from __future__ import annotations

import json

import click


@click.command("construct")
@click.argument("type_name", metavar="TYPE", required=False)
@click.option("--pd", "pd_text", metavar="CODE", default=None, help="Build from this PD code instead of a name.")
@click.option(
    "-o", "--output", type=click.Path(dir_okay=False), required=True, help="The scaffold file to write (.json)."
)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout and nothing else.")
def construct_cmd(type_name: str | None, pd_text: str | None, output: str, as_json: bool) -> None:
    """Write a scaffold file with twist labels whose strands are the knot or link TYPE.

    TYPE is any name `solve --type` takes (3_1, m3_1, 8_17, 12n_242, L11a1, K14n10910,
    3_1#4_1, "Borromean rings"); --pd takes a PD code as SnapPy and KnotInfo write it.
    The mesh is the diagram's checkerboard graph with each twist region one edge; the
    result is named again before it is written.  Table types are built-in names too:
    `lkspace export knot:8_17 --relax -o 8_17.stl`.

    \b
    Examples:
      lkspace construct 8_17 -o 8_17.json
      lkspace construct --pd "[[1,5,2,4],[3,1,4,6],[5,3,6,2]]" -o trefoil.json
    """
    from ..errors import UsageError
    from ..io.atomic import write_text
    from ..io.scaffold_json import format_scaffold_json
    from ..linktypes.construct import construct
    from ..words import plural
    from .common import Context, emit

    ctx = Context(as_json)
    if (type_name is None) == (pd_text is None):
        raise UsageError("give TYPE or --pd CODE (one of them)")
    pd = None
    if pd_text is not None:
        try:
            pd = json.loads(pd_text.replace("(", "[").replace(")", "]").replace("X", "").replace("PD", ""))
        except (ValueError, RecursionError) as exc:
            raise UsageError(f"--pd: not a PD code ({exc.args[0]}); write it as [[1,5,2,4],[3,1,4,6],...]") from exc
        if not isinstance(pd, list):
            raise UsageError("--pd: expected a list of crossings such as [[1,5,2,4],[3,1,4,6],[5,3,6,2]]")
    try:
        made = construct(type_name, pd)
    except UsageError as exc:  # the type names of solve --type, spoken of as TYPE here
        raise UsageError(str(exc).replace("type_name ", "TYPE ").replace("--type ", "TYPE ")) from None
    s = made.scaffold
    write_text(output, format_scaffold_json(s, s.labels))
    assert s.labels is not None
    answer = {
        "output": output,
        "name": made.name,
        "mirror": made.mirror,
        "builtin": made.builtin,
        "layout": made.layout,
        "clear": made.clear,
        "diagram_crossings": made.crossings,
        "vertices": s.n_vertices,
        "edges": s.n_edges,
        "faces": s.n_faces,
        "labels": [int(t) for t in s.labels],
        "sum_abs": int(abs(s.labels).sum()),
    }

    def human() -> None:
        chiral = {True: " (mirror image)", False: "", None: ""}[made.mirror]
        also = f"; also the built-in {made.builtin}" if made.builtin else ""
        if not made.clear:
            also += "; its strands come too close at the default radius: export it with a smaller --radius"
        click.echo(
            f"wrote {output}: {made.name}{chiral} on {plural(s.n_faces, 'face')}, {plural(s.n_edges, 'edge')}, "
            f"sum |t| = {answer['sum_abs']}, from a {made.crossings}-crossing diagram{also}"
        )

    emit(ctx, answer, human)
