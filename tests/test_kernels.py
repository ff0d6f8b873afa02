"""Compiled kernels and their plain-Python runs agree (small jobs skip numba entirely)."""

import os
import subprocess
import sys

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import lkspace
from lkspace.compiled.kernels import SMALL_WORK, Kernel, kernel
from lkspace.compiled.loops import join_pairs
from lkspace.model.specs import parse_label_set
from lkspace.strands.holding_together import echelon_index, winding_links
from lkspace.strands.ports import edge_partner, port_model
from lkspace.strands.walk import walk_strands

from .strategies import traceable_scaffolds


def _walk_args(scaffold, labels):
    model = port_model(scaffold)
    partner = edge_partner(model, scaffold.edge_degrees, labels)
    translation = scaffold.side_translation if scaffold.periodic else np.zeros((scaffold.n_corners, 0), np.int64)
    return model.corner_partner, partner, np.ascontiguousarray(translation)


def _joins(kernel_func, pairs, shifts, n):
    """``join_pairs`` as run by ``kernel_func`` (plain or compiled): pieces and the closed translations."""
    dim = shifts.shape[1]
    parent, size, pot = np.arange(n), np.ones(n, np.int64), np.zeros((n, dim), np.int64)
    closed = np.zeros((len(pairs), dim), np.int64)
    joined = kernel_func(parent, size, pot, pairs, np.ascontiguousarray(shifts), closed)
    return n - int(joined.sum()), closed[~joined]


def _same(a, b):
    if isinstance(a, tuple):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    return np.array_equal(np.asarray(a), np.asarray(b))


@settings(max_examples=60, deadline=None)
@given(traceable_scaffolds(), st.integers(0, 2**32 - 1))
def test_walk_and_holding_together_agree_compiled_and_plain(scaffold, seed):
    labels = np.random.default_rng(seed).integers(-3, 4, scaffold.n_edges)
    args = _walk_args(scaffold, labels)
    assert _same(walk_strands.py_func(*args), walk_strands.compiled(*args))
    trace = lkspace.trace(scaffold, labels)
    pairs, shifts = winding_links(trace)
    plain = _joins(join_pairs.py_func, pairs, shifts, trace.components)
    assert _same(plain, _joins(join_pairs.compiled, pairs, shifts, trace.components))


def test_periodic_kernels_agree():
    for name in ("honeycomb:cP@2x2x2", "tiling:hexagonal@3x2", "honeycomb:cI"):
        scaffold = lkspace.load(name)
        for t in parse_label_set("-2..3").tolist():
            labels = np.full(scaffold.n_edges, t)
            args = _walk_args(scaffold, labels)
            assert _same(walk_strands.py_func(*args), walk_strands.compiled(*args))
            trace = lkspace.trace(scaffold, labels)
            pairs, shifts = winding_links(trace)
            plain = _joins(join_pairs.py_func, pairs, shifts, trace.components)
            compiled = _joins(join_pairs.compiled, pairs, shifts, trace.components)
            assert _same(plain, compiled)
            vectors = np.concatenate([trace.periods, plain[1]])
            assert echelon_index.py_func(vectors) == echelon_index.compiled(vectors)


def test_run_picks_plain_python_for_small_jobs_only():
    def double(x):
        return 2 * x

    k = kernel(double)
    assert isinstance(k, Kernel) and "not compiled" in repr(k)
    assert k.run(SMALL_WORK - 1, 21) == 42 and "not compiled" in repr(k)  # ran as plain Python
    assert k.run(SMALL_WORK, 4) == 8 and "(compiled)" in repr(k)
    assert k(5) == 10 == k.run(1, 5)  # once compiled, always compiled


HELPERS_MODULE = """
from lkspace.compiled.kernels import helper


@helper
def bump(x):
    return x + STEP


@helper
def bump_all(a, out):
    for i in range(len(a)):
        out[i] = bump(a[i])
"""

KERNEL_MODULE = """
import numpy as np

from lkspace.compiled.kernels import kernel

from .helpers import bump_all


@kernel
def bumped_sum(a):
    out = np.empty_like(a)
    bump_all(a, out)
    return out.sum()
"""

RUN = """
import sys
import numpy as np
from pkg.kern import bumped_sum
a = np.arange(5)
plain = bumped_sum.run(1, a)
assert "numba" not in sys.modules  # the small job ran the plain helpers
if sys.argv[1] == "compiled":
    print(int(bumped_sum(a)), int(plain), bool(bumped_sum.compiled.stats.cache_hits), bool(bumped_sum.compiled.stats.cache_misses))
else:
    print(int(plain))
"""


def _run(tmp_path, mode):
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache"), "PYTHONPATH": str(tmp_path)}
    done = subprocess.run([sys.executable, "-c", RUN, mode], env=env, capture_output=True, text=True, check=True)
    return done.stdout.split()


def test_kernels_call_helpers_plain_and_compiled_and_the_cache_follows_helper_edits(tmp_path):
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "helpers.py").write_text("STEP = 1\n" + HELPERS_MODULE)
    (pkg / "kern.py").write_text(KERNEL_MODULE)
    assert _run(tmp_path, "plain") == ["15"]  # 1 + 2 + 3 + 4 + 5, numba never imported
    assert _run(tmp_path, "compiled") == ["15", "15", "False", "True"]  # compiled and saved
    assert _run(tmp_path, "compiled") == ["15", "15", "True", "False"]  # a second process loads it
    # a constant a helper reads changes in another file: the kernel's file is untouched, its cached code stale
    (pkg / "helpers.py").write_text("STEP = 2\n" + HELPERS_MODULE)
    assert _run(tmp_path, "compiled") == ["20", "20", "False", "True"]
