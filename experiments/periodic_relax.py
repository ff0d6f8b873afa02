"""Periodic designs before and after smoothing and relaxing their thread classes in the periodic cell.

For each design, a block of cells is realized three ways: the **construction** (what every
block drew before: ``GeometryParams(smooth=False)``), the default (**smoothed** in the
periodic cell) and **relaxed** (``export --relax``, lattice fixed).  Measured here on the
block's curves, with code of this script: the least curvature radius, the least distance
between two different curves of the block (distinct threads or rings, every lattice image
the block holds), the thickness (the smaller of the curvature radius and half that
distance), the ropelength per cell (the thread classes' length in one cell / the
thickness), and the wall time of the realization.  Writes ``results/periodic-relax.{json,md}``
with the commit, machine and load average.

Run: ``python experiments/periodic_relax.py``.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from benchkit import RESULTS, load_average, provenance  # noqa: E402

import lkspace  # noqa: E402
from lkspace.geometry.block import realize_block  # noqa: E402
from lkspace.geometry.params import GeometryParams  # noqa: E402
from lkspace.geometry.relax import relax  # noqa: E402

DESIGNS = [
    ("square chainmail", "tiling:square", [2, 2], (3, 3)),
    ("hexagonal chainmail", "tiling:hexagonal", [2, 2, 2], (3, 3)),
    ("biaxial weave", "tiling:square", [1, 1], (3, 3)),
    ("triaxial weave", "tiling:hexagonal", [1, 1, 1], (3, 3)),
    ("cubic honeycomb threads", "honeycomb:cP", [2, 1, 1], (2, 2, 2)),
    ("Laves", "laves", [1] * 6, (1, 1, 1)),
]
"""(name, scaffold, labels, block sizes)."""


def circumradii(curve: np.ndarray, closed: bool) -> np.ndarray:
    """Radius of the circle through each point and its neighbours (``inf`` where straight)."""
    p = np.vstack([curve[-1:], curve, curve[:1]]) if closed else curve
    a, b, c = p[:-2], p[1:-1], p[2:]
    ab, bc, ca = (np.linalg.norm(x, axis=1) for x in (b - a, c - b, a - c))
    area2 = np.linalg.norm(np.cross(b - a, c - a), axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(area2 > 1e-14 * ab * bc, ab * bc * ca / (2 * area2), np.inf)


def dense(curve: np.ndarray, closed: bool, spacing: float) -> np.ndarray:
    """Points about ``spacing`` apart along the polyline."""
    p = np.vstack([curve, curve[:1]]) if closed else curve
    cum = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])
    s = np.linspace(0.0, cum[-1], max(3, int(np.ceil(cum[-1] / spacing))))
    return np.column_stack([np.interp(s, cum, p[:, i]) for i in range(3)])


def measured(real: lkspace.Realization, cell_length: float, seconds: float) -> dict:
    """Least curvature radius, least distance between different curves, thickness and ropelength per cell."""
    curves = list(zip(real.curves, real.closed.tolist(), strict=True))
    # an open run's end points are where the block cut it (on a segment): left out of the bends
    bend = min(float(circumradii(c if cl else c[1:-1], cl).min()) for c, cl in curves)
    pts = [dense(c, cl, 0.004) for c, cl in curves]
    gap = np.inf
    for k, p in enumerate(pts):
        others = [q for m, q in enumerate(pts) if m != k]
        if others:
            gap = min(gap, float(cKDTree(np.vstack(others)).query(p)[0].min()))
    thick = min(bend, 0.5 * gap)
    return {
        "curves": real.n_curves,
        "curvature_radius": bend,
        "distance": gap,
        "thickness": thick,
        "ropelength_per_cell": cell_length / thick,
        "tube_radius": real.tube_radius,
        "seconds": round(seconds, 2),
        **({"relax_steps": real.relaxation.steps, "stopped": real.relaxation.stopped} if real.relaxation else {}),
    }


def class_length(real: lkspace.Realization) -> float:
    """Length of the thread classes in one cell (copy 0 before the cut: a loop closed, a thread's one period)."""
    total = 0.0
    for c, cl, copy in zip(real.curves, real.closed.tolist(), real.copy_of.tolist(), strict=True):
        if copy == 0:
            p = np.vstack([c, c[:1]]) if cl else c
            total += float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum())
    return total


def run() -> list[dict]:
    rows = []
    for name, mesh, labels, sizes in DESIGNS:
        scaffold = lkspace.load(mesh)
        row: dict = {"design": name, "scaffold": mesh, "labels": labels, "block": list(sizes)}
        for stage, params, then in (
            ("construction", GeometryParams(smooth=False), None),
            ("smoothed", None, None),
            ("relaxed", None, relax),
        ):
            copies: list[lkspace.Realization] = []

            def kept(r: lkspace.Realization, then=then, copies=copies) -> lkspace.Realization:
                copies.append(r if then is None else then(r))  # the copies before the cut
                return copies[-1]

            start = time.perf_counter()
            real = realize_block(scaffold, labels, None, params, sizes, relax=kept)
            seconds = time.perf_counter() - start
            length = class_length(copies[0])
            row[stage] = measured(real, length, seconds)
            print(name, stage, {k: row[stage][k] for k in ("ropelength_per_cell", "distance", "seconds")}, flush=True)
        rows.append(row)
    return rows


PICTURES = """Relaxed, one colour per thread class (`lkspace export ... --relax --size 480x480`, kept by hand):

| square chainmail 3x3 | hexagonal chainmail 3x3 | triaxial weave 3x3 | Laves 1x1x1 |
|---|---|---|---|
| ![](periodic-relax/square-chainmail-relaxed.png) | ![](periodic-relax/hexagonal-chainmail-relaxed.png) \
| ![](periodic-relax/triaxial-weave-relaxed.png) | ![](periodic-relax/laves-relaxed.png) |"""
"""The pictures section of the page (``results/periodic-relax/*.png``)."""


def markdown(rows: list[dict], info: dict) -> str:
    out = [
        "# Periodic designs smoothed and relaxed in the periodic cell",
        "",
        f"Commit {info['commit']} ({'dirty' if info['dirty'] else 'clean'}), {info['date']}, "
        f"{info['machine']['cpu_count']} cores ({info['machine']['cpu']}), load average before "
        f"{info['load_before']} and after {info['load_after']}.  `python experiments/periodic_relax.py`.",
        "",
        "Measured by the script on the block's curves: ropelength per cell = the thread classes' "
        "length in one cell / thickness; thickness = min(least curvature radius, half the least "
        "distance between two different curves of the block); time = wall seconds of "
        "`realize_block` (relaxed: with `relax`, to convergence).  Construction = what blocks drew "
        "before (no smoothing).",
        "",
        "| design | block | stage | ropelength / cell | least distance | least curvature radius | tube radius | time (s) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        for stage in ("construction", "smoothed", "relaxed"):
            m = r[stage]
            extra = f" ({m['relax_steps']} steps, {m['stopped']})" if "relax_steps" in m else ""
            out.append(
                f"| {r['design']} (`{r['scaffold']} --twist {','.join(map(str, r['labels']))}`) | "
                f"{'x'.join(map(str, r['block']))} | {stage}{extra} | {m['ropelength_per_cell']:.1f} | "
                f"{m['distance']:.3f} | {m['curvature_radius']:.3f} | {m['tube_radius']:.3f} | {m['seconds']:.1f} |"
            )
    out += ["", PICTURES]
    return "\n".join(out) + "\n"


def main() -> None:
    info = provenance()
    info["load_before"] = load_average()
    rows = run()
    info["load_after"] = load_average()
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / "periodic-relax.json").write_text(json.dumps({"provenance": info, "rows": rows}, indent=1) + "\n")
    (RESULTS / "periodic-relax.md").write_text(markdown(rows, info))


if __name__ == "__main__":
    main()
