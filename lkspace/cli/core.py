"""``lkspace scaffold``, ``info`` and ``trace``."""

from __future__ import annotations

import os

import click
import numpy as np
from rich.console import Console
from rich.table import Table

from .. import io
from ..scaffolds import builtin
from ..symmetry import symmetry_group
from ..tracing import trace
from .common import Context, emit, json_option, load_mesh, mesh_argument, nulls_of, twists_of


def _console() -> Console:
    return Console(highlight=False, soft_wrap=False, width=max(100, Console().width))


@click.command("scaffold")
@click.argument("name")
@click.option(
    "-o", "--output", type=click.Path(dir_okay=False), help="File to write (.obj or .json); default: JSON on stdout."
)
@json_option
def scaffold_cmd(name, output, as_json):
    """Write the built-in scaffold NAME to a file.

    \b
    Built-in names:
      tetrahedron, cube, octahedron,      the Platonic solids
      dodecahedron, icosahedron
      truncated-octahedron                6 squares + 8 hexagons
      dihedron:N                          two-sided regular N-gon (two faces, one N-cycle)
      book:K                              K quads sharing one edge at equal angles
      cube-net, cube-lid                  a cube unfolded flat; an open box with a lid
      cubes:piano, cubes:vertex           two cubes sharing an edge; sharing a vertex
      figure-eight                        the paper's 4_1 mesh (design as default twists)
      whitehead                           the paper's L5a1 mesh (design as default twists)
      tiling:square, tiling:hexagonal     the 2D Wigner-Seitz tilings (periodic)
      honeycomb:cP                        cubes; edge classes x, y, z
      honeycomb:hP                        hexagonal prisms
      honeycomb:oF                        face-centred orthorhombic cells (a,b,c = 1,1.25,1.5)
      honeycomb:cF                        rhombic dodecahedra
      honeycomb:cI                        truncated octahedra
      voronoi:cube-faces                  Voronoi cells of a cubic lattice with points at
                                          the cube's face centres (the paper's figure)
      NAME@AxBxC                          A x B x C supercell of a periodic NAME (AxB in 2D)

    \b
    A .json file {"format": "lkspace-voronoi", "lattice": [...], "points": [...]}
    gives a Voronoi scaffold of your own generator points.
    """
    ctx = Context(as_json)
    scaffold = builtin(name)
    if output is None:
        if as_json:
            emit(ctx, {"scaffold": name, "written": None, "data": io.scaffold_json.scaffold_to_dict(scaffold)}, None)
        else:
            click.echo(io.format_scaffold_json(scaffold), nl=False)
        return
    io.write(scaffold, output)
    emit(
        ctx,
        {
            "scaffold": name,
            "written": os.path.abspath(output),
            "vertices": scaffold.n_vertices,
            "edges": scaffold.n_edges,
            "faces": scaffold.n_faces,
        },
        lambda: click.echo(
            f"wrote {name} to {output} ({scaffold.n_vertices} vertices, "
            f"{scaffold.n_edges} edges, {scaffold.n_faces} faces)"
        ),
    )


def info_dict(scaffold) -> dict:
    """Counts and incidence summary of a scaffold (the ``info`` JSON)."""
    degrees = scaffold.edge_degrees
    hist = np.bincount(degrees)
    sizes = np.bincount(scaffold.face_sizes)
    out = {
        "name": scaffold.name,
        "vertices": scaffold.n_vertices,
        "edges": scaffold.n_edges,
        "faces": scaffold.n_faces,
        "corners": scaffold.n_corners,
        "edge_degrees": {str(k): int(n) for k, n in enumerate(hist) if n},
        "face_sizes": {str(k): int(n) for k, n in enumerate(sizes) if n},
        "boundary_edges": int(np.sum(degrees == 1)),
        "non_manifold_edges": int(np.sum(degrees >= 3)),
        "periodic": scaffold.periodic,
        "lattice": scaffold.lattice.basis.tolist() if scaffold.periodic else None,
        "content_hash": scaffold.content_hash(),
    }
    if not scaffold.periodic:
        out["euler_characteristic"] = scaffold.n_vertices - scaffold.n_edges + scaffold.n_faces
    return out


@click.command("info")
@mesh_argument
@json_option
def info_cmd(mesh, as_json):
    """Counts, edge-degree histogram, boundary and non-manifold edges of MESH."""
    ctx = Context(as_json)
    scaffold = load_mesh(ctx, mesh)
    scaffold.radial  # validates the radial order
    data = info_dict(scaffold)
    group = symmetry_group(scaffold)
    data["symmetry_group_order"] = {"rotations": group.n_rotations, "isometries": group.order}

    def human():
        table = Table(title=f"{scaffold.name}", show_header=False, box=None)
        for key, value in data.items():
            if value is not None:
                table.add_row(key.replace("_", " "), str(value))
        _console().print(table)

    emit(ctx, data, human)


@click.command("trace")
@mesh_argument
@click.option(
    "--twist", "twist_spec", metavar="SPEC", help="One integer, a comma list per edge, or a file naming edges."
)
@click.option("--null", "null_spec", metavar="SPEC", help="Null edge-sides as FACE.SIDE, comma separated.")
@json_option
def trace_cmd(mesh, twist_spec, null_spec, as_json):
    """Trace the strands of MESH labelled by --twist."""
    ctx = Context(as_json)
    scaffold = load_mesh(ctx, mesh)
    twists = twists_of(scaffold, twist_spec)
    result = trace(scaffold, twists, nulls_of(scaffold, null_spec))
    data = result.to_dict()
    data["twists"] = twists.tolist()

    def human():
        con = _console()
        con.print(
            f"{scaffold.name}: {result.components} component(s), "
            f"{'holds together' if result.holds_together else 'falls apart'}"
        )
        if scaffold.periodic:
            con.print(
                f"threads per module: {data['threads_per_module']} "
                f"({data['closed_loops']} closed loops, {data['infinite_threads']} infinite threads)"
            )
        table = Table("strand", "closed", "length", "period", "faces")
        for k, s in enumerate(data["strands"]):
            faces = " ".join(map(str, s["faces"][:24])) + (" …" if len(s["faces"]) > 24 else "")
            table.add_row(
                str(k),
                "yes" if s["closed"] else "no",
                str(s["length"]),
                "-" if s["period"] is None else str(s["period"]),
                faces,
            )
        con.print(table)

    emit(ctx, data, human)
