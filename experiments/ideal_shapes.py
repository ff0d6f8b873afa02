"""Ship the tightest relaxed shape of every knot up to 10 crossings with lkspace (``lookup``'s ``ideal_shape``).

Reads ``results/ropelength.json`` (``experiments/relax_ropelength.py``: per knot, the design
and relaxation options whose exported curve came closest to KnotInfo's ideal ropelength),
names each design's chirality with ``lkspace.identify``, and writes
``lkspace/data/ideal-shapes.json.gz`` (:mod:`lkspace.linktypes.ideal_shapes`).

    python experiments/ideal_shapes.py
"""

from __future__ import annotations

import gzip
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import lkspace  # noqa: E402
from lkspace.io.atomic import atomic_path  # noqa: E402
from lkspace.linktypes.ideal_shapes import SHIPPED, IdealShape  # noqa: E402


def main() -> None:
    """Name each row's design and write the shipped file."""
    rows = json.loads((ROOT / "results" / "ropelength.json").read_text())["rows"]
    shapes = []
    for row in rows:
        named = lkspace.identify(row["scaffold"], row["labels"])
        if named.name != row["type"]:
            raise SystemExit(f"{row['type']}: its design names {named.name}")
        shapes.append(
            IdealShape(
                chiral_name=str(named.naming.chiral_name or named.name),
                scaffold=row["scaffold"],
                labels=tuple(row["labels"]),
                relax_flags=tuple(row.get("relax_flags", ())),
                ropelength=round(float(row["ropelength"]), 3),
                ideal=float(row["ideal"]),
                ratio=round(float(row["ratio"]), 4),
            ).to_json()
        )
    with atomic_path(SHIPPED) as tmp, gzip.open(tmp, "wt") as f:
        json.dump({"source": "results/ropelength.json", "rows": shapes}, f, separators=(",", ":"))
    print(f"{len(shapes)} shapes: {SHIPPED.relative_to(ROOT)}, worst ratio {max(s['ratio'] for s in shapes)}")


if __name__ == "__main__":
    main()
