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
3. **Sums and split links.**  A trusted key of a table name whose Jones polynomial a sum
   or split link of two or three table types (the unknot too) with no more crossings has
   is kept as shared (``null``): the key cannot tell L9a24 from L2a1#7_6, nor 11n_30
   from 3_1#6_2.  ``--sums-only`` applies this step to the shipped file.

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
import re
import subprocess
import sys
import tempfile
import time
from importlib.metadata import version
from pathlib import Path

import numpy as np

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
    parser.add_argument("--sums-only", action="store_true", help="keep the shipped files, mark keys sums share")
    args = parser.parse_args()
    start = time.perf_counter()
    if args.sums_only:
        with gzip.open(SHIPPED, "rt", encoding="utf-8") as fh:
            header = json.loads(fh.readline())
        lines = dict(shipped_keys().lines())
        mark_sums(header, lines, args.knots)
        write({**header, "keys": len(lines)}, lines)
        print(f"{time.perf_counter() - start:.0f} s")
        return
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
    mark_sums(header, lines, args.knots)
    write({**header, "keys": len(lines)}, lines)
    print(f"{time.perf_counter() - start:.0f} s")


SUM_FACTOR_MAX = 9
"""Most crossings of a factor of a sum or split link within the tables' 12 crossings (the other has 2 or more, or is an unknot)."""


def _poly(lowest: int, coeffs: list[int]) -> tuple[int, tuple[int, ...]]:
    """A Laurent polynomial in x without zero ends: ``(lowest exponent, coefficients)``."""
    c = np.trim_zeros(np.asarray(coeffs, np.int64), "b")
    lead = len(c) - len(np.trim_zeros(c, "f"))
    return lowest + lead, tuple(int(v) for v in c[lead:])


def _times(a: tuple[int, tuple[int, ...]], b: tuple[int, tuple[int, ...]]) -> tuple[int, tuple[int, ...]]:
    return _poly(a[0] + b[0], np.convolve(a[1], b[1]).tolist())


UNLINK_FACTOR = (-1, (-1, 0, -1))
"""``V(A + B) / (V(A) V(B))`` for a split link: ``-x - 1/x`` (x = sqrt t)."""


def sums_and_splits(limit: int) -> dict[tuple[int, int, tuple[int, ...]], int]:
    """``(components, lowest, coefficients)`` of the Jones polynomial of every sum and split link of two or three
    table types (the unknot too, in split links) with at most ``limit`` crossings in all -> the fewest crossings."""
    from lkspace.knots.jones import jones
    from lkspace.knots.tables import tables

    factors = {(1, 0, 0, (1,))}  # (crossings, components, lowest, coefficients): the unknot
    for entry in {e.table_name: e for es in tables().values() for e in es if e.pd}.values():
        if entry.crossings <= SUM_FACTOR_MAX:
            lowest, coeffs = jones(np.asarray(entry.pd_code(), np.int64))
            for low, c in ((lowest, list(coeffs)), (-(lowest + len(coeffs) - 1), list(coeffs)[::-1])):
                factors.add((entry.crossings, entry.components, *_poly(low, c)))
    singles = sorted(factors)
    found: dict[tuple[int, int, tuple[int, ...]], int] = {}

    def keep(crossings: int, components: int, poly: tuple[int, tuple[int, ...]]) -> None:
        key = (components, *poly)
        found[key] = min(found.get(key, crossings), crossings)

    made = []
    for i, (ca, na, la, pa) in enumerate(singles):
        for cb, nb, lb, pb in singles[i:]:
            if ca + cb > limit:
                continue
            product = _times((la, pa), (lb, pb))
            if ca and cb:  # a sum: the unknot adds nothing
                keep(ca + cb, na + nb - 1, product)
                made.append((ca + cb, na + nb - 1, product))
            split = _times(product, UNLINK_FACTOR)
            keep(ca + cb, na + nb, split)
            made.append((ca + cb, na + nb, split))
    for cm, nm, pm in made:
        for cb, nb, lb, pb in singles:
            if cm + cb > limit:
                continue
            product = _times(pm, (lb, pb))
            if cb:
                keep(cm + cb, nm + nb - 1, product)
            keep(cm + cb, nm + nb, _times(product, UNLINK_FACTOR))
    return found


def jones_terms(text: str) -> list[tuple[int, int]]:
    """``(exponent of x, coefficient)`` of each term of a Jones polynomial's text (``"-x^4 + 3 x^2 - 4"``)."""
    terms = []
    for term in re.split(r"(?<!\^)(?=[+-])", text.replace(" ", "")):
        if term:
            sign, digits, power, exponent = re.fullmatch(r"([+-]?)(\d*)(x(?:\^(-?\d+))?)?", term).groups()
            terms.append((0 if power is None else int(exponent or 1), (-1 if sign == "-" else 1) * int(digits or 1)))
    return terms


def mark_sums(header: dict[str, object], lines: dict[tuple[int | str, ...], str], knots: int) -> None:
    """Keep as shared (``null``) every trusted key of a table name whose Jones polynomial a sum or split link of
    table types with no more crossings has (L9a24 and L2a1#7_6): the key cannot tell them apart."""
    from lkspace.knots.naming import name_key
    from lkspace.knots.tables import tables

    components = {e.name: e.components for es in tables().values() for e in es}
    sums = sums_and_splits(knots)
    marked, names = 0, set()
    for key, text in list(lines.items()):
        fields = json.loads(text)["fields"]
        name = (fields or {}).get("knot_name")
        if not name or "#" in name or fields.get("table") not in ("knotinfo", "linkinfo") or not fields.get("jones"):
            continue
        terms = jones_terms(fields["jones"])
        low = min(e for e, _ in terms)
        coeffs = [0] * (max(e for e, _ in terms) - low + 1)
        for e, c in terms:
            coeffs[e - low] += c
        crossings = sums.get((components.get(name, 1), *_poly(low, coeffs)))
        if crossings is not None and crossings <= name_key(name)[0]:
            lines[key] = line(key, None)
            marked += 1
            names.add(name)
    header["sums"] = {"factors_up_to": SUM_FACTOR_MAX, "lines_marked": marked, "names": len(names)}
    print(f"sums and split links: {marked} lines of {len(names)} names marked ({', '.join(sorted(names)[:12])}, ...)")


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
