"""``lkspace atlas``: every knot and link type a design space realizes (docs/design-to-target.md)."""

from __future__ import annotations

import os

import click

from ..knots.budget import TIME_LIMIT
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
)
from .export import is_catalog
from .numbers import Count, Finite


@click.command("atlas")
@mesh_argument
@labels_option
@click.option("--no-zero", is_flag=True, help="Leave label 0 out of the space.")
@click.option(
    "-o",
    "--output",
    "folder",
    type=click.Path(file_okay=False),
    default=None,
    help="Folder for atlas.parquet, README.md, the PNG gallery and the resumable cache.",
)
@click.option(
    "--pictures",
    type=Count(0, 200),
    default=12,
    show_default=True,
    help="PNG pictures of the simplest designs of the first N named types.",
)
@click.option("--processes", type=Count(1, 256), default=1, show_default=True, help="Worker processes identifying.")
@click.option(
    "--time-limit",
    type=Finite(0),
    default=TIME_LIMIT,
    show_default=True,
    metavar="S",
    help="CPU seconds per design for identification (past it: an unknown type); 0: no limit.",
)
@click.option(
    "--stop-after",
    type=Finite(0),
    default=0,
    metavar="S",
    help="Identify for at most S seconds of wall-clock time, then write the atlas of the designs done (complete: false); 0: no limit.",
)
@click.option("--seed", type=Count(0, 2**31 - 1), default=0, show_default=True, help="Projection seed.")
@json_option
def atlas_cmd(
    mesh: str | None,
    labels_spec: str,
    no_zero: bool,
    folder: str | None,
    pictures: int,
    processes: int,
    time_limit: float,
    stop_after: float,
    seed: int,
    as_json: bool,
) -> None:
    """List every knot and link type the designs of MESH with labels SET realize.

    Designs are taken up to rotation (a rotation keeps type and chirality) and
    identified; each type gets its number of designs and assignments and its simplest
    design (smallest sum |t|, then fewest non-zero labels).  With -o DIR: DIR/atlas.parquet,
    DIR/README.md (a Markdown table), DIR/*.png (pictures) and DIR/cache.jsonl, which
    makes an interrupted run resume.  MESH may be a catalog written by
    'enumerate --identify': its knot_name column is summed, nothing is identified.

    \b
    Examples:
      lkspace atlas tetrahedron --labels -1..1
      lkspace atlas cube --labels -1..1 -o cube-atlas --processes 2
      lkspace atlas designs.parquet --json
    """
    from ..knots.recognition import check_identifiable
    from ..linktypes.atlas import AtlasOptions, atlas
    from ..linktypes.atlas_catalog import atlas_of_catalog
    from ..linktypes.gallery import atlas_folder, write_gallery

    ctx = Context(as_json)
    if folder is not None:
        atlas_folder(folder, (mesh,))  # before any work
    scaffold = None
    if is_catalog(mesh):
        data = atlas_of_catalog(mesh)
    else:
        scaffold = load_mesh(ctx, mesh)
        check_identifiable(scaffold)
        labels = label_set(labels_spec)
        options = AtlasOptions(
            no_zero=no_zero,
            processes=processes,
            seed=seed,
            time_limit=time_limit or None,
            stop_after=stop_after or None,
            tolerance=symmetry_tolerance(),
        )
        data = atlas(scaffold, labels, folder, options)
    files: list[str] = []
    if folder is not None:
        files, data = write_gallery(folder, data, scaffold, pictures)
    out = {**data.to_json(), "written": [os.path.join(os.path.abspath(folder), f) for f in files] if folder else []}

    def human() -> None:
        took = f" [{data.run.wall_time:.1f} s]" if data.run is not None else ""
        click.echo(f"{data.scaffold}: {plural(data.designs, 'design')}, {plural(len(data.types), 'type')}{took}")
        if data.run is not None and not data.run.complete:
            click.echo(
                f"  partial: --stop-after reached, {data.run.skipped:,} designs not identified (rerun with -o to go on)"
            )
        for t in data.types:
            simplest = ",".join(map(str, t.simplest))
            table = f" ({t.table})" if t.table else ""
            click.echo(
                f"  {t.name:<24}{table:<19} {t.designs:>8,} {'design ' if t.designs == 1 else 'designs'}  simplest {simplest}"
            )
        if folder:
            click.echo(f"wrote {', '.join(files)} to {folder}")

    emit(ctx, out, human)
