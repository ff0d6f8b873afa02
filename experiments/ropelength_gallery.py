"""A gallery page of the relaxed knots of ``results/ropelength/``: one small picture per knot.

Each knot's row (``results/ropelength/NAME.json``, written by
``experiments/relax_ropelength.py``) names the design it kept; the picture is that design
relaxed and drawn by the real command, ``python -m lkspace export MESH --twist ... --relax
--no-mesh --size 160x160 -o NAME.png`` with the row's ``relax_flags`` (``--relax-fine``, when
the row is a refined relaxation, and ``--relax-points``, ``--relax-escape`` where it escaped; the relaxation is deterministic: the curve whose
ropelength the row records), then reduced to a 64-colour palette so 249 pictures stay near
1 MB.  Pictures already made are kept (``--fresh`` redoes them).  Writes
``results/ropelength/gallery/NAME.png`` and ``results/ropelength/gallery.md`` (knots in
table order, captions with the name and the ratio to KnotInfo's ideal ropelength).

    nice python experiments/ropelength_gallery.py [--only 3_1,8_17] [--fresh]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from PIL import Image

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
ROWS = ROOT / "results" / "ropelength"
PICTURES = ROWS / "gallery"
SIZE = 160
COLUMNS = 6


def table_order(name: str) -> tuple[int, int]:
    """``"10_12"`` -> ``(10, 12)``: crossings, then the table index."""
    crossings, _, index = name.partition("_")
    return int(crossings), int(index)


def picture(row: dict, out: Path) -> str | None:
    """Draw ``row``'s design relaxed into ``out``; return the error line when the command fails."""
    twist = ",".join(str(t) for t in row["labels"])
    with tempfile.TemporaryDirectory() as tmp:
        raw = os.path.join(tmp, "knot.png")
        cmd = [sys.executable, "-m", "lkspace", "export", row["scaffold"], f"--twist={twist}", "--relax", "--no-mesh"]
        cmd += row.get(
            "relax_flags", []
        )  # --relax-fine (--relax-points, --relax-escape) where the row's curve is the refined one
        cmd += ["--size", f"{SIZE}x{SIZE}", "-o", raw]
        proc = subprocess.run(cmd, capture_output=True, text=True, env={**os.environ, "PYTHONPATH": str(ROOT)})
        if proc.returncode:
            return (proc.stderr.strip().splitlines() or ["failed"])[-1]
        image = Image.open(raw).convert("RGBA").quantize(colors=64, method=Image.Quantize.FASTOCTREE)
        image.save(out, optimize=True)
    return None


def page(rows: list[dict], failed: dict[str, str]) -> str:
    """The markdown page: a grid of pictures, ``COLUMNS`` a row, each captioned name and ratio."""
    lines = [
        "# Relaxed knots to 10 crossings",
        "",
        f"Every knot of `results/ropelength.md` ({len(rows)}), its kept design relaxed by `lkspace export --relax` "
        "and drawn at 160 px (`experiments/ropelength_gallery.py`); the caption gives the ratio of its "
        "ropelength to KnotInfo's ideal (tight) ropelength.",
        "",
        "| " * COLUMNS + "|",
        "|---" * COLUMNS + "|",
    ]
    cells = []
    for r in rows:
        name = r["type"]
        ratio = f"{r['ratio']:.3f}x" if r.get("ratio") else "not relaxed"
        art = f"({failed[name]})" if name in failed else f"![{name}](gallery/{name}.png)"
        cells.append(f"{art}<br>{name} {ratio}")
    for i in range(0, len(cells), COLUMNS):
        chunk = cells[i : i + COLUMNS]
        lines.append("| " + " | ".join(chunk + [""] * (COLUMNS - len(chunk))) + " |")
    return "\n".join(lines) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", default="", help="comma-separated knot names (default: every row)")
    parser.add_argument("--fresh", action="store_true", help="redraw pictures already made")
    args = parser.parse_args()
    rows = sorted((json.loads(p.read_text()) for p in ROWS.glob("*_*.json")), key=lambda r: table_order(r["type"]))
    only = set(args.only.split(",")) if args.only else None
    PICTURES.mkdir(parents=True, exist_ok=True)
    failed: dict[str, str] = {}
    for r in rows:
        out = PICTURES / f"{r['type']}.png"
        if (only is None or r["type"] in only) and (args.fresh or not out.exists()) and "labels" in r:
            why = picture(r, out)
            if why:
                failed[r["type"]] = why
            print(r["type"], why or "ok", flush=True)
            (ROWS / "gallery.md").write_text(page(rows, failed))
    for r in rows:
        if not (PICTURES / f"{r['type']}.png").exists() and r["type"] not in failed:
            failed[r["type"]] = "not drawn yet"
    (ROWS / "gallery.md").write_text(page(rows, failed))


if __name__ == "__main__":
    main()
