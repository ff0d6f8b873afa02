"""``lkspace surfaces``: the scaffolds one graph admits, and the strand structures on each."""

from __future__ import annotations

from typing import Any

import click

from ..errors import UsageError
from ..words import plural
from .common import Context, emit, json_option, load_mesh
from .numbers import Count


@click.command("surfaces")
@click.argument("graph")
@click.option("--max-length", type=Count(3, 12), default=6, show_default=True, help="Longest cycle that may be a face.")
@click.option("--per-edge", type=Count(1, 6), default=2, show_default=True, help="Faces on every edge (2: surfaces).")
@click.option("--labels", "labels_spec", metavar="SET", help="Also count designs with labels from SET (e.g. -1..1).")
@click.option(
    "--own-faces", is_flag=True, help="MESH's own faces only: its radial orders and structures, coordinates ignored."
)
@json_option
def surfaces_cmd(
    graph: str, max_length: int, per_edge: int, labels_spec: str | None, own_faces: bool, as_json: bool
) -> None:
    """Choose cycles of GRAPH as faces, each edge on --per-edge faces; list the results up to automorphism.

    GRAPH is a named graph (K4, K5, cube, octahedron, K3,3, petersen) or a finite MESH
    whose edges are taken as the graph.  For each face set (a "cover"): how many covers it
    stands for, its automorphisms, its radial orders (edges on K >= 3 faces have (K-1)!),
    and the strand structures (radial orders and t mod K per edge) up to automorphism;
    with --labels, designs too.  --own-faces takes MESH's faces as they are: the
    structures of its radial orders and residues up to the automorphisms keeping them.

    \b
    Examples:
      lkspace surfaces K4 --max-length 4
      lkspace surfaces petersen --max-length 6 --labels -1..1
      lkspace surfaces K5 --max-length 3 --per-edge 3
      lkspace surfaces book:3 --own-faces
    """
    from ..design.embeddings import graph_surfaces, own_surface
    from ..design.graph_faces import NAMED_GRAPHS, named_graph
    from .common import label_set

    ctx = Context(as_json)
    if graph in NAMED_GRAPHS:
        n, edges = named_graph(graph)
    else:
        scaffold = load_mesh(ctx, graph)
        if scaffold.periodic:
            raise UsageError(f"{graph}: surfaces takes a finite graph; periodic nets are not supported yet")
        n, edges = scaffold.n_vertices, [(int(a), int(b)) for a, b in scaffold.edge_vertices.tolist()]
    labels = None if labels_spec is None else label_set(labels_spec).tolist()
    if own_faces and graph in NAMED_GRAPHS:
        raise UsageError("--own-faces takes a MESH (its faces), not a named graph")
    found = [own_surface(scaffold, labels)] if own_faces else graph_surfaces((n, edges), max_length, per_edge, labels)
    rows: list[dict[str, Any]] = [
        {
            "faces": [list(f) for f in s.faces],
            "covers": s.covers,
            "symmetry": s.symmetry,
            "radial_orders": s.radial_orders,
            "structures": s.structures,
            "designs": s.designs,
        }
        for s in found
    ]
    payload = {
        "graph": graph,
        "vertices": n,
        "edges": len(edges),
        "max_length": max_length,
        "per_edge": per_edge,
        "own_faces": own_faces,
        "label_set": labels,
        "surfaces": rows,
        "structures": sum(r["structures"] for r in rows),
        "designs": None if labels is None else sum(r["designs"] for r in rows),
    }

    def human() -> None:
        faces = "its own faces" if own_faces else f"faces of length <= {max_length}, {per_edge} per edge"
        click.echo(
            f"{graph}: {n} vertices, {len(edges)} edges; {faces}: "
            f"{plural(len(rows), 'face set')} up to automorphism, {plural(payload['structures'], 'strand structure')}"
        )
        for i, r in enumerate(rows):
            sizes = sorted(len(f) for f in r["faces"])
            extra = "" if r["designs"] is None else f", {plural(r['designs'], 'design')}"
            click.echo(
                f"  {i}: {len(sizes)} faces {sizes}, {plural(r['covers'], 'cover')}, symmetry {r['symmetry']}, "
                f"{plural(r['radial_orders'], 'radial order')}, {plural(r['structures'], 'structure')}{extra}"
            )

    emit(ctx, payload, human)
