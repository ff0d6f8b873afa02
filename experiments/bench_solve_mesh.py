"""Benchmark ``lkspace solve MESH --type 3_1`` on meshes a user brings (issue 33, deliverable 6).

Each query runs as a user types it, ``python -m lkspace solve FILE --type 3_1 --json``, in a
fresh process on an OBJ written here: a hexagonal prism (18 edges, the walk meets 61,457
designs before its trefoil) and a 6 x 4 quad torus (48 edges, too many designs to walk:
the answer is built from the trefoil's diagram).  Wall and CPU seconds (median of
``--runs``), the answer's Σ|t| and which filter decided how many designs, with the commit
and the load average before and after, go to ``results/bench_solve_mesh.json`` and ``.md``.

    python experiments/bench_solve_mesh.py [--runs 3]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from benchkit import RESULTS, load_average, provenance, summary, timed  # noqa: E402


def prism_obj(n: int = 6) -> str:
    """An ``n``-gonal prism as OBJ text (unit circumradius, height 1)."""
    angles = 2 * np.pi * np.arange(n) / n
    lines = [f"v {np.cos(a):.6f} {np.sin(a):.6f} {z}" for z in (0.0, 1.0) for a in angles]
    lines.append("f " + " ".join(str(n - i) for i in range(n)))
    lines.append("f " + " ".join(str(n + 1 + i) for i in range(n)))
    lines += [f"f {i + 1} {(i + 1) % n + 1} {n + (i + 1) % n + 1} {n + i + 1}" for i in range(n)]
    return "\n".join(lines) + "\n"


def torus_obj(rings: int = 6, sides: int = 4) -> str:
    """A quad torus of ``rings x sides`` faces as OBJ text (radii 2 and 0.7)."""
    lines = []
    for i in range(rings):
        u = 2 * np.pi * i / rings
        for j in range(sides):
            v = 2 * np.pi * j / sides
            r = 2 + 0.7 * np.cos(v)
            lines.append(f"v {r * np.cos(u):.6f} {r * np.sin(u):.6f} {0.7 * np.sin(v):.6f}")

    def vid(i: int, j: int) -> int:
        return (i % rings) * sides + (j % sides) + 1

    for i in range(rings):
        for j in range(sides):
            lines.append(f"f {vid(i, j)} {vid(i + 1, j)} {vid(i + 1, j + 1)} {vid(i, j + 1)}")
    return "\n".join(lines) + "\n"


MESHES = {"hexagonal prism": prism_obj, "torus 6 x 4": torus_obj}


def main() -> None:
    """Time each query, write the results."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    rows = []
    load_before = load_average()
    with tempfile.TemporaryDirectory() as tmp:
        for name, make in MESHES.items():
            path = Path(tmp) / (name.split()[0] + ".obj")
            path.write_text(make())
            cmd = [sys.executable, "-m", "lkspace", "solve", str(path), "--type", "3_1", "--json"]
            answer = json.loads(subprocess.run(cmd, capture_output=True, text=True, check=True).stdout)
            samples = [timed(cmd) for _ in range(args.runs)]  # caches in place, as for a user's second query
            solutions = answer.get("solutions") or [{}]
            rows.append(
                {
                    "mesh": name,
                    "status": answer["status"],
                    "sum_abs": solutions[0].get("sum_abs"),
                    "stats": answer.get("stats", {}),
                    **summary(samples),
                }
            )
            print(name, rows[-1]["median_s"], rows[-1]["cpu_median_s"], flush=True)
    out = {**provenance(), "load_before": load_before, "load_after": load_average(), "rows": rows}
    (RESULTS / "bench_solve_mesh.json").write_text(json.dumps(out, indent=1) + "\n")
    lines = [
        "# `solve MESH --type 3_1` on a user's own mesh (issue 33, deliverable 6)",
        "",
        f"Made by `python experiments/bench_solve_mesh.py --runs {args.runs}`: fresh processes, as users type it;",
        f"commit `{out['commit']}`, {out['date']}, load {load_before} -> {out['load_after']} (2 cores, shared).",
        "",
        "| mesh | status | Σ\\|t\\| | wall (s), median | CPU (s), median | designs | decided by the determinant |",
        "|---|---|---:|---:|---:|---:|---:|",
    ]
    for r in rows:
        stats = r["stats"]
        lines.append(
            f"| {r['mesh']} | {r['status']} | {r['sum_abs']} | {r['median_s']} | {r['cpu_median_s']} | "
            f"{stats.get('designs', 0):,} | {stats.get('other: determinant', 0):,} |"
        )
    (RESULTS / "bench_solve_mesh.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
