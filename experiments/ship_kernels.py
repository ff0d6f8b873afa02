"""Refresh ``lkspace/compiled/shipped/``: numba's cache files of lkspace's kernels, for a fresh machine.

Run the test suite with an empty numba cache, then collect what it compiled:

    NUMBA_CACHE_DIR=/tmp/kernels python -m pytest
    python experiments/ship_kernels.py /tmp/kernels

Every index file of the run's cache whose source file is this checkout's (numba's stamp:
the SHA-256 of the file) is copied with its compiled code, keeping only the entries
compiled for the portable ``generic`` CPU (``lkspace.compiled.shipped``); the folder is
written anew, so kernels that changed or went away leave it.  With ``--keep`` the shipped
files still current are kept as well (after changing one kernel file, a run of its tests
is enough: ``NUMBA_CACHE_DIR=/tmp/k python -m pytest tests/test_geometry.py`` then
``python experiments/ship_kernels.py --keep /tmp/k``).  ``--check`` only reports the
shipped files whose source changed since (they are not used: a fresh machine compiles
those kernels).
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


def cache_files(cache: Path) -> list[tuple[Path, list[Path]]]:
    """Return each index file of numba's cache folder ``cache`` with the lkspace folders its source may be in."""
    by_name = packages()
    return [(index, by_name.get(index.parent.name.rsplit("_", 1)[0], [])) for index in sorted(cache.glob("*/*.nbi"))]


def shipped_files() -> list[tuple[Path, list[Path]]]:
    """Return each shipped index file with the lkspace folder of its source."""
    return [(index, [package_of(index)]) for index in sorted(SHIPPED.glob("*/*.nbi"))]


def package_of(index: Path) -> Path:
    """Return the lkspace folder a shipped index file's kernels are defined in."""
    return PACKAGE if index.parent.name == "lkspace" else PACKAGE.joinpath(*index.parent.name.split("."))


def collect(sources: list[tuple[Path, list[Path]]]) -> tuple[int, int, int]:
    """Write the shipped folder from the index files ``sources``; return ``(index files, entries, bytes)`` shipped."""
    staged = SHIPPED.with_name("shipped.new")
    shutil.rmtree(staged, ignore_errors=True)
    files: set[Path] = set()
    entries: set[tuple[Path, tuple]] = set()
    for index, folders in sources:
        found = source_of(index, folders)
        if found is None:
            continue
        source, stamp = found
        base = index.name[: -len(".nbi")]
        src = IndexDataCacheFile(str(index.parent), base, stamp)
        folder = shipped_folder(str(source))
        assert folder is not None
        target = staged / folder.relative_to(SHIPPED)
        dst = IndexDataCacheFile(str(target), base, stamp)
        for key in [key for key in src._load_index() if key[1][1] == PORTABLE]:
            target.mkdir(parents=True, exist_ok=True)
            dst.save(key, src.load(key))
            files.add(target / index.name)
            entries.add((target / index.name, key))
    shutil.rmtree(SHIPPED, ignore_errors=True)
    staged.mkdir(exist_ok=True)
    staged.rename(SHIPPED)
    size = sum(p.stat().st_size for p in SHIPPED.rglob("*") if p.is_file())
    return len(files), len(entries), size


def stale() -> list[str]:
    """Return the shipped index files whose source changed (or went away) since they were collected."""
    return [str(index.relative_to(ROOT)) for index, folders in shipped_files() if source_of(index, folders) is None]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cache", nargs="*", type=Path, help="the NUMBA_CACHE_DIR of runs")
    parser.add_argument("--keep", action="store_true", help="keep the shipped files that are still current")
    parser.add_argument("--check", action="store_true", help="only list the shipped files whose source changed")
    args = parser.parse_args()
    if args.check or not args.cache:
        old = stale()
        print("\n".join(old) or "every shipped kernel is current")
        sys.exit(1 if old else 0)
    sources = [f for cache in args.cache for f in cache_files(cache)]
    if args.keep:
        kept = SHIPPED.with_name("shipped.kept")  # collect() rewrites SHIPPED: read the kept files from a copy
        shutil.rmtree(kept, ignore_errors=True)
        shutil.copytree(SHIPPED, kept)
        sources = [(kept / i.relative_to(SHIPPED), f) for i, f in shipped_files()] + sources
    files, entries, size = collect(sources)
    if args.keep:
        shutil.rmtree(kept)
    print(
        f"shipped {entries} compiled kernels in {files} index files, {size / 1e6:.1f} MB: {SHIPPED.relative_to(ROOT)}"
    )


if __name__ == "__main__":
    main()
