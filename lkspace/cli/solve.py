"""``lkspace solve``: inverse design with CP-SAT."""

from __future__ import annotations

import os
import sys

import click
from click.core import ParameterSource

from .. import io
from ..errors import UsageError
from ..io.paths import output_file
from ..words import plural
from .common import (
    Context,
    emit,
    json_option,
    label_set,
    labels_option,
    load_mesh,
    mesh_argument,
    symmetry_tolerance,
    usage_errors,
)
from .edges import edge_values, fix_label
from .numbers import Count, Finite

MAX_SEED = 2**31 - 1
"""Largest ``--seed`` (CP-SAT takes a 32-bit signed seed)."""


def _parity(value: str, item: str) -> int:
    if value.lower() not in ("odd", "even"):
        raise UsageError(f"--parity {item!r}: expected odd or even, got {value!r}")
    return int(value.lower() == "odd")


DEFAULT_TIME_LIMIT = 120.0
"""Seconds ``solve`` may take by default (all stages: fast path, model building, search); 0 lifts it."""

MAX_COUNT = 10_000
"""Most designs ``--count`` may ask for (the library's :data:`lkspace.inverse.pipeline.MAX_COUNT`)."""


@click.command("solve")
@mesh_argument
@click.option(
    "--components",
    "-n",
    type=Count(min=1),
    default=None,
    help="Exact number of strand components N (more than the mesh can have: infeasible).",
)
@click.option(
    "--type",
    "type_name",
    metavar="NAME",
    default=None,
    help="A knot or link type instead of --components: 3_1, m3_1, 4_1, L6a4, K14n10910, 3_1#4_1 ...",
)
@click.option(
    "--chirality",
    type=click.Choice(["any", "table", "mirror"]),
    default="any",
    show_default=True,
    help="With --type: either mirror image, the table diagram's, or its mirror (same as an m prefix).",
)
@click.option(
    "--linking-matrix",
    "linking_text",
    metavar="M",
    default=None,
    help="Pairwise linking numbers up to renumbering, rows split by ';' (e.g. 0,1;1,0); alone or with --type.",
)
@click.option("--signed", is_flag=True, help="With --linking-matrix: compare signs too (strands as traced).")
@click.option(
    "--processes",
    type=Count(min=1, max=256),
    default=1,
    show_default=True,
    help="With --type/--linking-matrix: worker processes screening designs.",
)
@click.option("--no-zero", is_flag=True, help="Forbid twist label 0.")
@labels_option
@click.option(
    "--fix",
    "fix_items",
    multiple=True,
    metavar="EDGE=T",
    help="Pin edge EDGE (index or vertex pair u-v) to label T; repeatable.",
)
@click.option(
    "--parity",
    "parity_items",
    multiple=True,
    metavar="EDGE=odd|even",
    help="Require an odd or even label on EDGE; repeatable.",
)
@click.option(
    "--count",
    type=Count(min=1, max=MAX_COUNT),
    default=1,
    show_default=True,
    help="Distinct designs wanted (they differ in how the strands connect).",
)
@click.option(
    "--distinct-up-to",
    type=click.Choice(["none", "rotations", "isometries"]),
    default="none",
    show_default=True,
    help="With --count: no two designs related by a symmetry of this kind (uses the scaffold's symmetry group).",
)
@click.option(
    "--objective",
    type=click.Choice(["none", "min-abs", "min-nonzero"]),
    default="none",
    show_default=True,
    help="Minimize the total |t| or the number of non-zero labels.",
)
@click.option(
    "--time-limit",
    type=Finite(0),
    default=DEFAULT_TIME_LIMIT,
    show_default=True,
    metavar="S",
    help="Give up after S seconds of wall-clock time (status 'unknown' if nothing is proved); 0: no limit.",
)
@click.option(
    "--workers",
    type=Count(min=0, max=256),
    default=0,
    show_default=True,
    help="CP-SAT search workers (0: one per core).",
)
@click.option(
    "--seed",
    type=Count(0, MAX_SEED),
    default=0,
    show_default=True,
    help="Random seed (search and spanning trees).",
)
@click.option(
    "--invariant",
    metavar="SUBGROUP",
    help="Only designs fixed by this subgroup of the symmetries (C3, C4:face=0, rotations, ...; docs/structured.md).",
)
@click.option(
    "--no-fast-path", is_flag=True, help="Always use CP-SAT, even where the spanning-tree construction applies."
)
@click.option(
    "-o",
    "--output",
    type=click.Path(dir_okay=False),
    default=None,
    help="Write the first design as a scaffold file with its labels (.json) for trace/export.",
)
@json_option
def solve_cmd(
    mesh: str | None,
    components: int | None,
    type_name: str | None,
    chirality: str,
    linking_text: str | None,
    signed: bool,
    processes: int,
    no_zero: bool,
    labels_spec: str,
    fix_items: tuple[str, ...],
    parity_items: tuple[str, ...],
    count: int,
    distinct_up_to: str,
    objective: str,
    time_limit: float,
    workers: int,
    seed: int,
    no_fast_path: bool,
    invariant: str | None,
    output: str | None,
    as_json: bool,
) -> None:
    """Find twist labels on MESH giving exactly --components strands (or a --type), or prove none exist.

    Status is optimal (objective proved), feasible, infeasible (proved: no design) or
    unknown (time ran out).  Every design is re-traced before it is printed.

    With --type or --linking-matrix (docs/design-to-target.md) the designs are searched
    simplest first (smallest largest |t|, then total |t|, then fewest non-zero labels);
    the status is found, exhausted (the whole space searched: proved absent) or unknown.
    A plain name matches either mirror image; m3_1 or --chirality asks for one.  Every
    answer is re-identified before it is printed.

    \b
    Examples:
      lkspace solve --components 1
      lkspace solve cube --components 1 --no-zero --count 3
      lkspace solve dodecahedron -n 2 --labels -1,1,2 --fix 0=2 --objective min-abs
      lkspace solve cube --components 2 --labels -1..1 --invariant C3:vertex=0 --count 5
      lkspace solve cube --type 3_1 --labels -1..1
      lkspace solve tetrahedron --type L6a4
      lkspace solve octahedron --linking-matrix "0,1,0;1,0,1;0,1,0" --labels -1..1
    """
    from ..inverse.pipeline import SolveOptions, solve
    from ..inverse.query import check_objective
    from ..symmetry.group import check_mode

    ctx = Context(as_json)
    if type_name is not None or linking_text is not None:
        if components is not None or parity_items or objective != "none" or distinct_up_to != "none" or invariant:
            raise UsageError(
                "--type/--linking-matrix: --components, --parity, --objective, --distinct-up-to and --invariant "
                "do not apply"
            )
        from .solve_target import target_cmd

        given = click.get_current_context().get_parameter_source("labels_spec") != ParameterSource.DEFAULT
        target_cmd(ctx, mesh, type_name, chirality, linking_text, signed, no_zero, labels_spec, given, fix_items,
                   count, time_limit, processes, seed, output)  # fmt: skip
        return
    if components is None:
        raise UsageError("solve: give --components N, --type NAME or --linking-matrix M")
    if chirality != "any" or signed or processes != 1:
        raise UsageError("--chirality, --signed and --processes apply to --type/--linking-matrix only")
    target = None if output is None else output_file(output, (".json",), (mesh,))  # checked before any work
    scaffold = load_mesh(ctx, mesh)
    labels = label_set(labels_spec)
    with usage_errors():
        fixes = edge_values(scaffold, fix_items, "--fix", fix_label)
        parities = edge_values(scaffold, parity_items, "--parity", _parity)
        if invariant is not None:
            from ..symmetry.edge_orbits import invariant_edge_orbits

            invariant_edge_orbits(scaffold, invariant)  # a bad subgroup name is bad usage (exit 2)
    mode = check_mode(distinct_up_to)  # checked before the objective, as the flags are listed
    result = solve(
        scaffold,
        components,
        label_set=labels,
        no_zero=no_zero,
        fixes=fixes,
        parities=parities,
        objective=check_objective(None if objective == "none" else objective),
        options=SolveOptions(
            count=count,
            distinct_up_to=mode,
            invariant=invariant,
            tolerance=symmetry_tolerance(),
            time_limit=time_limit or None,
            workers=workers,
            seed=seed,
            fast_path=not no_fast_path,
        ),
    )
    written = None
    if target is not None and output is not None and result.solutions:
        io.write(scaffold, target, result.solutions[0].labels)
        written = os.path.abspath(output)
    data = {
        "components": components,
        "label_set": labels.tolist(),
        "no_zero": no_zero,
        **result.to_dict(),
        "written": written,
    }

    def human() -> None:
        line = f"{scaffold.name}: {result.status}"
        if result.reason:
            line += f" ({result.reason})"
        click.echo(
            f"{line} — {plural(len(result.solutions), 'design')} with {plural(components, 'component')} "
            f"[{result.method}, {result.wall_time:.3f} s]"
        )
        for k, sol in enumerate(result.solutions):
            click.echo(f"  {k}: {','.join(map(str, sol.labels.tolist()))}")
        if result.status == "unknown":
            click.echo("  time ran out before a design was found or ruled out", err=True)
        if written:
            click.echo(f"wrote the first design to {output}")
        sys.stdout.flush()

    emit(ctx, data, human)
