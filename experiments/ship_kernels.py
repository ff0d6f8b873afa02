"""Refresh ``lkspace/compiled/shipped/``: numba's cache files of lkspace's kernels, for a fresh machine.

Run the test suite with an empty numba cache, then collect what it compiled:

    NUMBA_CACHE_DIR=/tmp/kernels python -m pytest
    python experiments/ship_kernels.py /tmp/kernels

Every index file of the run's cache whose source file is this checkout's (numba's stamp:
the SHA-256 of the file) is copied with its compiled code, keeping only the entries
compiled for the portable ``generic`` CPU (``lkspace.compiled.shipped``); the folder is
written anew, so kernels that changed or went away leave it.  ``--check`` only reports
the shipped files whose source changed since (they are not used: a fresh machine
compiles those kernels).
"""

from __future__ import annotations

import argparse
import hashlib
import shutil
import sys
from pathlib import Path

from numba.core.caching import IndexDataCacheFile

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from lkspace.compiled.shipped import PACKAGE, SHIPPED, shipped_folder  # noqa: E402

PORTABLE = "generic"


def packages() -> dict[str, list[Path]]:
    """Return lkspace's folders by their own name (numba names a cache folder ``<name>_<hash of its path>``)."""
    out: dict[str, list[Path]] = {}
    for folder in [PACKAGE, *sorted(p for p in PACKAGE.rglob("*") if p.is_dir() and p.name != "__pycache__")]:
        out.setdefault(folder.name, []).append(folder)
    return out


def source_of(index: Path, folders: list[Path]) -> tuple[Path, bytes] | None:
    """Return the source file an index file belongs to, with numba's stamp of it, if its stamp is current."""
    module = index.name.split(".", 1)[0]
    for folder in folders:
        source = folder / f"{module}.py"
        if source.exists():
            stamp = hashlib.sha256(source.read_bytes()).digest()
            if IndexDataCacheFile(str(index.parent), index.name[: -len(".nbi")], stamp)._load_index():
                return source, stamp
    return None


def collect(cache: Path) -> tuple[int, int, int]:
    """Write the shipped folder from ``cache``; return ``(index files, entries, bytes)`` shipped."""
    by_name = packages()
    staged = SHIPPED.with_name("shipped.new")
    shutil.rmtree(staged, ignore_errors=True)
    files = entries = 0
    for index in sorted(cache.glob("*/*.nbi")):
        found = source_of(index, by_name.get(index.parent.name.rsplit("_", 1)[0], []))
        if found is None:
            continue
        source, stamp = found
        base = index.name[: -len(".nbi")]
        src = IndexDataCacheFile(str(index.parent), base, stamp)
        folder = shipped_folder(str(source))
        assert folder is not None
        dst = IndexDataCacheFile(str(staged / folder.relative_to(SHIPPED)), base, stamp)
        kept = [key for key in src._load_index() if key[1][1] == PORTABLE]
        if kept:
            (staged / folder.relative_to(SHIPPED)).mkdir(parents=True, exist_ok=True)
            files += 1
        for key in kept:
            dst.save(key, src.load(key))
            entries += 1
    shutil.rmtree(SHIPPED, ignore_errors=True)
    staged.mkdir(exist_ok=True)
    staged.rename(SHIPPED)
    size = sum(p.stat().st_size for p in SHIPPED.rglob("*") if p.is_file())
    return files, entries, size


def stale() -> list[str]:
    """Return the shipped index files whose source changed (or went away) since they were collected."""
    out = []
    for index in sorted(SHIPPED.glob("*/*.nbi")):
        folder = PACKAGE.joinpath(*index.parent.name.split(".")) if index.parent.name != "lkspace" else PACKAGE
        if source_of(index, [folder]) is None:
            out.append(str(index.relative_to(ROOT)))
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cache", nargs="?", type=Path, help="the NUMBA_CACHE_DIR of a run")
    parser.add_argument("--check", action="store_true", help="only list the shipped files whose source changed")
    args = parser.parse_args()
    if args.check or args.cache is None:
        old = stale()
        print("\n".join(old) or "every shipped kernel is current")
        sys.exit(1 if old else 0)
    files, entries, size = collect(args.cache)
    print(
        f"shipped {entries} compiled kernels in {files} index files, {size / 1e6:.1f} MB: {SHIPPED.relative_to(ROOT)}"
    )


if __name__ == "__main__":
    main()
