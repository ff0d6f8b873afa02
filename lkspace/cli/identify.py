"""``lkspace identify``: the knot or link type of a labelled scaffold."""

from __future__ import annotations

import click
import numpy as np

from ..words import plural
from .common import Context, emit, json_option
from .export import design_options, params_of, resolve_design
from .numbers import Finite

TIME_LIMIT = 60.0
"""Default ``--time-limit`` of ``identify`` in seconds (:data:`lkspace.knots.budget.TIME_LIMIT`)."""


@click.command("identify")
@design_options
@click.option(
    "--seed",
    type=click.IntRange(0, 2**31 - 1),
    default=0,
    show_default=True,
    help="Seed of the generic projection (the next two are tried if it is not generic).",
)
@click.option(
    "--time-limit",
    type=Finite(0),
    default=TIME_LIMIT,
    show_default=True,
    metavar="S",
    help="Stop after S seconds with the status 'unknown: time limit ...'; 0: no limit.",
)
@json_option
def identify_cmd(
    mesh: str | None,
    twist_spec: str | None,
    null_spec: str | None,
    row: int | None,
    radius: float | None,
    normal_offset: float | None,
    tube_radius: float | None,
    seed: int,
    time_limit: float,
    as_json: bool,
) -> None:
    """Name the knot or link that MESH labelled by --twist realizes.

    Needs the extra [knots] (snappy, spherogram, regina, database-knotinfo).  Names are
    Rolfsen's for knots (0_1, 3_1, 4_1, 8_19, ...) and Thistlethwaite's for links (L2a1,
    L4a1, L6a4, ...), and SnapPy's HTLinkExteriors past them (K14n10910, L13n4723);
    'table' says which table named it; 'name' is null when no table entry is certain.  The status says
    'identified' or 'unknown: <why>' (not in the tables, diagram too large, time limit).
    Periodic scaffolds are refused; twists making more than 2,000 crossings too.

    \b
    Examples:
      lkspace identify dihedron:5 --twist 1          # 5_1
      lkspace identify book:4 --twist 3              # 8_19
      lkspace identify tetrahedron --twist 1 --json  # L6a4, the Borromean rings
    """
    from ..knots.recognition import check_identifiable, identify
    from ..linktypes.common_names import common_name

    ctx = Context(as_json)
    scaffold, labels, nulls = resolve_design(ctx, mesh, twist_spec, null_spec, row)
    check_identifiable(scaffold)
    params = params_of(radius, normal_offset, tube_radius)
    result = identify(scaffold, labels, nulls, params, seed=seed, time_limit=time_limit or None).to_dict()
    result["labels"] = np.asarray(labels).tolist()
    result["common_name"] = common_name(result["name"], result.get("mirror")) if result["name"] else None

    def human() -> None:
        name = result["name"] or "unknown"
        if result["status"] != "identified":
            click.echo(f"{scaffold.name}: {result['status']}")
        if result["status"].startswith("unknown: time limit"):
            click.echo(f"  raise --time-limit (now {time_limit:g} s; 0: no limit) to let it finish")
        said = [result["common_name"]] if result["common_name"] else []
        if result.get("mirror") is not None:
            said.append("mirror of the table diagram" if result["mirror"] else "as in the table")
        chir = f" ({', '.join(said)})" if said else ""
        table = f" [{result['table']}]" if result.get("table") and result["name"] else ""
        click.echo(f"{scaffold.name}: {plural(result['components'], 'component')}: {name}{chir}{table}")
        if result.get("crossings") is not None:
            click.echo(f"  crossings of the simplified diagram: {result['crossings']}")
        else:
            click.echo(f"  crossings of the projection: {result.get('projected_crossings')}")
        click.echo(f"  linking matrix: {result['linking_matrix']}")
        if result.get("jones"):
            click.echo(f"  Jones polynomial (in sqrt t): {result['jones']}")
        if not result["name"] and result.get("candidates"):
            click.echo(f"  candidates: {', '.join(result['candidates'])}")
        if result.get("note"):
            click.echo(f"  note: {result['note']}")

    emit(ctx, result, human)
