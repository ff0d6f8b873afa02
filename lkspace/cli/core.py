"""``lkspace scaffold``, ``info`` and ``trace``."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

import click
import numpy as np

from .. import io
from ..errors import UsageError
from ..io.paths import output_file
from ..io.scaffold_json import format_scaffold_json, scaffold_to_dict
from ..model.scaffold import Scaffold
from ..strands.tracing import trace
from ..words import plural
from .common import (
    Context,
    emit,
    json_option,
    labels_of,
    load_mesh,
    mesh_argument,
    nulls_of,
    symmetry_facts,
    usage_errors,
    weld_option,
)

if TYPE_CHECKING:
    from rich.console import Console


def _console() -> Console:
    from rich.console import Console

    return Console(highlight=False, soft_wrap=False, width=max(100, Console().width))


@click.command("scaffold")
@click.argument("name", metavar="NAME|FILE")
@click.option(
    "-o", "--output", type=click.Path(dir_okay=False), help="File to write (.obj or .json); default: JSON on stdout."
)
@weld_option
@json_option
def scaffold_cmd(name: str, output: str | None, as_json: bool) -> None:
    """Write the built-in scaffold NAME (or convert FILE, .obj or .json) to a file.

    \b
    Built-in names:
      tetrahedron, cube, octahedron,      the Platonic solids
      dodecahedron, icosahedron
      truncated-tetrahedron               4 triangles + 4 hexagons
      cuboctahedron                       8 triangles + 6 squares
      truncated-octahedron                6 squares + 8 hexagons
      prism:N, antiprism:N                uniform N-gonal prism, antiprism, 3 <= N <= 1000
      dihedron:N                          two-sided regular N-gon (two faces, one N-cycle), N <= 1000
      book:K                              K quads sharing one edge at equal angles, K <= 1000
      kaleidocycle:K                      a ring of K tetrahedra hinged edge to edge, K even
      cube-net, cube-lid                  a cube unfolded flat; an open box with a lid
      cubes:piano, cubes:vertex           two cubes sharing an edge; sharing a vertex
      figure-eight                        the paper's 4_1 mesh (design as default labels)
      whitehead                           the paper's L5a1 mesh (design as default labels)
      tiling:square, tiling:hexagonal     the 2D Wigner-Seitz tilings (periodic)
      honeycomb:cP                        cubes; edge classes x, y, z
      honeycomb:hP                        hexagonal prisms
      honeycomb:oF                        face-centred orthorhombic cells (a,b,c = 1,1.25,1.5)
      honeycomb:cF                        rhombic dodecahedra
      honeycomb:cI                        truncated octahedra
      laves                               the Laves graph (srs net): 10-rings as faces
      voronoi:cube-faces                  Voronoi cells of a cubic lattice with points at
                                          the cube's face centres (the paper's figure)
      NAME@AxBxC                          A x B x C supercell of a periodic NAME (AxB in 2D),
                                          at most 200000 faces

    \b
    A FILE is converted: 'lkspace scaffold mesh.obj --weld -o mesh.json' welds an OBJ
    with one vertex copy per face and writes the scaffold file.
    A built-in name always means the built-in (in every command), even where a file
    or folder of that name exists here: write ./cube or cube.obj to read a file.
    A .json file {"format": "lkspace-voronoi", "lattice": [...], "points": [...]}
    gives a Voronoi scaffold of your own generator points.
    """
    ctx = Context(as_json)
    target = None
    if output is not None:
        with usage_errors():
            target = output_file(output, (".obj", ".json"), (name,))
    scaffold = load_mesh(ctx, name)
    if output is None or target is None:
        if as_json:
            emit(
                ctx, {"scaffold": scaffold.name, "written": None, "data": scaffold_to_dict(scaffold)}, None, exact=True
            )
        else:
            click.echo(format_scaffold_json(scaffold), nl=False)
        return
    if scaffold.periodic and target.lower().endswith(".obj"):
        raise UsageError(f"{scaffold.name}: OBJ cannot hold a periodic scaffold; write a .json scaffold file")
    io.write(scaffold, output)
    emit(
        ctx,
        {
            "scaffold": scaffold.name,
            "written": os.path.abspath(output),
            "vertices": scaffold.n_vertices,
            "edges": scaffold.n_edges,
            "faces": scaffold.n_faces,
        },
        lambda: click.echo(
            f"wrote {scaffold.name} to {output} ({scaffold.n_vertices} vertices, "
            f"{scaffold.n_edges} edges, {scaffold.n_faces} faces)"
        ),
    )


def info_dict(scaffold: Scaffold) -> dict[str, Any]:
    """Return the counts and incidence summary of a scaffold (the ``info`` JSON)."""
    degrees = scaffold.edge_degrees
    hist = np.bincount(degrees)
    sizes = np.bincount(scaffold.face_sizes)
    out: dict[str, Any] = {
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
        "lattice": scaffold.lattice.basis.tolist() if scaffold.lattice is not None else None,
        "content_hash": scaffold.content_hash(),
    }
    if not scaffold.periodic:
        out["euler_characteristic"] = scaffold.n_vertices - scaffold.n_edges + scaffold.n_faces
    return out


def edge_list(scaffold: Scaffold) -> list[dict[str, Any]]:
    """Return every edge: index, vertex pair (0-based and 1-based as in OBJ files), degree, name."""
    out = []
    for e, ((a, b), k) in enumerate(zip(scaffold.edge_vertices.tolist(), scaffold.edge_degrees.tolist(), strict=True)):
        entry = {"index": e, "a": a, "b": b, "a_obj": a + 1, "b_obj": b + 1, "degree": k, "name": scaffold.edge_name(e)}
        if scaffold.periodic:
            entry["offset"] = scaffold.edge_deltas[e].tolist()
        out.append(entry)
    return out


@click.command("info")
@mesh_argument
@click.option(
    "--edges", "list_edges", is_flag=True, help="List every edge: index, vertex pair (0- and 1-based), degree."
)
@json_option
def info_cmd(mesh: str | None, list_edges: bool, as_json: bool) -> None:
    """Show counts, edge-degree histogram, boundary and non-manifold edges, symmetry of MESH.

    \b
    With --edges, every edge in edge order (the order of --twist lists): its index, its
    vertex pair 0-based (as in twist files) and 1-based (as in the OBJ file), its degree
    K (number of faces on it) and its name (periodic: with the offset of its end b).
    """
    ctx = Context(as_json)
    scaffold = load_mesh(ctx, mesh)
    scaffold.radial  # validates the radial order
    data = info_dict(scaffold)
    data.update(symmetry_facts(scaffold))  # periodic: the orders without the group's tables
    data["n_edges"] = scaffold.n_edges
    if list_edges:  # the JSON field "edges" then holds the list (n_edges keeps the count)
        data["edges"] = edge_list(scaffold)

    def human() -> None:
        from rich.table import Table

        table = Table(title=f"{scaffold.name}", show_header=False, box=None)
        hidden = {"symmetry_note", "n_edges"} | ({"symmetry_group_order"} if "group" in data else set())
        for key, value in data.items():  # n_edges and the group order repeat "edges" and "group"
            if value is not None and not isinstance(value, list) and key not in hidden:
                shown = f"{value:.3g}" if key == "symmetry_tolerance" else str(value)
                table.add_row(key.replace("_", " "), shown)
        _console().print(table)
        if list_edges:
            edges = Table("edge", "a-b", "OBJ a-b", "degree", "name", title="edges (edge order)")
            for row in data["edges"]:
                edges.add_row(
                    str(row["index"]), f"{row['a']}-{row['b']}", f"{row['a_obj']}-{row['b_obj']}", str(row["degree"]),
                    row["name"],
                )  # fmt: skip
            _console().print(edges)

    emit(ctx, data, human)


KINDS = {"loop": "closed loop", "thread": "infinite thread", "open": "open"}
"""What the trace table shows for each strand kind of :attr:`~lkspace.strands.tracing.Trace.strand_kinds`."""


@click.command("trace")
@mesh_argument
@click.option(
    "--twist", "twist_spec", metavar="SPEC", help="One integer, a comma list per edge, or a file naming edges."
)
@click.option("--null", "null_spec", metavar="SPEC", help="Null edge-sides as FACE.SIDE, comma separated.")
@json_option
def trace_cmd(mesh: str | None, twist_spec: str | None, null_spec: str | None, as_json: bool) -> None:
    """Trace the strands of MESH labelled by --twist."""
    ctx = Context(as_json)
    scaffold = load_mesh(ctx, mesh)
    result = trace(scaffold, labels_of(scaffold, twist_spec), nulls_of(scaffold, null_spec))
    data = result.to_dict()

    def human() -> None:
        from .boxes import box_table  # rich's look without rich's import time: trace is a start-up figure

        click.echo(
            f"{scaffold.name}: {plural(result.components, 'component')}, "
            f"{'holds together' if result.holds_together else 'falls apart'}"
        )
        if scaffold.periodic:
            click.echo(
                f"threads per module: {data['threads_per_module']} "
                f"({plural(data['closed_loops'], 'closed loop')}, {plural(data['infinite_threads'], 'infinite thread')})"
            )
        rows = [
            [
                str(k),
                KINDS[s["kind"]],
                str(s["length"]),
                "-" if s["period"] is None else str(s["period"]),
                " ".join(map(str, s["faces"][:24])) + (" …" if len(s["faces"]) > 24 else ""),
            ]
            for k, s in enumerate(data["strands"])
        ]
        click.echo(box_table(["strand", "kind", "length", "period", "faces"], rows))

    emit(ctx, data, human)
