"""``lkspace motifs``: labels of a supercell from a motif or a gradient, and what they make."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import click
import numpy as np

from ..errors import UsageError
from ..model.validation import MAX_LABEL
from ..words import plural
from .common import Context, emit, json_option, label_set, labels_option, load_mesh, usage_errors

if TYPE_CHECKING:
    from ..symmetry.group import SymmetryMode


MAX_INT = 10**6
"""Largest block size, offset or direction entry (a supercell holds at most 200000 faces)."""


def _integers(text: str, option: str, sep: str, example: str, bound: int = MAX_INT) -> list[int]:
    """Parse ``text`` as integers separated by ``sep``, each within ``-bound..bound`` (usage errors, one line)."""
    try:
        numbers = [int(x) for x in text.lower().split(sep)]
    except ValueError:
        raise UsageError(f"{option} {text[:60]!r}: expected integers such as {example}") from None
    if any(abs(n) > bound for n in numbers):
        raise UsageError(f"{option} {text[:60]!r}: integers must lie within -{bound}..{bound}")
    return numbers


def _sizes(text: str, option: str) -> list[int]:
    sizes = _integers(text, option, "x", "2x2 or 2x1x1")
    if min(sizes) < 1:
        raise UsageError(f"{option} {text!r}: sizes must be at least 1")
    return sizes


def _gradient(text: str, dim: int) -> tuple[list[int], list[int]]:
    direction, colon, values = text.partition(":")
    if not colon or not values:
        raise UsageError(f"--gradient {text[:60]!r}: expected DIRECTION:VALUES such as 1,0:0,1,2")
    d = _integers(direction, "--gradient", ",", "1,0:0,1,2")
    v = _integers(values, "--gradient", ",", "1,0:0,1,2", MAX_LABEL)
    if len(d) != dim:
        raise UsageError(f"--gradient {text!r}: the direction needs {dim} integers and at least one value")
    return d, v


@click.command("motifs")
@click.argument("mesh")
@click.option("--supercell", required=True, metavar="AxB[xC]", help="The supercell the motif fills.")
@click.option("--block", metavar="AxB[xC]", help="Cells of the motif (default one cell).")
@click.option("--offsets", metavar="S,...", default="", help="Offset pattern: entries below the tiling's diagonal.")
@click.option("--gradient", metavar="DIR:VALUES", help="Instead of motifs: label = VALUES[cell . DIR] on every edge.")
@labels_option
@click.option(
    "--symmetry",
    type=click.Choice(["rotations", "isometries", "none"]),
    default="rotations",
    show_default=True,
    help="Motifs whose supercell designs these motions relate are one class.",
)
@json_option
def motifs_cmd(
    mesh: str,
    supercell: str,
    block: str | None,
    offsets: str,
    gradient: str | None,
    labels_spec: str,
    symmetry: SymmetryMode,
    as_json: bool,
) -> None:
    """Repeat a motif (labels on a block of cells) over a supercell of the periodic MESH.

    Lists every motif with labels from --labels, one class per design up to the
    supercell's symmetry, with its components, thread periods and whether it holds
    together.  --offsets shifts the blocks row against row: --block 2x1 --offsets 1 is a
    brick bond.  --gradient traces one design whose labels follow the layers along a
    direction instead.  See docs/structured.md.

    \b
    Examples:
      lkspace motifs tiling:square --supercell 2x2 --labels -1..1
      lkspace motifs tiling:square --supercell 4x2 --block 2x1 --offsets 1 --labels -1,1
      lkspace motifs honeycomb:cP --supercell 4x1x1 --gradient 1,0,0:0,1,2,1
    """
    from ..design.motifs import cell_map, check_tiles, gradient_labels, motif_classes, tiling_matrix
    from ..strands.tracing import trace
    from ..symmetry.group import check_label_set, check_mode, symmetry_group

    ctx = Context(as_json)
    base = load_mesh(ctx, mesh)
    if not base.periodic:
        raise UsageError(f"{mesh}: motifs need a periodic scaffold (a tiling or honeycomb)")
    sizes = _sizes(supercell, "--supercell")
    sc = load_mesh(ctx, f"{mesh}@{'x'.join(map(str, sizes))}")
    base_edge, cell = cell_map(base, sc, sizes)
    rows: list[dict[str, Any]] = []
    found: list[tuple[np.ndarray | None, np.ndarray, int]]
    if gradient is not None:
        direction, values = _gradient(gradient, base.dim)
        found = [(None, gradient_labels(base_edge, cell, values, direction), 1)]
    else:
        with usage_errors():
            tiling = tiling_matrix(
                _sizes(block or "x".join(["1"] * base.dim), "--block"),
                _integers(offsets, "--offsets", ",", "1 or 1,0,2") if offsets else [],
            )
            if len(tiling) != base.dim:
                raise UsageError(f"--block: {mesh} has {base.dim} directions")
            check_tiles(tiling, sizes)
            labels = label_set(labels_spec)
            check_label_set(labels, symmetry)
        perms, signs = symmetry_group(sc).action(check_mode(symmetry))
        found = [
            (c.motif, c.labels, c.motifs) for c in motif_classes(base_edge, cell, tiling, labels.tolist(), perms, signs)
        ]
    for motif, labels_row, count in found:
        t = trace(sc, labels_row)
        periods = np.asarray(t.periods)
        rows.append(
            {
                "motif": None if motif is None else motif.tolist(),
                "labels": np.asarray(labels_row).tolist(),
                "motifs": count,
                "components": int(t.components),
                "holds_together": bool(t.holds_together),
                "n_infinite": int(np.any(periods != 0, axis=1).sum()),
                "periods": periods.tolist(),
            }
        )
    payload = {"supercell": sc.name, "edges": sc.n_edges, "symmetry": symmetry, "classes": rows}

    def human() -> None:
        click.echo(f"{sc.name}: {plural(len(rows), 'design')}")
        for i, r in enumerate(rows):
            what = f"motif {r['motif']}" if r["motif"] is not None else f"labels {r['labels']}"
            together = "holds together" if r["holds_together"] else "falls apart"
            click.echo(
                f"  {i}: {what} ({plural(r['motifs'], 'motif')}): {plural(r['components'], 'component')}, "
                f"{plural(r['n_infinite'], 'infinite thread')}, {together}"
            )

    emit(ctx, payload, human)
