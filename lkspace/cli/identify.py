"""``lkspace identify``: the knot or link type of a labelled scaffold."""

from __future__ import annotations

import click
import numpy as np

from ..words import plural
from .common import Context, emit, json_option
from .export import design_options, params_of, resolve_design
from .numbers import Count, Finite

TIME_LIMIT = 60.0
"""Default ``--time-limit`` of ``identify`` in seconds (:data:`lkspace.knots.budget.TIME_LIMIT`)."""


@click.command("identify")
@design_options
@click.option(
    "--seed",
    type=Count(0, 2**31 - 1),
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
    help="Stop after S seconds of the naming's CPU time with the status 'unknown: time limit ...'; 0: no limit.",
)
@click.option(
    "--geometric",
    is_flag=True,
    help="Realize the strands in 3D and project them (seconds) instead of assembling the diagram from the labels.",
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
    geometric: bool,
    as_json: bool,
) -> None:
    """Name the knot or link that MESH labelled by --twist realizes.

    Needs the extra [knots] (snappy, spherogram, regina, database-knotinfo).  Names are
    Rolfsen's for knots (0_1, 3_1, 4_1, 8_19, ...) and Thistlethwaite's for links (L2a1,
    L4a1, L6a4, ...), and SnapPy's HTLinkExteriors past them (K14n10910, L13n4723); a split
    link is 'split: 0_1 + 3_1' (pieces sorted), an unlink 'split: 0_1 + 0_1'.
    'table' says which table named it; 'name' is null when no table entry is certain.  The status says
    'identified' or 'unknown: <why>' (not in the tables, diagram too large, time limit).
    The diagram is assembled from the labels (JSON 'method': combinatorial) unless
    --geometric, null edge-sides or a geometry option ask for realized strands; 'pd_code'
    is the PD code of the diagram named.
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
    shaped = (radius, normal_offset, tube_radius) != (None, None, None)
    params = params_of(radius, normal_offset, tube_radius) if shaped else None
    limit = time_limit or None
    found = identify(scaffold, labels, nulls, params, seed=seed, time_limit=limit, geometric=geometric)
    named = found.naming
    common = common_name(found.name, found.mirror) if found.name else None
    result = {**found.to_json(), "labels": np.asarray(labels).tolist(), "common_name": common}

    def human() -> None:
        name = found.name or "unknown"
        if found.status != "identified":
            click.echo(f"{scaffold.name}: {found.status}")
        if found.status.startswith("unknown: time limit"):
            click.echo(f"  raise --time-limit (now {time_limit:g} s; 0: no limit) to let it finish")
        said = [common] if common else []
        if found.mirror is not None:
            said.append("mirror of the table diagram" if found.mirror else "as in the table")
        chir = f" ({', '.join(said)})" if said else ""
        table = f" [{named.table}]" if named.table and found.name else ""
        click.echo(f"{scaffold.name}: {plural(found.components, 'component')}: {name}{chir}{table}")
        if found.crossings is not None:
            click.echo(f"  crossings of the simplified diagram: {found.crossings}")
        else:
            click.echo(f"  crossings of the projection: {found.details.get('projected_crossings')}")
        click.echo(f"  linking matrix: {found.linking_matrix}")
        if named.jones:
            click.echo(f"  Jones polynomial (in sqrt t): {named.jones}")
        if not found.name and named.candidates:
            click.echo(f"  candidates: {', '.join(str(c) for c in named.candidates)}")
        if named.note:
            click.echo(f"  note: {named.note}")

    emit(ctx, result, human)
