"""``lkspace solve --type NAME`` / ``--linking-matrix M``: designs of a knot or link type (docs/design-to-target.md)."""

from __future__ import annotations

import os
import sys

import click

from .. import io
from ..errors import UsageError
from ..io.paths import output_file
from ..knots.budget import TIME_LIMIT
from ..words import plural
from .common import Context, emit, label_set, load_mesh, symmetry_tolerance, usage_errors
from .edges import edge_values, fix_label


def target_cmd(
    ctx: Context,
    mesh: str | None,
    type_name: str | None,
    chirality: str,
    linking_text: str | None,
    signed: bool,
    no_zero: bool,
    labels_spec: str,
    labels_given: bool,
    fix_items: tuple[str, ...],
    count: int,
    time_limit: float,
    processes: int,
    seed: int,
    output: str | None,
) -> None:
    """Run the target search and print its answer (JSON fields in ``docs/cli.md``)."""
    from ..knots.recognition import check_identifiable
    from ..linktypes.linking import parse_linking_matrix
    from ..linktypes.names import parse_type
    from ..linktypes.screen import Goal
    from ..linktypes.search import SearchOptions, solve_target

    if signed and linking_text is None:
        raise UsageError("--signed applies to --linking-matrix only")
    if chirality != "any" and type_name is None:
        raise UsageError("--chirality applies to --type only")
    target_path = None if output is None else output_file(output, (".json",), (mesh,))
    scaffold = load_mesh(ctx, mesh)
    check_identifiable(scaffold)
    labels = label_set(labels_spec)
    with usage_errors():
        fixes = edge_values(scaffold, fix_items, "--fix", fix_label)
        linking = parse_linking_matrix(linking_text) if linking_text is not None else None
        target = parse_type(type_name, chirality) if type_name is not None else None
    if target is not None and linking is not None and len(linking) != target.components:
        raise UsageError(
            f"--linking-matrix has {len(linking)} components but --type {type_name} has {target.components}"
        )
    n = target.components if target is not None else len(linking)  # type: ignore[arg-type]
    goal = Goal(n, target, linking, signed)
    limit = time_limit or None
    options = SearchOptions(
        no_zero=no_zero,
        fixes=tuple(sorted(fixes.items())) if fixes else (),
        count=count,
        time_limit=limit,
        identify_time_limit=min(TIME_LIMIT, limit) if limit else TIME_LIMIT,
        processes=processes,
        seed=seed,
        tolerance=symmetry_tolerance(),
        widen=not labels_given,
    )
    result = solve_target(scaffold, goal, label_set=labels, options=options)
    written = None
    if target_path is not None and output is not None and result.solutions:
        io.write(scaffold, target_path, list(result.solutions[0].labels))
        written = os.path.abspath(output)
    data = {"label_set": labels.tolist(), "no_zero": no_zero, **result.to_dict(), "written": written}
    widened = list(result.label_set) != labels.tolist()

    def human() -> None:
        line = f"{scaffold.name}: {result.status} — {plural(len(result.solutions), 'design')} of {goal.label}"
        click.echo(f"{line} [{result.stats.get('designs', 0):,} designs screened, {result.wall_time:.1f} s]")
        if widened:
            bound = result.label_set[-1]
            click.echo(f"  labels -{bound}..{bound}: the diagram of {goal.label} needs them on this mesh")
        for k, sol in enumerate(result.solutions):
            name = sol.chiral_name or sol.name or ""
            matrix = None if sol.linking_matrix is None else [list(r) for r in sol.linking_matrix]
            extra = f" {name} ({sol.table})" if name else f" linking matrix {matrix}"
            click.echo(f"  {k}: {','.join(map(str, sol.labels))}  sum|t|={sol.sum_abs}{extra}")
        if result.reason:
            click.echo(f"  {result.reason}", err=result.status == "unknown")
        if written:
            click.echo(f"wrote the first design to {output}")
        sys.stdout.flush()

    emit(ctx, data, human)
