"""Geometry worth showing: regular, evenly spaced helices, symmetric designs realized
symmetrically, knot types kept, and periodic blocks cut to their cells."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import cKDTree

import lkspace
from lkspace import GeometryParams, RealizeOptions, load, realize
from lkspace.errors import GeometryError
from lkspace.geometry.block import clip_curves, join_curves, realize_block
from lkspace.geometry.clearance import resample
from lkspace.geometry.helix import RAMP, spacing_weight, twist_profile
from lkspace.symmetry.group import symmetry_group


def test_twist_profile_and_spacing_weight():
    s = np.linspace(0, 1, 2001)
    g, w = twist_profile(s), spacing_weight(s)
    assert g[0] == 0 and g[-1] == pytest.approx(1) and np.all(np.diff(g) >= 0)
    np.testing.assert_allclose(g + g[::-1], 1, atol=1e-12)  # G(1 - s) = 1 - G(s)
    slope = np.gradient(g, s)
    middle = (s > RAMP + 0.01) & (s < 1 - RAMP - 0.01)
    np.testing.assert_allclose(slope[middle], 1 / (1 - RAMP), rtol=1e-6)  # a regular helix there
    assert slope[0] == pytest.approx(0, abs=1e-3) and slope[-1] == pytest.approx(0, abs=1e-3)
    assert w[0] == 0 and w[-1] == 0 and np.all(w[middle] == 1)


@pytest.mark.parametrize("k, t", [(3, 1), (4, 3), (5, 2)])
def test_book_spine_carries_evenly_spaced_regular_helices(k, t):
    # the construction (smoothing off): its helices are exact
    real = realize(f"book:{k}", t, params=GeometryParams(samples_per_turn=400, edge_samples=400, smooth=False))
    pts = np.vstack(real.curves)
    owner = np.repeat(np.arange(real.n_curves), [len(c) for c in real.curves])
    near = np.hypot(pts[:, 0], pts[:, 1]) < 0.2  # on the spine (the z axis)
    z = pts[near, 2]
    lo, hi = z.min(), z.max()
    mid = 0.5 * (lo + hi)
    layer = near & (np.abs(pts[:, 2] - mid) < 0.004)
    angles = np.sort(np.arctan2(pts[layer, 1], pts[layer, 0]))
    radii = np.hypot(pts[layer, 0], pts[layer, 1])
    # cluster the layer's points into the K strands passing the middle of the spine
    groups = np.split(angles, np.flatnonzero(np.diff(angles) > 0.2) + 1)
    if len(groups) > k:  # the first and last group are one strand across -pi/pi
        groups = [np.concatenate([groups[-1] - 2 * np.pi, groups[0]])] + groups[1:-1]
    assert len(groups) == k
    centres = np.sort([np.mean(g) % (2 * np.pi) for g in groups])
    gaps = np.diff(np.concatenate([centres, [centres[0] + 2 * np.pi]]))
    np.testing.assert_allclose(gaps, 2 * np.pi / k, atol=0.05)  # 2 pi / K apart
    assert np.ptp(radii) < 1e-3  # one helix radius
    # one pass's angle grows linearly with z in the middle of the spine: a regular helix, right-handed for t > 0
    first = int(np.flatnonzero(layer)[0])
    curve = real.curves[owner[first]]
    at = first - int(np.flatnonzero(owner == owner[first])[0])
    run = [at]
    for step in (-1, 1):  # walk along the curve while it stays in the middle of the spine
        i = at + step
        while 0 <= i < len(curve) and abs(curve[i, 2] - mid) < 0.05:
            run.append(i)
            i += step
    seg = curve[np.sort(run)]
    phi = np.unwrap(np.arctan2(seg[:, 1], seg[:, 0]))
    fit = np.polyfit(seg[:, 2], phi, 1)
    assert len(seg) > 10 and np.sign(fit[0]) == np.sign(t)
    assert np.max(np.abs(np.polyval(fit, seg[:, 2]) - phi)) < 0.01


def hausdorff_to(real, mapped: np.ndarray) -> float:
    dense = np.vstack(
        [resample(c, bool(cl), 0.002 * real.scale).points for c, cl in zip(real.curves, real.closed, strict=True)]
    )
    return float(cKDTree(dense).query(mapped)[0].max())


@pytest.mark.parametrize("smooth, tolerance", [(False, 0.003), (True, 0.015)])
@pytest.mark.parametrize("name", ["cube", "tetrahedron", "dihedron:5", "book:4", "truncated-octahedron"])
def test_symmetric_designs_realize_symmetrically(name, smooth, tolerance):
    # the construction is symmetric up to its sampling; the smoothing flow acts on samples
    # placed from each curve's start, so it keeps the symmetry to about a point spacing
    scaffold = lkspace.load(name)
    group = symmetry_group(scaffold)
    rng = np.random.default_rng(7)
    checked = 0
    for g in range(1, group.order):
        if not group.proper[g] or checked >= 6:
            continue
        perm = group.edge_perms[g]
        labels = np.full(scaffold.n_edges, 99)
        for e in range(scaffold.n_edges):  # random labels constant on the orbits of <g>
            if labels[e] == 99:
                orbit, x = [e], perm[e]
                while x != e:
                    orbit.append(int(x))
                    x = perm[x]
                labels[orbit] = rng.integers(-2, 3)
        real = realize(scaffold, labels, params=GeometryParams(smooth=smooth))
        mapped = np.vstack(real.curves) @ group.matrices[g].T + group.translations[g]
        assert hausdorff_to(real, mapped) < tolerance * real.scale  # the sampling, not the geometry
        checked += 1
    assert checked > 0


@pytest.mark.parametrize(
    "mesh, twist, name",
    [("tetrahedron", 1, "L6a4"), ("dihedron:3", 1, "3_1"), ("book:4", 3, "8_19"), ("whitehead", None, "L5a1")],
)
def test_knot_types_are_kept(mesh, twist, name):
    pytest.importorskip("snappy")
    assert lkspace.identify(mesh, twist, geometric=True).name == name  # the realized helices


def test_pitch_confines_the_twist_and_is_checked():
    free = realize("book:3", 1)
    tight = realize("book:3", 1, params=GeometryParams(pitch=0.2))
    assert tight.min_distance > 0 and free.n_curves == tight.n_curves
    with pytest.raises(GeometryError, match="`pitch` 5 needs") as bad:
        realize("book:3", 2, params=GeometryParams(pitch=5.0))
    assert bad.value.parameter == "pitch" and bad.value.exit_code == 2


@pytest.mark.parametrize(
    "name, labels, sizes", [("honeycomb:cP", [2, 1, 1], (2, 2, 2)), ("tiling:hexagonal", 1, (3, 2))]
)
def test_block_is_cut_to_its_cells(name, labels, sizes):
    real = realize_block(load(name), labels, None, None, sizes)
    block = real.block
    assert block is not None
    half = block.sizes / 2 + block.slack()
    for curve, closed in zip(real.curves, real.closed, strict=True):
        f = block.fractional(curve)
        if closed:  # a closed loop is whole: its centre is in the block
            assert np.all(np.abs(block.fractional(curve.mean(axis=0))) <= block.sizes / 2 + 1e-9)
        else:  # one run per thread, in the widened block (straying past it by a little) and ending on its surface
            assert np.all(np.abs(f) <= half + 0.1)
            for end in (f[0], f[-1]):
                assert np.max(np.abs(end) - half) == pytest.approx(0, abs=1e-9)
    # nothing is missing: one more layer of translates all round, joined and cut the same way, gives the same runs
    scaffold = lkspace.load(name)
    steps = np.array(np.meshgrid(*[[-1, 0, 1]] * scaffold.dim, indexing="ij")).reshape(scaffold.dim, -1).T
    more = np.unique((real.translations[:, None] + steps[None]).reshape(-1, scaffold.dim), axis=0)
    assert len(more) > len(real.translations)
    wide = realize(scaffold, labels, options=RealizeOptions(embedding="measure", translations=more))
    joined, flags, _ = join_curves(wide.curves, wide.closed, 1e-6 * wide.scale)
    pieces, _, _ = clip_curves(joined, flags, block)
    lengths = sorted(float(np.linalg.norm(np.diff(c, axis=0), axis=1).sum()) for c in pieces)
    ours = sorted(float(np.linalg.norm(np.diff(c, axis=0), axis=1).sum()) for c in real.curves)
    assert len(lengths) == len(ours)
    np.testing.assert_allclose(lengths, ours, rtol=1e-9)
