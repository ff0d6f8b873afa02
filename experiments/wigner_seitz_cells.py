"""Write ``lkspace/scaffolds/wigner_seitz_cells.py``: the built-in tilings and honeycombs as data.

Each built-in Wigner–Seitz scaffold is computed with Qhull
(:func:`lkspace.scaffolds.periodic.wigner_seitz_from_voronoi`) and written as Python
literals: vertex positions (``repr`` of each float, so they read back bit for bit and
the scaffolds' ``content_hash`` is unchanged), faces and corner offsets.  Loading a
built-in then needs no scipy.  ``tests/test_periodic.py`` checks the data against the
construction; rerun this after changing the construction or the lattices:

    python experiments/wigner_seitz_cells.py
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from lkspace.scaffolds.periodic import LATTICES, wigner_seitz_from_voronoi

OUT = Path(__file__).resolve().parents[1] / "lkspace" / "scaffolds" / "wigner_seitz_cells.py"

HEADER = '''"""The built-in Wigner–Seitz tilings and honeycombs, precomputed (see :mod:`lkspace.scaffolds.periodic`).

``CELLS[name] = (vertices, faces, offsets)``: vertex positions ``(n_vertices, 3)``, each face's
vertex classes, and each face corner's lattice offset, as
:func:`~lkspace.scaffolds.periodic.wigner_seitz_from_voronoi` computes them with Qhull.
Written by ``experiments/wigner_seitz_cells.py`` (do not edit by hand); ``tests/test_periodic.py``
checks them against the construction.
"""

CELLS: dict[str, tuple[list[list[float]], list[list[int]], list[list[list[int]]]]] = {
'''


def literal(name: str) -> str:
    """The ``CELLS`` entry of ``name``: one line per vertex, per face and per face's offsets."""
    scaffold = wigner_seitz_from_voronoi(name)
    offsets = scaffold.corner_offsets
    starts = scaffold.face_starts.tolist()
    lines = [f"    {name!r}: (", "        ["]
    lines += [f"            [{', '.join(repr(float(x)) for x in v)}]," for v in scaffold.vertices]
    lines += ["        ],", "        ["]
    lines += [f"            {face!r}," for face in scaffold.faces()]
    lines += ["        ],", "        ["]
    lines += [f"            {offsets[a:b].tolist()!r}," for a, b in zip(starts[:-1], starts[1:], strict=True)]
    lines += ["        ],", "    ),"]
    return "\n".join(lines)


def main() -> None:
    OUT.write_text(HEADER + "\n".join(literal(name) for name in LATTICES) + "\n}\n")
    subprocess.run([sys.executable, "-m", "ruff", "format", "-q", str(OUT)], check=True)
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
