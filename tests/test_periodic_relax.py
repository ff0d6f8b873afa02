"""Periodic designs smoothed and relaxed in the periodic cell, through ``python -m lkspace export``.

Everything is measured here from the written files (OBJ polylines, binary PLY), with
code of its own (and ``tests/ropelength.py``), never with ``lkspace.geometry``.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

from .ropelength import curvature_radii, read_obj_polylines

ROOT = Path(__file__).resolve().parents[1]


def export(tmp_path: Path, name: str, *args: str) -> tuple[Path, dict]:
    """Run ``python -m lkspace export ARGS --json -o tmp_path/name``; return the file and the JSON."""
    out = tmp_path / name
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run(
        [sys.executable, "-m", "lkspace", "export", *args, "-o", str(out), "--json"],
        capture_output=True,
        text=True,
        env=env,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    return out, json.loads(done.stdout)


def dense(points: np.ndarray, closed: bool, spacing: float) -> np.ndarray:
    """Points about ``spacing`` apart along the polyline."""
    p = np.vstack([points, points[:1]]) if closed else points
    seg = np.linalg.norm(np.diff(p, axis=0), axis=1)
    cum = np.concatenate([[0.0], np.cumsum(seg)])
    s = np.linspace(0.0, cum[-1], max(3, int(np.ceil(cum[-1] / spacing))))
    return np.column_stack([np.interp(s, cum, p[:, i]) for i in range(3)])


def between_curves(curves: list[tuple[np.ndarray, bool]], spacing: float = 0.005) -> float:
    """Least distance between points of two different polylines."""
    pts = [dense(c, cl, spacing) for c, cl in curves]
    best = np.inf
    for k, p in enumerate(pts):
        others = [q for m, q in enumerate(pts) if m != k]
        if others:
            best = min(best, float(cKDTree(np.vstack(others)).query(p)[0].min()))
    return best


def ring_ropelength(curves: list[tuple[np.ndarray, bool]]) -> float:
    """Mean ring length / the thickness the rings carry (least bend, half the least gap between rings)."""
    length = np.mean([np.linalg.norm(np.diff(np.vstack([c, c[:1]]), axis=0), axis=1).sum() for c, _ in curves])
    bend = min(float(curvature_radii(c, True).min()) for c, _ in curves)
    return float(length / min(bend, 0.5 * between_curves(curves)))


def test_chainmail_rings_relax_round_and_apart(tmp_path):
    # the square chainmail: one ring per cell, smoothed by default, relaxed with --relax
    smooth_path, smooth = export(tmp_path, "s.obj", "tiling:square", "--twist", "2", "--block", "3x3")
    tight_path, tight = export(tmp_path, "t.obj", "tiling:square", "--twist", "2", "--block", "3x3", "--relax")
    rings, smooth_rings = read_obj_polylines(tight_path), read_obj_polylines(smooth_path)
    assert len(rings) == len(smooth_rings) == 9 and all(cl for _, cl in rings)  # 3 x 3 cells, one ring each
    assert tight["relaxation"]["converged"]
    # distinct rings (a ring and its neighbours' translates) at least a tube diameter apart
    gap = between_curves(rings)
    assert gap >= 2 * tight["tube_radius"], (gap, tight["tube_radius"])
    # round: tighter than the smoothed construction, measured here (47.4 -> 33.9 when written; the
    # smoothing spreads the rings to 2 insets since issue 34, and already reaches 35.6)
    before, after = ring_ropelength(smooth_rings), ring_ropelength(rings)
    assert after < 0.97 * before, (before, after)
    bend = [min(float(curvature_radii(c, True).min()) for c, _ in r) for r in (smooth_rings, rings)]
    # least curvature radius 0.134 -> 0.190 when written; the smoothing of issue 34 already bends no tighter (0.214)
    assert min(bend) >= tight["tube_radius"], bend
    # every copy of the class has one shape: the rings are translates of each other
    centred = [c - c.mean(axis=0) for c, _ in rings]
    assert all(len(c) == len(centred[0]) and np.allclose(c, centred[0], atol=1e-6) for c in centred)


def test_weave_relaxed_threads_stay_apart_and_whole(tmp_path):
    path, data = export(tmp_path, "w.obj", "tiling:hexagonal", "--twist", "1", "--block", "3x3", "--relax")
    threads = read_obj_polylines(path)
    assert threads and not any(cl for _, cl in threads)  # infinite threads, cut at the block's faces
    assert between_curves(threads) >= 2 * data["tube_radius"]
    names = [line.split()[1] for line in path.read_text().splitlines() if line.startswith("o ")]
    classes = {n.split("_")[1] for n in names}
    assert len(classes) == data["components"] == 3  # the triaxial weave: three thread classes


def read_ply_edges(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """Vertex colours ``(n, 3)`` and edges ``(m, 2)`` of a binary PLY of polylines."""
    raw = path.read_bytes()
    end = raw.index(b"end_header\n") + len(b"end_header\n")
    header = raw[:end].decode().splitlines()
    nv = int(next(h for h in header if h.startswith("element vertex")).split()[-1])
    ne = int(next(h for h in header if h.startswith("element edge")).split()[-1])
    vdt = np.dtype([("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("r", "u1"), ("g", "u1"), ("b", "u1")])
    v = np.frombuffer(raw, vdt, nv, end)
    e = np.frombuffer(raw, np.dtype([("a", "<i4"), ("b", "<i4")]), ne, end + nv * vdt.itemsize)
    return np.column_stack([v["r"], v["g"], v["b"]]), np.column_stack([e["a"], e["b"]])


def test_one_colour_per_thread_class_across_cells(tmp_path):
    ply, data = export(tmp_path, "w.ply", "tiling:hexagonal", "--twist", "1", "--block", "3x3")
    obj, _ = export(tmp_path, "w.obj", "tiling:hexagonal", "--twist", "1", "--block", "3x3")
    colours, edges = read_ply_edges(ply)
    assert np.array_equal(colours[edges[:, 0]], colours[edges[:, 1]])  # a run is one colour
    runs = read_obj_polylines(obj)
    assert len(runs) == data["curves"] > 3
    # one colour per class: 3 colours for the many runs, and runs of one class share theirs
    assert len({tuple(c) for c in colours.tolist()}) == data["components"] == 3
    names = [line.split()[1] for line in obj.read_text().splitlines() if line.startswith("o ")]
    starts = np.cumsum([0] + [len(c) for c, _ in runs[:-1]])
    by_class: dict[str, set[tuple[int, ...]]] = {}
    for name, s in zip(names, starts, strict=True):
        by_class.setdefault(name.split("_")[1], set()).add(tuple(colours[s].tolist()))
    assert all(len(c) == 1 for c in by_class.values()) and len(by_class) == 3


def test_periodic_relax_is_deterministic(tmp_path):
    args = ("honeycomb:cP", "--twist", "2,1,1", "--relax-steps", "150")
    a, _ = export(tmp_path, "a.obj", *args)
    b, _ = export(tmp_path, "b.obj", *args)
    assert a.read_bytes() == b.read_bytes()


def test_image_pairs_match_brute_force():
    # every pair of points within r of each other's lattice images, against all images up to +-6 cells
    from itertools import product

    from lkspace.geometry.cell import image_pairs

    rng = np.random.default_rng(3)
    for basis in (np.array([[1.0, 0, 0], [0.5, 0.8, 0], [0.2, 0.1, 0.9]]), np.array([[1.0, 0, 0], [-0.5, 0.87, 0]])):
        points = rng.uniform(-1.5, 1.5, (60, 3))
        r = 0.45
        want = set()
        for t in product(range(-6, 7), repeat=len(basis)):
            d = np.linalg.norm(points[:, None] - points[None] - np.asarray(t) @ basis, axis=2)
            for i, j in zip(*np.nonzero(d <= r), strict=True):
                if i != j or any(t):
                    want.add((int(i), int(j), t))
        i, j, m = image_pairs(points, basis, r)
        got = {(int(a), int(b), tuple(c)) for a, b, c in zip(i, j, m.tolist(), strict=True)}
        got |= {(b, a, tuple(-x for x in c)) for a, b, c in got}
        assert got == want
