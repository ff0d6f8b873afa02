"""Build what lkspace ships so that a first ``--identify`` run costs what later ones do.

Run: ``python experiments/build_key_names.py [--knots 12] [--links 11] [--harvest cube:-1..1 ...]``.

0. ``lkspace/data/knot-tables.pickle.xz``: the tables' index by Jones value
   (:func:`lkspace.knots.tables.tables`, 15-20 s to build), for the installed
   ``database_knotinfo`` version.
1. ``lkspace/data/names-by-key.jsonl.gz``: every KnotInfo knot up to ``--knots`` crossings and LinkInfo link up to ``--links``,
   both mirror images (:func:`lkspace.knots.table_keys.table_keys`, about two minutes).
2. Each ``--harvest`` space (``scaffold:labels``) is identified by ``python -m lkspace
   enumerate ... --identify`` with an empty cache (beside the file of step 1), and the
   keys that run judged (composites, split links, HTLinkExteriors names, second-level
   keys) are added as the run wrote them: names found by the live identification.

The first line is a header (key version, tables version, bounds, spaces harvested);
then one cache line per key, as :class:`lkspace.knots.key_names.KeyCache` writes them.
Rebuild whenever :data:`lkspace.knots.keyed.KEY_VERSION` changes (a test checks it).
"""

from __future__ import annotations

import argparse
import glob
import gzip
import json
import lzma
import os
import pickle
import subprocess
import sys
import tempfile
import time
from importlib.metadata import version
from pathlib import Path

from lkspace.knots.keyed import KEY_VERSION
from lkspace.knots.shipped_keys import SHIPPED, shipped_keys
from lkspace.knots.table_keys import line, table_keys
from lkspace.knots.tables import SHIPPED_TABLES, build_tables, knot_modules

HARVEST = ["tetrahedron:-2..2", "cube:-1..1", "octahedron:-1..1"]


def write(header: dict[str, object], lines: dict[tuple[int | str, ...], str]) -> tuple[int, int]:
    """Write the shipped file; return its sizes (text, compressed)."""
    text = "\n".join([json.dumps(header), *(lines[k] for k in sorted(lines, key=str))]) + "\n"
    data = gzip.compress(text.encode(), compresslevel=9, mtime=0)
    Path(SHIPPED).write_bytes(data)
    return len(text), len(data)


def harvest(space: str, folder: str) -> dict[tuple[int | str, ...], str]:
    """Identify ``space`` with an empty cache in ``folder``; return the lines of the keys the run judged."""
    name, labels = space.split(":")
    cache = os.path.join(folder, name)
    env = {**os.environ, "LKSPACE_CACHE": cache}
    out = os.path.join(folder, f"{name}.parquet")
    cmd = [sys.executable, "-m", "lkspace", "enumerate", name, "--labels", labels, "--identify", "-o", out]
    subprocess.run(cmd, env=env, check=True, stdout=subprocess.DEVNULL)
    found: dict[tuple[int | str, ...], str] = {}
    for path in glob.glob(os.path.join(cache, "names-by-key-*.jsonl")):
        with open(path, encoding="utf-8") as fh:
            for text in fh:
                item = json.loads(text)
                found[tuple(item["key"])] = json.dumps(item, separators=(",", ":"))
    return found


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--knots", type=int, default=12, help="most crossings of the knots kept")
    parser.add_argument("--links", type=int, default=11, help="most crossings of the links kept")
    parser.add_argument("--harvest", nargs="*", default=HARVEST, help="spaces scaffold:labels to harvest")
    parser.add_argument("--harvest-only", action="store_true", help="keep the shipped files, add the spaces' keys")
    args = parser.parse_args()
    start = time.perf_counter()
    if args.harvest_only:
        with gzip.open(SHIPPED, "rt", encoding="utf-8") as fh:
            header = json.loads(fh.readline())
        add_harvest(header, dict(shipped_keys().lines()), args.harvest)
        return
    dki = knot_modules()[2]
    index = (str(dki.version()), build_tables(dki))
    Path(SHIPPED_TABLES).write_bytes(lzma.compress(pickle.dumps(index, protocol=pickle.HIGHEST_PROTOCOL), preset=9))
    print(f"tables index: {Path(SHIPPED_TABLES).stat().st_size:,} bytes -> {SHIPPED_TABLES}", flush=True)
    keys = table_keys(args.knots, args.links)
    lines: dict[tuple[int | str, ...], str] = {k: line(k, v) for k, v in keys.items()}
    header: dict[str, object] = {
        "key_version": KEY_VERSION,
        "tables": version("database_knotinfo"),
        "knots": args.knots,
        "links": args.links,
        "harvested": [],
    }
    write(header, lines)
    print(f"tables: {len(keys):,} keys ({sum(v is not None for v in keys.values()):,} trusted)", flush=True)
    add_harvest(header, lines, args.harvest)
    print(f"{time.perf_counter() - start:.0f} s")


def add_harvest(header: dict[str, object], lines: dict[tuple[int | str, ...], str], spaces: list[str]) -> None:
    """Add the keys each space's cold run judges to ``lines`` and write the shipped file after each."""
    with tempfile.TemporaryDirectory() as folder:
        for space in spaces:
            found = {k: v for k, v in harvest(space, folder).items() if k not in lines}
            lines.update(found)
            done = [s for s in header.get("harvested", []) if s != space]  # type: ignore[attr-defined]
            header["harvested"] = [*done, space]
            write(header, lines)
            print(f"{space}: {len(found):,} keys added", flush=True)
    size, packed = write({**header, "keys": len(lines)}, lines)
    print(f"{len(lines):,} keys, {size:,} bytes of text, {packed:,} compressed -> {SHIPPED}")


if __name__ == "__main__":
    main()
