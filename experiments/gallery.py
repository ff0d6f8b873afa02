"""The paper's gallery, regenerated from built-in scaffolds with the installed ``lkspace`` CLI.

Every picture is made by ``lkspace export`` and every number in the table by ``lkspace
trace --json`` or ``lkspace identify --json``; nothing is typed in by hand except the
paper's claim each picture checks (quoted from ``twisted-edges.tex``).  Writes
``results/gallery/*.png`` (480 x 480, palette-quantized by Pillow to stay small) and
``results/gallery/README.md``.

Run: ``python experiments/gallery.py`` (about two minutes on 2 cores).
``--renderer blender`` draws the 3D pictures with Blender's Cycles instead (``python -m
lkspace.blender render``, extra ``[blender]``; knot diagrams stay lkspace's).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from dataclasses import dataclass, field

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "results", "gallery")
SIZE = "480x480"
MAX_BYTES = 150_000


@dataclass
class Entry:
    """One picture: the design, how to draw it, the claim it checks and how to measure it."""

    file: str
    mesh: str
    twist: str | None
    claim: str
    check: str = "trace"  # "trace" or "identify"
    draw: list[str] = field(default_factory=list)
    expect: str = ""  # what the measurement must show for the claim to hold (said in the table)


def entries() -> list[Entry]:
    """The gallery, in the paper's order."""
    e = Entry
    return [
        e("cube-chainmail.png", "cube", "2", "fig:teaser (a): positive even twists on a cube give a chainmail-like link "
          "(6 face loops, interlinked).", expect="6 components, holds together"),
        e("cube-one-even.png", "cube", "2,1,1,1,1,1,1,1,1,1,1,1", "fig:teaser (b): 'one even-twisted edge and all others "
          "odd' gives a single unicursal knot.", expect="1 component"),
        e("cube-knot.png", "cube", "1,1,1,1,1,1,1,1,1,2,2,2", "fig:teaser (b), as a parity count shows it: a cube knot "
          "needs 3 to 7 even edges (the odd edges a spanning tree of the dual octahedron).", expect="1 component"),
        e("cube-net.png", "cube-net", "1", "fig:teaser (c): an unfolded cube (a disk) with odd twists on "
          "its folds is one articulated knot.", expect="1 component", draw=["--view", "-60,60"]),
        e("cube-lid.png", "cube-lid", "2", "fig:teaser (d), fig:lidexample: a cube with a lid; even twists keep the six face "
          "loops, linked across the hinge.", expect="6 components, holds together"),
        e("cubes-piano.png", "cubes:piano", "1", "fig:teaser (e), fig:hinge_types (b): two cubes joined by a piano hinge (an edge "
          "of degree 4) give one connected structure.", expect="holds together"),
        e("cubes-vertex.png", "cubes:vertex", "1", "fig:hinge_types (a): cubes joined only at a vertex cannot hang together.",
          expect="falls apart"),
        e("trefoil.png", "dihedron:3", "1", "fig:prime_knots (a): a two-sided triangle gives the trefoil 3_1.",
          check="identify", expect="3_1"),
        e("trefoil-relaxed.png", "dihedron:3", "1", "The same trefoil relaxed (`--relax`): drawn tight without changing the type.",
          check="identify", expect="3_1", draw=["--relax"]),
        e("knot-5-1.png", "dihedron:5", "1", "fig:prime_knots (c, d): a two-sided pentagon gives 5_1 (and a heptagon 7_1: "
          "`lkspace identify dihedron:7 --twist 1`).", check="identify",
          expect="5_1", draw=["--diagram"]),
        e("figure-eight.png", "figure-eight", None, "fig:prime_knots (b): two triangles in front, a quadrilateral behind: "
          "the figure-eight knot 4_1.", check="identify", expect="4_1"),
        e("figure-eight-relaxed.png", "figure-eight", None, "The figure-eight knot relaxed (`--relax`).", check="identify",
          expect="4_1", draw=["--relax"]),
        e("borromean.png", "tetrahedron", "1", "fig:prime_links (a): every edge of a tetrahedron twisted once gives the "
          "Borromean rings.", check="identify", expect="L6a4"),
        e("borromean-relaxed.png", "tetrahedron", "1", "The Borromean rings relaxed (`--relax`).", check="identify",
          expect="L6a4", draw=["--relax"]),
        e("borromean-diagram.png", "tetrahedron", "1", "The Borromean rings as a link diagram, components coloured.",
          check="identify", expect="L6a4", draw=["--diagram"]),
        e("whitehead.png", "whitehead", None, "fig:prime_links (b): a square fanned into four triangles, no back: the "
          "Whitehead link.", check="identify", expect="L5a1"),
        e("solomon.png", "dihedron:4", "1", "fig:prime_links (c): a two-sided square gives the Solomon link T(2,4).",
          check="identify", expect="L4a1", draw=["--diagram"]),
        e("torus-2-8.png", "dihedron:8", "1", "fig:prime_links (d): the (2,8) torus link from a two-sided polygon "
          "(here the octagon, twist 1 on every edge).", check="identify", expect="L8a14", draw=["--diagram"]),
        e("truncated-octahedron.png", "truncated-octahedron", "1", "fig:teaser2: LK structures from a truncated "
          "octahedron; twist 1 everywhere: 6 loops of 12 corners.", expect="6 components"),
        e("square-weave.png", "tiling:square", "1", "fig:bravais2D_repeated (a): one twist on the square tiling gives the biaxial "
          "weave (2 threads per module).", expect="2 components", draw=["--block", "4x4"]),
        e("square-chainmail.png", "tiling:square", "2", "fig:bravais2D_repeated (a): two twists give square chainmail (one loop "
          "per square, interlinked).", expect="1 component, holds together", draw=["--block", "4x4"]),
        e("hexagonal-weave.png", "tiling:hexagonal", "1", "fig:bravais2D_repeated (b): one twist on the hexagonal tiling gives the "
          "triaxial weave (3 threads per module).", expect="3 components", draw=["--block", "4x4"]),
        e("hexagonal-chainmail.png", "tiling:hexagonal", "2", "fig:bravais2D_repeated (b): two twists give hexagonal chainmail.",
          expect="1 component, holds together", draw=["--block", "4x4"]),
        e("cP-2-1-1.png", "honeycomb:cP", "2,1,1", "fig:cp_single top row, labels [2,1,1]: one infinite thread repeating in a "
          "4x2x2 domain.", expect="1 component, period [-4, 0, 0]", draw=["--block", "2x2x2"]),
        e("cP-1-3-1.png", "honeycomb:cP", "1,3,1", "fig:cp_multiple top row, labels [1,3,1]: two distinct threads, 1x2x1 "
          "repeating domain.", expect="2 components, periods [0, 2, 0]", draw=["--block", "2x2x2"]),
        e("kaleidocycle.png", "kaleidocycle:6", "solve:1", "fig:flexagon: tetrahedra hinged edge to edge in "
          "a ring merge into a single knot; labels found by `lkspace solve kaleidocycle:6 --components 1`.",
          expect="1 component", draw=["--view", "-60,50"]),
        e("laves.png", "laves", "1", "fig:laves_intro: the Laves graph's 10-rings as faces: every edge lies on 10 of "
          "them, every vertex on 15.", check="info", expect="edge degrees {10: 6}, 60 corners = 4 vertices x 15",
          draw=["--block", "1x1x1"]),
        e("cI-1.png", "honeycomb:cI", "1", "fig:bravais3D_repeated_cf: truncated octahedra (cI); uniform twisting gives 7 components "
          "per module for every twist number (one cubic cell drawn).", expect="7 components", draw=["--block", "1x1x1"]),
    ]  # fmt: skip


def labels_of(entry: Entry) -> str | None:
    """The entry's ``--twist``; ``solve:N`` asks ``lkspace solve`` for labels with N components."""
    if entry.twist is None or not entry.twist.startswith("solve:"):
        return entry.twist
    found = run(["solve", entry.mesh, "--components", entry.twist.split(":")[1]])
    return ",".join(str(t) for t in found["solutions"][0]["labels"])


def run(args: list[str]) -> dict:
    """Run the installed ``lkspace`` with ``--json``; return its JSON object."""
    proc = subprocess.run(["lkspace", *args, "--json"], capture_output=True, text=True, check=False)
    try:
        return json.loads(proc.stdout.strip().splitlines()[-1])
    except (IndexError, json.JSONDecodeError):
        return {"error": {"message": proc.stderr.strip()}}


def render_blender(entry: Entry, path: str) -> dict:
    """Draw ``entry`` with Blender headless; return ``{}`` or ``{"error": ...}`` like :func:`run`."""
    block = entry.draw[entry.draw.index("--block") :][:2] if "--block" in entry.draw else []
    args = [entry.mesh, "--twist", entry.twist or "", "-o", path, "--size", SIZE, *block]
    proc = subprocess.run([sys.executable, "-m", "lkspace.blender", "render", *args], capture_output=True, text=True)
    return {} if proc.returncode == 0 else {"error": {"message": proc.stderr.strip()}}


def shrink(path: str) -> int:
    """Quantize the PNG to a 256-colour palette (Pillow) when that makes it smaller; return its size."""
    from PIL import Image

    size = os.path.getsize(path)
    with Image.open(path) as img:
        small = img.convert("RGB").quantize(colors=256, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
        tmp = path + ".tmp.png"
        small.save(tmp, optimize=True)
    if os.path.getsize(tmp) < size:
        os.replace(tmp, path)
    else:
        os.remove(tmp)
    return os.path.getsize(path)


def measure(entry: Entry) -> tuple[str, dict]:
    """Return the measured facts of a design as text, and the raw JSON."""
    design = [entry.mesh] + (["--twist", entry.twist] if entry.twist else [])
    if entry.check == "info":
        data = run(["info", entry.mesh])
        if "error" in data:
            return f"error: {data['error'].get('message')}", data
        traced, _ = measure(Entry(entry.file, entry.mesh, entry.twist, entry.claim))
        return (
            f"edge degrees {data['edge_degrees']}, {data['corners']} corners on {data['vertices']} vertices; {traced}",
            data,
        )
    if entry.check == "identify":
        data = run(["identify", *design])
        if "error" in data:
            return f"error: {data['error'].get('message')}", data
        name = data.get("chiral_name") or data.get("name")
        return f"{data['components']} component(s), **{name}**, {data.get('crossings')} crossings", data
    data = run(["trace", *design])
    if "error" in data:
        return f"error: {data['error'].get('message')}", data
    text = f"{data['components']} component(s), {'holds together' if data['holds_together'] else 'falls apart'}"
    periods = [s["period"] for s in data.get("strands", []) if s.get("period") and any(s["period"])]
    if periods:
        text += f", periods {periods}"
    return text, data


def cube_parities() -> tuple[int, dict[int, int]]:
    """Trace all 4,096 parity patterns of the cube (labels 1 or 2): components with one even edge, and
    how many even edges the one-component patterns have (``{n_even: count}``)."""
    import numpy as np

    import lkspace

    cube = lkspace.load("cube")
    one_even = lkspace.trace(cube, [2] + [1] * 11).components
    knots: dict[int, int] = {}
    for bits in range(1 << 12):
        labels = np.where((bits >> np.arange(12)) & 1, 2, 1)
        if lkspace.trace(cube, labels).components == 1:
            n_even = int((labels == 2).sum())
            knots[n_even] = knots.get(n_even, 0) + 1
    return one_even, dict(sorted(knots.items()))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=OUT)
    parser.add_argument("--only", help="make only the pictures whose file name contains this")
    parser.add_argument(
        "--renderer", choices=["lkspace", "blender"], default="lkspace", help="who draws the 3D pictures"
    )
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = []
    t_all = time.perf_counter()
    for entry in entries():
        if args.only and args.only not in entry.file:
            continue
        path = os.path.join(args.out, entry.file)
        entry.twist = labels_of(entry)
        design = [entry.mesh] + (["--twist", entry.twist] if entry.twist else [])
        t0 = time.perf_counter()
        if args.renderer == "blender" and "--diagram" not in entry.draw:
            written = render_blender(entry, path)
        else:
            written = run(["export", *design, "-o", path, "--size", SIZE, *entry.draw])
        if "error" in written:
            print(f"{entry.file}: {written['error'].get('message')}", file=sys.stderr)
            continue
        size = shrink(path)
        measured, _ = measure(entry)
        seconds = time.perf_counter() - t0
        print(f"{entry.file}: {size / 1000:.0f} kB, {seconds:.1f} s; {measured}")
        if size > MAX_BYTES:
            print(f"{entry.file}: {size} bytes > {MAX_BYTES}", file=sys.stderr)
        command = "lkspace export " + " ".join(design + entry.draw) + f" -o {entry.file}"
        rows.append((entry, command, measured))
    lines = [
        "# The paper's gallery, regenerated",
        "",
        "Made by `python experiments/gallery.py` with the installed `lkspace` command: every picture by",
        "`lkspace export`, every measurement by `lkspace trace --json` (components, holding together, thread",
        "periods) or `lkspace identify --json` (knot/link name).  Each row quotes the claim of",
        "*Twisted Edges* the picture checks (by the figure's LaTeX label), what the claim needs, and",
        "what lkspace measured.",
        f"Pictures are {SIZE} pixels; periodic structures are drawn as blocks of cells with the threads cut",
        "at the block's faces.",
        "",
        "| picture | design | the paper's claim | needs | measured |",
        "|---|---|---|---|---|",
    ]
    for entry, command, measured in rows:
        lines.append(f"| ![{entry.file}]({entry.file}) | `{command}` | {entry.claim} | {entry.expect} | {measured} |")
    one_even, knots = cube_parities()
    lines += [
        "",
        "Notes:",
        "",
        '- *cube-one-even*: the teaser\'s example ("one even-twisted edge and all others odd") does not give a',
        "  knot: on a cube every edge has degree 2, so only the parities count, and eleven odd edges with one even",
        f"  edge leave {one_even} components (by symmetry, whichever edge is even).  Tracing all 4,096 parity",
        "  patterns, the one-component ones have these numbers of even edges (even edges: patterns): "
        + ", ".join(f"{k}: {v}" for k, v in knots.items())
        + ".  *cube-knot* shows one.",
        "- *torus-2-8*: the paper draws T(2,8) from a two-sided hexagon; with twist 1 on every edge the",
        "  two-sided N-gon gives T(2,N), so the octagon is used here.",
        "- Knot names are KnotInfo/LinkInfo names; `m` marks the mirror image of the table's diagram.",
        "- Colours in a block ([the rule](../../docs/geometry.md#colours-in-a-block)): a thread keeps its thread",
        "  class's colour in every cell (*square-weave*: 2 colours, *hexagonal-weave*: 3, *cP-2-1-1*: 1,",
        "  *cP-1-3-1*: 2); a ring, each lattice copy its own component, takes a colour by its cell.  In",
        "  *square-chainmail* and *hexagonal-chainmail* the one ring class comes in 4 tones repeating every",
        "  second cell: every ring's linked neighbours (4 on squares, 6 on hexagons) and the next rings out",
        "  (diagonal squares; hexagons 1.73 spacings away) have other colours, the nearest ring of the same",
        "  colour is 2 spacings away.",
        "",
        f"Total time: {time.perf_counter() - t_all:.0f} s.",
    ]
    if args.only:  # a partial run leaves the table alone
        return
    with open(os.path.join(args.out, "README.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
