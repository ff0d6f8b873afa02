"""The compiled kernels ship with lkspace: a fresh machine loads them instead of compiling (lkspace.compiled.shipped)."""

from __future__ import annotations

import hashlib
import importlib
import json
import os
import pickle
import subprocess
import sys
from pathlib import Path

import pytest

from lkspace.compiled.kernels import Kernel
from lkspace.compiled.shipped import SHIPPED, shipped_folder

ROOT = Path(__file__).resolve().parent.parent
REFRESH = "NUMBA_CACHE_DIR=/tmp/kernels python -m pytest; python experiments/ship_kernels.py /tmp/kernels"


def kernels() -> list[Kernel]:
    """Every kernel of the package (the modules that define one)."""
    found = []
    for path in sorted((ROOT / "lkspace").rglob("*.py")):
        if "shipped" in path.parts or "@kernel" not in path.read_text():
            continue
        module = importlib.import_module(".".join(path.relative_to(ROOT).with_suffix("").parts))
        found += [v for v in vars(module).values() if isinstance(v, Kernel) and v.py_func.__module__ == module.__name__]
    return found


def shipped_entries(k: Kernel) -> list[tuple]:
    """Return the index keys shipped for ``k`` whose source stamp is its file's current one (read with pickle only)."""
    source = Path(k.py_func.__code__.co_filename)
    folder = shipped_folder(str(source))
    assert folder is not None
    name = f"{source.stem}.{k.py_func.__qualname__}-{k.py_func.__code__.co_firstlineno}.py{sys.version_info[0]}{sys.version_info[1]}.nbi"
    try:
        with open(folder / name, "rb") as fh:
            pickle.load(fh)  # numba's version
            stamp, overloads = pickle.loads(fh.read())
    except FileNotFoundError:
        return []
    return list(overloads) if stamp == hashlib.sha256(source.read_bytes()).digest() else []


def test_every_kernel_ships_current_code():
    found = kernels()
    assert len(found) >= 15, [k.__name__ for k in found]
    missing = [k.__name__ for k in found if not shipped_entries(k)]
    assert not missing, f"kernels without current shipped code (their source changed?): {missing}; refresh: {REFRESH}"
    for k in found:
        for key in shipped_entries(k):
            assert key[1][1] == "generic", (k.__name__, key[1])  # portable machine code only


WORKLOAD = """
import gc, json
import numpy as np
import lkspace
from lkspace.compiled.kernels import Kernel
from lkspace.knots.keyed import keys_of
cube = lkspace.load("cube")
rows = np.random.default_rng(0).integers(-1, 2, size=(5000, cube.n_edges))
keys = keys_of(cube, rows)
count = lkspace.count_designs("cube", "-1..1")
used = [k for k in gc.get_objects() if isinstance(k, Kernel) and k._compiled is not None]
print(json.dumps({k.__name__: [sum(k.compiled.stats.cache_hits.values()), sum(k.compiled.stats.cache_misses.values())]
                  for k in used}))
"""


@pytest.mark.skipif(not SHIPPED.is_dir(), reason="no shipped kernels in this checkout")
def test_a_fresh_cache_loads_kernels_instead_of_compiling(tmp_path):
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "empty")}
    env.pop("NUMBA_CPU_NAME", None)
    out = subprocess.run([sys.executable, "-c", WORKLOAD], env=env, capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr
    stats = json.loads(out.stdout.strip().splitlines()[-1])
    assert "design_keys" in stats and len(stats) >= 3, stats
    compiled = {name: hm for name, hm in stats.items() if hm[1]}
    assert not compiled, f"compiled on a fresh cache (hits, misses): {compiled}; refresh: {REFRESH}"
    # what was loaded is now in numba's own cache: the next process reads it from there
    assert list((tmp_path / "empty").glob("knots_*/keyed.design_keys-*.nbc"))


ENUMERATE = """
import json, sys
from lkspace.cli import main
code = main(["enumerate", *sys.argv[1:]])
registries = "numba.np.arraymath" in sys.modules  # imported by numba's refresh (with scipy.linalg)
import numba, numpy as np
sort_sum = int(numba.njit(lambda a: np.sort(a).sum())(np.arange(5)))  # compiling after loading: still works
print(json.dumps({"code": code, "registries": registries, "sort_sum": sort_sum}))
"""


@pytest.mark.skipif(not SHIPPED.is_dir(), reason="no shipped kernels in this checkout")
@pytest.mark.parametrize("mesh", ["honeycomb:oF", "cube"])
def test_enumerate_loads_its_kernels_without_numba_registries(tmp_path, mesh):
    # the code of every kernel enumerate runs needs only numba's runtime; numba's refresh costs 0.3 s
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "empty")}
    env.pop("NUMBA_CPU_NAME", None)
    args = [mesh, "--labels", "-1..1", "-o", str(tmp_path / "c.parquet")]
    out = subprocess.run([sys.executable, "-c", ENUMERATE, *args], env=env, capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout.strip().splitlines()[-1]) == {"code": 0, "registries": False, "sort_sum": 10}


def test_links_now_only_for_code_whose_symbols_are_known():
    import llvmlite.binding as ll
    from numba.core.registry import cpu_target
    from numba.core.runtime import rtsys

    from lkspace.compiled.shipped import links_now

    rtsys.initialize(cpu_target.target_context)  # as before loading a kernel

    def code(*declarations: str) -> tuple:
        bitcode = ll.parse_assembly("\n".join(f"declare void @{d}()" for d in declarations)).as_bitcode()
        return (("name", "object", (b"", bitcode)),)

    assert links_now(code("PyErr_Clear", "NRT_MemInfo_alloc_aligned", "llvm.trap"))
    assert not links_now(code("PyErr_Clear", "lkspace_no_such_symbol"))
    assert not links_now((("name", "bitcode", b""),))
    assert not links_now(())
