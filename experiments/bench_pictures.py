"""Benchmark: picture sizes and times, ``lkspace export ... -o X.png`` and ``-o X.svg``, per design.

Each design is exported once per format in a fresh process (``python -m lkspace`` with
the tree given by ``--tree``, default this one); the file's bytes, the wall and CPU time
are recorded with the commit and machine load (:mod:`benchkit`).  Runs are merged into
``results/bench_pictures.json`` by ``--label`` (e.g. ``before`` on main, ``after`` here).

Run: ``python experiments/bench_pictures.py --label after`` (a few minutes on a quiet machine).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
from pathlib import Path

from benchkit import RESULTS, load_average, provenance, timed

DESIGNS = {
    "trefoil": ["dihedron:3", "--twist", "1"],
    "cube": ["cube", "--twist", "1"],
    "dodecahedron": ["dodecahedron", "--twist", "1"],
    "chainmail 3x3": ["tiling:square", "--twist", "2", "--block", "3x3"],
}
"""Name -> the design's arguments of ``lkspace export``."""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--label", required=True)
    parser.add_argument("--tree", default=str(Path(__file__).resolve().parents[1]))
    args = parser.parse_args()
    tree = Path(args.tree)
    env = {**os.environ, "PYTHONPATH": str(tree)}
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, design in DESIGNS.items():
            for ext in ("png", "svg"):
                out = os.path.join(tmp, f"x.{ext}")
                load = load_average()
                t = timed([sys.executable, "-m", "lkspace", "export", *design, "-o", out], env=env)
                size = os.path.getsize(out) if os.path.exists(out) else None
                rows.append({"design": name, "format": ext, "bytes": size, **t, "load": load})
                print(name, ext, size, f"{t['wall']:.2f}s", file=sys.stderr)
    path = RESULTS / "bench_pictures.json"
    data = json.loads(path.read_text()) if path.exists() else {}
    data[args.label] = {"provenance": provenance(tree), "rows": rows}
    path.write_text(json.dumps(data, indent=1) + "\n")


if __name__ == "__main__":
    main()
