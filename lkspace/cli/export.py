"""``lkspace export``: strand geometry to .obj, .ply, .glb or .png; also catalog rows."""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING, Any, TypeGuard, TypeVar, cast

import click
import numpy as np

from ..errors import CatalogError, TooLargeError, UsageError
from ..io.sources import reads_builtin
from ..model.scaffold import Scaffold
from ..words import plural
from .common import Context, emit, json_option, labels_of, load_mesh, nulls_of, weld_option
from .numbers import Count, Finite
from .relaxing import check_seed, relax_options, relaxed

if TYPE_CHECKING:
    from ..formats.options import FormatOptions, PictureOptions
    from ..geometry.realization import GeometryParams

F = TypeVar("F", bound=Callable[..., Any])

MAX_BLOCK_COPIES = 1000
"""Most lattice translates ``--block`` may ask for (the product of its sizes)."""


def is_catalog(path: str | None) -> TypeGuard[str]:
    """Whether MESH names a Parquet catalog (a ``.parquet`` file or a folder of parts; a built-in name never)."""
    if path is None:
        return False
    if path.endswith(".parquet"):
        return True
    if reads_builtin(path):  # a folder named like a built-in is written ./cube (lkspace.io.sources)
        return False
    return os.path.isdir(path) and any(n.endswith(".parquet") for n in os.listdir(path))


def catalog_row(path: str, row: int) -> tuple[Scaffold, np.ndarray]:
    """Return ``(scaffold, labels (n_edges,) int64)`` of row ``row`` of the catalog at ``path``.

    The catalog is checked first (:func:`lkspace.catalog.verify.open_catalog`: manifest
    and every part's footer), then the SHA-256 of the part holding the row; only that
    part's row group holding the row is read (its page checksums verified).
    """
    import pyarrow as pa
    import pyarrow.parquet as pq

    from ..catalog.settings import catalog_scaffold
    from ..catalog.verify import damaged, open_catalog

    parts = open_catalog(path)
    if parts.n_rows == 0:
        raise UsageError(f"{path}: the catalog has no rows")
    try:
        part, at = parts.locate(row)
    except IndexError:
        raise UsageError(f"{path}: row {row} out of range 0..{parts.n_rows - 1}") from None
    parts.verify(part)
    file = parts.files[part]
    try:
        parquet = pq.ParquetFile(file, page_checksum_verification=True)
        names = parquet.schema_arrow.names
        column = "key" if "key" in names else "labels"
        for group in range(parquet.metadata.num_row_groups):
            size = parquet.metadata.row_group(group).num_rows
            if at < size:
                cell = parquet.read_row_group(group, columns=[column]).column(0)[at].as_py()
                break
            at -= size
    except (OSError, pa.ArrowException) as exc:
        raise damaged(file, exc) from None
    values = np.frombuffer(cell, np.int8) if column == "key" else np.array(cell)
    labels = values.astype(np.int64)
    scaffold = catalog_scaffold(parts.footer, path)
    if len(labels) != scaffold.n_edges:
        raise CatalogError(f"{path} row {row}: {len(labels)} labels, but {scaffold.name} has {scaffold.n_edges} edges")
    return scaffold, labels


def design_options(func: F) -> F:
    """Add MESH, --twist, --null, --row and the geometry options shared by export and identify."""
    options = [
        click.argument("mesh", required=False, metavar="[MESH|CATALOG.parquet]"),
        weld_option,
        click.option(
            "--twist", "twist_spec", metavar="SPEC", help="One integer, a comma list per edge, or a file naming edges."
        ),
        click.option("--null", "null_spec", metavar="SPEC", help="Null edge-sides as FACE.SIDE, comma separated."),
        click.option("--row", type=Count(min=0), help="Row of CATALOG.parquet to use (instead of --twist)."),
        click.option(
            "--radius",
            "--inset",
            "radius",
            type=Finite(0, low_open=True),
            help="Inset: distance of the strands from their edge inside the face, > 0 (default 0.12 x shortest edge).",
        ),
        click.option(
            "--normal-offset",
            type=Finite(0),
            help="Offset of the strands along the face normal, >= 0 (default 0.35 x inset where faces nearly coincide).",
        ),
        click.option(
            "--tube-radius",
            type=Finite(0, low_open=True),
            help="Tube radius, > 0 (default from the mesh, the strand spacing and the tightest bend).",
        ),
    ]
    for option in reversed(options):
        func = option(func)
    return func


def resolve_design(
    ctx: Context, mesh: str | None, twist_spec: str | None, null_spec: str | None, row: int | None
) -> tuple[Scaffold, np.ndarray, np.ndarray | None]:
    """Return ``(scaffold, labels, nulls)`` from MESH + ``--twist``, or from a catalog row."""
    if is_catalog(mesh):
        if row is None:
            raise UsageError(f"{mesh}: give --row I to pick a design of the catalog")
        if twist_spec is not None:
            raise UsageError("--twist and a catalog --row are exclusive")
        scaffold, labels = catalog_row(mesh, row)
        ctx.notes.update(scaffold=scaffold.name, catalog=os.path.abspath(mesh), row=row)
        return scaffold, labels, nulls_of(scaffold, null_spec)
    if row is not None:
        raise UsageError("--row needs a catalog (.parquet) as MESH")
    scaffold = load_mesh(ctx, mesh)
    return scaffold, labels_of(scaffold, twist_spec), nulls_of(scaffold, null_spec)


def block_sizes(scaffold: Scaffold, spec: str | None) -> np.ndarray | None:
    """Return the sizes ``(dim,)`` of an ``AxBxC`` block, or ``None``."""
    if spec is None:
        return None
    if not scaffold.periodic:
        raise UsageError(f"--block {spec}: {scaffold.name} is not periodic")
    try:
        sizes = [int(x) for x in spec.lower().split("x")]
    except ValueError:
        raise UsageError(f"--block {spec!r}: expected sizes like 3x3 or 2x2x2") from None
    if len(sizes) != scaffold.dim or min(sizes) < 1:
        raise UsageError(f"--block {spec!r}: give {scaffold.dim} positive sizes for a {scaffold.dim}D lattice")
    copies = int(np.prod(sizes, dtype=object))
    if copies > MAX_BLOCK_COPIES:
        raise TooLargeError(f"--block {spec}: {copies:,} copies > {MAX_BLOCK_COPIES:,} (MAX_BLOCK_COPIES)")
    return np.array(sizes, np.int64)


def params_of(
    radius: float | None,
    normal_offset: float | None,
    tube_radius: float | None,
    helix_radius: float | None = None,
    pitch: float | None = None,
) -> GeometryParams:
    """Return the :class:`~lkspace.geometry.realization.GeometryParams` of the geometry options."""
    from ..geometry.realization import GeometryParams

    return GeometryParams(
        radius=radius, normal_offset=normal_offset, tube_radius=tube_radius, helix_radius=helix_radius, pitch=pitch
    )


def format_options(
    ext: str,
    tubes: bool,
    thickness: float | None,
    clearance: float | None,
    units: str | None,
    scale: float,
    picture: PictureOptions | None,
) -> FormatOptions:
    """Return the options record of format ``ext`` from the fabrication flags and ``--tubes``.

    ``--units`` is a comment of ``.obj`` and ``.ply`` only (left out of other formats),
    ``--clearance`` is checked on tubes only (``--tubes``, ``.glb``, pictures, printable formats;
    refused for curves), ``--thickness`` and ``--scale`` set every tube.
    ``picture`` holds the picture flags of a ``.png`` or ``.svg`` (refused for other formats).
    """
    from ..formats.options import GlbOptions, MeshOptions, PictureOptions, PrintOptions
    from ..formats.registry import PICTURES, PRINTABLE
    from ..geometry.fabrication import Units

    if ext in PRINTABLE:
        return PrintOptions(thickness, clearance, cast(Units, units or "mm"), scale)
    if not tubes and ext not in (".glb", *PICTURES) and clearance is not None:
        raise UsageError(
            f"--clearance is checked on tubes, and a {ext} file holds the strands as curves: "
            "add --tubes, or leave --clearance out"
        )
    if ext == ".glb":
        return GlbOptions(thickness=thickness, scale=scale, clearance=clearance)
    if ext in PICTURES:
        return replace(picture or PictureOptions(), thickness=thickness, scale=scale, clearance=clearance)
    return MeshOptions(thickness=thickness, scale=scale, clearance=clearance, tubes=tubes, units=cast(Units, units))


FORMAT_HELP = "Output file: .obj, .ply, .glb, .stl, .3mf, .png or .svg (the format follows the extension)."


def picture_options(func: F) -> F:
    """Add the picture options --view, --size, --background, --colors, --diagram, --title."""
    options = [
        click.option(
            "--view",
            metavar="AZ,EL|NAME",
            help="Pictures: azimuth,elevation in degrees, or iso, front, back, left, right, top, bottom.",
        ),
        click.option("--size", metavar="WxH", help="Pictures: width x height in pixels (default 900x900)."),
        click.option("--background", metavar="COLOR", help="Pictures: 'transparent' or a colour (default white)."),
        click.option(
            "--colors", metavar="LIST", help="Pictures: colours per strand, a comma list or colormap; or gradient."
        ),
        click.option(
            "--diagram", is_flag=True, help="Pictures: draw the simplified 2D knot/link diagram instead of 3D tubes."
        ),
        click.option("--title", help="Pictures: a title above the picture."),
    ]
    for option in reversed(options):
        func = option(func)
    return func


def fabrication_options(func: F) -> F:
    """Add --thickness, --clearance, --units and --scale (printable .stl/.3mf)."""
    options = [
        click.option(
            "--thickness",
            type=Finite(0, low_open=True),
            help="Tube diameter in output units, > 0 (.stl/.3mf; sets the tube of the other formats too).",
        ),
        click.option(
            "--clearance",
            type=Finite(0),
            help="Least gap between distinct pieces in output units, >= 0; checked on the final tubes.",
        ),
        click.option(
            "--units",
            type=click.Choice(["mm", "cm", "m", "in", "ft", "um"]),
            help="What one output unit is: the 3MF unit and STL header (default mm), a PLY/OBJ comment.",
        ),
        click.option(
            "--scale",
            type=Finite(0, low_open=True),
            default=1.0,
            help="Output units per scaffold unit (.stl/.3mf; default 1).",
        ),
    ]
    for option in reversed(options):
        func = option(func)
    return func


@click.command("export")
@design_options
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False), help=FORMAT_HELP)
@click.option(
    "--tubes", is_flag=True, help="Write tube meshes instead of polylines (.obj, .ply; other formats are tubes)."
)
@click.option("--no-mesh", is_flag=True, help="Leave the input mesh out of the picture (.png, .svg).")
@click.option(
    "--block",
    metavar="AxB[xC]",
    help="Periodic scaffolds: an A x B (x C) block of cells, threads cut at its faces.",
)
@click.option(
    "--helix-radius",
    type=Finite(0, low_open=True),
    help="Distance of the evenly spaced strands from the edge axis, > 0 (default about the inset).",
)
@click.option(
    "--pitch",
    type=Finite(0, low_open=True),
    help="Axial length of one full helix turn, > 0 (default: the twist spreads over the whole edge).",
)
@relax_options
@fabrication_options
@picture_options
@json_option
def export_cmd(
    mesh: str | None,
    twist_spec: str | None,
    null_spec: str | None,
    row: int | None,
    radius: float | None,
    normal_offset: float | None,
    tube_radius: float | None,
    output: str,
    tubes: bool,
    no_mesh: bool,
    block: str | None,
    helix_radius: float | None,
    pitch: float | None,
    relax: bool,
    relax_steps: int | None,
    relax_time: float | None,
    relax_fine: bool,
    relax_points: int | None,
    relax_escape: int | None,
    relax_seed: int | None,
    thickness: float | None,
    clearance: float | None,
    units: str | None,
    scale: float,
    view: str | None,
    size: str | None,
    background: str | None,
    colors: str | None,
    diagram: bool,
    title: str | None,
    as_json: bool,
) -> None:
    """Realize the strands of MESH labelled by --twist and write them to -o FILE.

    \b
    Examples:
      lkspace export dihedron:3 --twist 1 -o trefoil.png
      lkspace export dihedron:3 --twist 1 --diagram -o trefoil.svg
      lkspace export dihedron:3 --twist 1 --relax -o tight-trefoil.png
      lkspace export dodecahedron --twist 1 --relax-time 60 -o tight.obj
      lkspace export tetrahedron --twist 1 -o borromean.glb
      lkspace export cube --twist 2 -o chainmail.stl --thickness 0.1 --clearance 0.05 --scale 10
      lkspace export honeycomb:cP --twist 2,1,1 --block 2x2x2 -o block.png --size 480x480
      lkspace export designs.parquet --row 7 -o design7.png
    """
    from ..formats.options import PictureOptions, PrintOptions
    from ..formats.registry import PICTURES, export, output_target, point_budget
    from ..geometry.params import RealizeOptions
    from ..geometry.realization import realize

    ctx = Context(as_json)
    output_target(output, (mesh, twist_spec, null_spec))  # checked before any work (export checks it again)
    ext = os.path.splitext(output)[1].lower()
    picture = None
    if ext in PICTURES:
        from ..formats.render import look_of

        look = look_of(view, size, background, colors)
        picture = PictureOptions(look=look, diagram=diagram, show_mesh=not no_mesh, title=title)  # checks the title
    elif diagram or any(v is not None for v in (view, size, background, colors)):
        raise UsageError(
            f"--view, --size, --background, --colors and --diagram are for pictures (.png, .svg), not {ext}"
        )
    if thickness is not None and tube_radius is not None:
        raise UsageError("--thickness (a diameter in output units) and --tube-radius are exclusive")
    check_seed(relax_seed, relax_escape)
    more = (
        relax_fine,
        relax_points is not None,
        relax_escape is not None,
        relax_steps is not None,
        relax_time is not None,
    )
    relax = relax or any(more)
    scaffold, labels, nulls = resolve_design(ctx, mesh, twist_spec, null_spec, row)
    params = params_of(radius, normal_offset, tube_radius, helix_radius, pitch)
    sizes = block_sizes(scaffold, block)
    if sizes is not None:
        from ..geometry.block import realize_block

        then = (
            (lambda r: relaxed(r, relax_steps, relax_time, relax_fine, relax_points, relax_escape, relax_seed))
            if relax
            else None
        )
        with point_budget(output, tubes) as max_points:
            real = realize_block(scaffold, labels, nulls, params, sizes, max_points=max_points, relax=then)
    else:
        with point_budget(output, tubes) as max_points:
            real = realize(scaffold, labels, nulls, params, options=RealizeOptions(max_points=max_points))
            if relax:
                real = relaxed(real, relax_steps, relax_time, relax_fine, relax_points, relax_escape, relax_seed)
    options = format_options(ext, tubes, thickness, clearance, units, scale, picture)
    pieces = None
    if isinstance(options, PrintOptions):
        from ..geometry.fabrication import printable

        pieces = printable(real, thickness, clearance, options.units, scale)
        options = replace(options, pieces=pieces)
    fmt = export(real, output, options=options)
    data = {
        "written": os.path.abspath(output),
        "format": fmt,
        "labels": np.asarray(labels).tolist(),
        "components": real.trace.components,
        **real.summary(),
    }
    data.pop("closed")
    if sizes is not None:
        data["block"] = [int(n) for n in sizes]
    if thickness is not None and pieces is None:  # the tube that was written
        data["tube_radius"] = thickness / 2 / scale
    human = (
        f"wrote {output}: {plural(real.n_curves, 'strand')} of {scaffold.name}, "
        f"minimum distance between {'strands' if real.n_curves > 1 else 'distant parts of the strand'} "
        f"{real.min_distance:.3g} (tube radius {data['tube_radius']:.3g})"
    )
    if pieces is not None:
        data["fabrication"] = pieces.summary()
        gap = f"> {pieces.clearance + pieces.radius:.4g}" if pieces.min_gap is None else f"{pieces.min_gap:.4g}"
        human = (
            f"wrote {output}: {plural(len(pieces.curves), 'piece')} of {scaffold.name}, thickness {2 * pieces.radius:.4g} "
            f"{pieces.units}, smallest gap {gap} {pieces.units} (clearance {pieces.clearance:.4g})"
        )
    emit(ctx, data, lambda: click.echo(human))
