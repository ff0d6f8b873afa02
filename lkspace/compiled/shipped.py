"""Compiled kernels shipped with lkspace, so that a fresh machine does not compile them.

Numba compiles a kernel on its first call and keeps the machine code in a cache beside
the source (``__pycache__``, or numba's user cache where that is read-only); on a fresh
install every kernel is compiled once, which took 200 s of a first ``enumerate cube
--identify`` against 21 s warm (``results/bench_fresh_machine.md``).  lkspace therefore
ships numba's cache files of its kernels in ``lkspace/compiled/shipped/`` (one folder per
subpackage, numba's own file names) and reads them when numba's cache misses.

What makes the files good on another machine:

* **Portable machine code.** Kernels are compiled for numba's ``generic`` CPU
  (:func:`portable_codegen` sets ``NUMBA_CPU_NAME=generic`` before numba is imported),
  so the cache key does not name this machine's processor.  If numba was imported
  before lkspace's first kernel with another CPU name, the shipped files do not match
  and kernels are compiled as usual.
* **Keys of content, not time.** Numba's index records a hash of the source file (not
  its modification time) and its own version; lkspace adds a digest of the helpers'
  sources (:mod:`~lkspace.compiled.kernels`).  A shipped file whose source, helpers or
  numba version changed is simply not used.

* **No registries to load code.** Numba refreshes its compiler's typing and lowering
  registries before loading cached code (0.3 s: it imports ``numba.np.arraymath``, which
  imports ``scipy.linalg``).  Loading needs only the runtime's symbols (NRT); compiling
  refreshes the registries itself.  So a kernel's code is loaded after the runtime alone
  when every external symbol it names is known then (:func:`links_now`), after numba's
  refresh otherwise.

A hit is copied into numba's writable cache, so the next process loads it from there.
``experiments/ship_kernels.py`` refreshes the folder (every kernel and signature a run of
the test suite compiled).
"""

from __future__ import annotations

import functools
import os
import sys
from pathlib import Path
from typing import Any

PACKAGE = Path(__file__).resolve().parent.parent
"""The ``lkspace`` package folder: shipped files are found by a source file's place under it."""

SHIPPED = Path(__file__).resolve().parent / "shipped"
"""``shipped/<subpackage path, dots>/<numba's file name>``: the shipped index (``.nbi``) and code (``.nbc``) files."""


def portable_codegen() -> None:
    """Compile for numba's ``generic`` CPU (unless the user chose one), before numba is imported."""
    if "numba" not in sys.modules:
        os.environ.setdefault("NUMBA_CPU_NAME", "generic")


def shipped_folder(source_file: str) -> Path | None:
    """Return the shipped folder of the kernels of ``source_file`` (``None`` outside the package)."""
    try:
        relative = Path(source_file).resolve().parent.relative_to(PACKAGE)
    except ValueError:
        return None
    return SHIPPED / (".".join(relative.parts) or "lkspace")


@functools.cache
def cache_class() -> type:
    """Return the numba function cache class of lkspace's kernels (see the module docstring).

    Its index key also holds ``digest`` (the helpers' sources); on a miss it loads the
    shipped entry of the same key, if any, and copies it into numba's own cache.  Loading
    starts numba's runtime and refreshes the registries only for code that needs them
    (:func:`links_now`; numba's own ``load_overload`` always refreshes first).
    """
    from numba.core.caching import FunctionCache, IndexDataCacheFile
    from numba.core.runtime import rtsys

    class ShippedCache(FunctionCache):
        def __init__(self, py_func: Any, digest: str) -> None:
            super().__init__(py_func)
            self._digest = digest
            folder = shipped_folder(py_func.__code__.co_filename)
            stamp = self._impl.locator.get_source_stamp()
            base = self._impl.filename_base
            self._shipped = None if folder is None else IndexDataCacheFile(str(folder), base, stamp)

        def _index_key(self, sig: Any, codegen: Any) -> tuple[Any, ...]:
            return (*super()._index_key(sig, codegen), self._digest)

        def load_overload(self, sig: Any, target_context: Any) -> Any:
            rtsys.initialize(target_context)  # what numba's refresh does first; the rest only if needed
            with self._guard_against_spurious_io_errors():
                return self._load_overload(sig, target_context)

        def _load_overload(self, sig: Any, target_context: Any) -> Any:
            if not self._enabled:
                return None
            key = self._index_key(sig, target_context.codegen())
            data = self._cache_file.load(key)
            if data is None and self._shipped is not None:
                data = self._shipped.load(key)
                if data is not None:
                    try:
                        self._impl.locator.ensure_cache_path()
                        self._cache_file.save(key, data)
                    except OSError:  # a read-only cache: the shipped file is read again next time
                        pass
            if data is None:
                return None
            if not links_now(data):
                target_context.refresh()
            return self._impl.rebuild(target_context, data)

    return ShippedCache


def links_now(data: Any) -> bool:
    """Whether the cached code ``data`` (a reduced ``CompileResult``) names only symbols known now.

    Its bitcode declares the functions and globals it calls (LLVM's intrinsics, named
    ``llvm.*``, are not symbols); each must be registered with LLVM or found in the process.
    Code in another layout (another numba's) is not checked: False.
    """
    import llvmlite.binding as ll

    library = data[0] if isinstance(data, tuple) and data else None  # (name, "object", (object code, bitcode))
    if not (isinstance(library, tuple) and len(library) == 3 and library[1] == "object"):
        return False
    module = ll.parse_bitcode(library[2][1])
    declared = [g.name for g in [*module.functions, *module.global_variables] if g.is_declaration]
    return all(name.startswith("llvm.") or ll.address_of_symbol(name) for name in declared)
