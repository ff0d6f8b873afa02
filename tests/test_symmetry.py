"""Symmetry groups: known orders, every element a rigid symmetry, tracing invariant under it."""

from __future__ import annotations

import numpy as np
import pytest

import lkspace
from lkspace.errors import LabelError
from lkspace.model.lattice import Lattice
from lkspace.model.scaffold import Scaffold
from lkspace.symmetry.group import check_label_set, symmetry_group


def square_tiling(n: int = 1) -> Scaffold:
    """The square tiling with an n x n supercell (built here; tests only)."""
    verts = [[i, j, 0.0] for j in range(n) for i in range(n)]
    faces, offsets = [], []
    for j in range(n):
        for i in range(n):
            corners = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
            faces.append([(x % n) + n * (y % n) for x, y in corners])
            offsets.append([[x // n, y // n] for x, y in corners])
    return Scaffold.from_faces(verts, faces, offsets=offsets, lattice=Lattice.square(float(n)), name=f"square{n}")


def cubic_honeycomb(n: int = 1) -> Scaffold:
    """The cubic honeycomb (three square faces per cell) with an n x n x n supercell (tests only)."""
    import itertools

    def corner(i, j, k):
        return (i % n) + n * (j % n) + n * n * (k % n), [i // n, j // n, k // n]

    verts = [[i, j, k] for k in range(n) for j in range(n) for i in range(n)]
    faces, offsets = [], []
    quads = (
        [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)],
        [(0, 0, 0), (0, 1, 0), (0, 1, 1), (0, 0, 1)],
        [(0, 0, 0), (0, 0, 1), (1, 0, 1), (1, 0, 0)],
    )
    for i, j, k in itertools.product(range(n), repeat=3):
        for quad in quads:
            cs = [corner(i + a, j + b, k + c) for a, b, c in quad]
            faces.append([c[0] for c in cs])
            offsets.append([c[1] for c in cs])
    return Scaffold.from_faces(verts, faces, offsets=offsets, lattice=Lattice.cubic(float(n)), name=f"cP{n}")


@pytest.mark.parametrize("n, isometries, rotations", [(1, 48, 24), (2, 384, 192)])
def test_periodic_cubic_honeycomb_orders(n, isometries, rotations):
    g = symmetry_group(cubic_honeycomb(n))
    assert (g.order, g.n_rotations) == (isometries, rotations)


@pytest.mark.parametrize(
    "name, isometries, rotations",
    [
        ("tetrahedron", 24, 12),
        ("cube", 48, 24),
        ("octahedron", 48, 24),
        ("dodecahedron", 120, 60),
        ("icosahedron", 120, 60),
        ("truncated-octahedron", 48, 24),
        ("dihedron:3", 12, 6),
        ("dihedron:7", 28, 14),
        ("book:1", 16, 8),
        ("book:3", 12, 6),
        ("book:5", 20, 10),
    ],
)
def test_known_orders(name, isometries, rotations):
    g = symmetry_group(lkspace.load(name))
    assert (g.order, g.n_rotations) == (isometries, rotations)


def test_periodic_square_tiling_orders():
    g = symmetry_group(square_tiling(1))
    assert (g.order, g.n_rotations) == (16, 8)  # p4m point group x the mirror in the plane
    perms, signs = g.action("isometries")
    assert len(perms) == 4  # on the two edge classes: identity/swap, each with both signs
    g2 = symmetry_group(square_tiling(2))
    assert (g2.order, g2.n_rotations) == (64, 32)  # 4 supercell translations x 16


@pytest.mark.parametrize("name", ["tetrahedron", "cube", "dodecahedron", "dihedron:5", "book:4"])
def test_elements_are_rigid_symmetries(name):
    sc = lkspace.load(name)
    g = symmetry_group(sc)
    assert np.allclose(g.matrices[0], np.eye(3)) and np.array_equal(g.vertex_perms[0], np.arange(sc.n_vertices))
    for q, tau, sigma, perm, proper in zip(
        g.matrices, g.translations, g.vertex_perms, g.edge_perms, g.proper, strict=True
    ):
        assert np.allclose(q @ q.T, np.eye(3))
        assert (np.linalg.det(q) > 0) == proper
        assert np.allclose(sc.vertices @ q.T + tau, sc.vertices[sigma], atol=1e-9)
        a, b = sc.edge_vertices[:, 0], sc.edge_vertices[:, 1]
        image = np.sort(np.column_stack([sigma[a], sigma[b]]), axis=1)
        assert np.array_equal(image, sc.edge_vertices[perm])


def _strand_multiset(sc, t):
    return sorted(lkspace.trace(sc, t).strand_lengths.tolist())


@pytest.mark.parametrize("name", ["book:3", "book:4", "cube", "tetrahedron", "dihedron:4", "cP1", "cP2"])
def test_tracing_is_invariant_under_the_group(name, rng):
    sc = cubic_honeycomb(int(name[2])) if name.startswith("cP") else lkspace.load(name)
    perms, signs = symmetry_group(sc).action("isometries")
    for _ in range(15):
        t = rng.integers(-3, 4, sc.n_edges)
        ref = _strand_multiset(sc, t)
        for perm, s in zip(perms, signs, strict=True):
            img = np.empty_like(t)
            img[perm] = s * t
            assert _strand_multiset(sc, img) == ref


def test_mirror_images_merge_only_under_isometries(rng):
    """Chirality: the mirror image of t (reflected edges, labels negated) is the same
    design under isometries, and usually a different one under rotations."""
    from lkspace.design.space import canonical_form, make_space

    sc = lkspace.load("cube")
    g = symmetry_group(sc)
    mirror = int(np.flatnonzero(~g.proper)[0])
    iso, rot = make_space(sc, "-3..3", "isometries"), make_space(sc, "-3..3", "rotations")
    chiral = 0
    for _ in range(20):
        t = rng.integers(-3, 4, 12)
        image = np.empty_like(t)
        image[g.edge_perms[mirror]] = -t
        assert np.array_equal(canonical_form(iso, t)[0], canonical_form(iso, image)[0])
        chiral += not np.array_equal(canonical_form(rot, t)[0], canonical_form(rot, image)[0])
    assert chiral > 10


def test_isometries_need_negation_closed_labels():
    with pytest.raises(LabelError, match="lacks"):
        check_label_set(np.array([-1, 0, 1, 2]), "isometries")
    check_label_set(np.array([-1, 0, 1, 2]), "rotations")


#: (isometries, rotations) of built-ins, computed on main (2e37b23) before the symmetry search was rewritten
BUILTIN_ORDERS = {
    "tetrahedron": (24, 12),
    "cube": (48, 24),
    "truncated-tetrahedron": (24, 12),
    "cuboctahedron": (48, 24),
    "octahedron": (48, 24),
    "dodecahedron": (120, 60),
    "icosahedron": (120, 60),
    "truncated-octahedron": (48, 24),
    "figure-eight": (8, 4),
    "whitehead": (16, 8),
    "cube-net": (4, 2),
    "cube-lid": (2, 1),
    "cubes:piano": (8, 4),
    "cubes:vertex": (12, 6),
    "dihedron:3": (12, 6),
    "dihedron:4": (16, 8),
    "dihedron:5": (20, 10),
    "dihedron:6": (24, 12),
    "dihedron:7": (28, 14),
    "dihedron:8": (32, 16),
    "dihedron:9": (36, 18),
    "book:1": (16, 8),
    "book:2": (8, 4),
    "book:3": (12, 6),
    "book:4": (16, 8),
    "book:5": (20, 10),
    "book:6": (24, 12),
    "book:7": (28, 14),
    "book:8": (32, 16),
    "book:9": (36, 18),
    "tiling:square": (16, 8),
    "tiling:hexagonal": (24, 12),
    "honeycomb:cP": (48, 24),
    "honeycomb:hP": (24, 12),
    "honeycomb:oF": (8, 4),
    "honeycomb:cF": (48, 24),
    "honeycomb:cI": (48, 24),
    "voronoi:cube-faces": (48, 24),
    "laves": (24, 24),  # the Laves graph is chiral: rotations only (point group 432)
    "tiling:square@2x2": (64, 32),
    "tiling:hexagonal@2x2": (96, 48),
    "honeycomb:cP@2x2x2": (384, 192),
    "tiling:square@3x2": (48, 24),
    "honeycomb:hP@2x1x1": (16, 8),  # the lattice (2 a1, a2, c) is rectangular: 4 in-plane maps x 2 x 2 translations
}


@pytest.mark.parametrize("name", sorted(BUILTIN_ORDERS))
def test_builtin_orders_are_pinned(name):
    g = symmetry_group(lkspace.load(name))
    assert (g.order, g.n_rotations) == BUILTIN_ORDERS[name]


def test_every_builtin_is_pinned():
    from lkspace.scaffolds import SOLIDS, periodic

    assert set(SOLIDS) | set(periodic.LATTICES) | set(periodic.VORONOI_EXAMPLES) <= set(BUILTIN_ORDERS)


@pytest.mark.parametrize("name", ["cube", "tetrahedron", "dihedron:5", "book:4", "truncated-octahedron"])
def test_finite_search_needs_no_automorphism_listing(name, monkeypatch):
    import lkspace.symmetry.motions as sym

    normal = symmetry_group(lkspace.load(name))
    monkeypatch.setattr(sym, "MAX_AUTOMORPHISMS", 0)  # igraph may list nothing: finite scaffolds never need it
    forced = symmetry_group(lkspace.load(name))
    assert (forced.order, forced.n_rotations) == (normal.order, normal.n_rotations)
    assert set(map(bytes, forced.edge_perms)) == set(map(bytes, normal.edge_perms))


def test_books_with_many_pages():
    g = symmetry_group(lkspace.load("book:9"))  # 9! * 2 incidence automorphisms: too many to list
    assert (g.order, g.n_rotations) == (36, 18)


def test_groups_and_port_models_are_kept_beside_the_scaffold_not_in_it():
    import dataclasses
    import gc
    import pickle
    import weakref
    from functools import cached_property

    from lkspace.design.space import make_space
    from lkspace.strands.ports import port_model

    sc = lkspace.load("cube")
    group = symmetry_group(sc)
    assert symmetry_group(sc) is group and port_model(sc) is port_model(sc)  # found once per scaffold
    own = {f.name for f in dataclasses.fields(Scaffold)}
    own |= {name for name, value in vars(Scaffold).items() if isinstance(value, cached_property)}
    assert set(vars(sc)) <= own, set(vars(sc)) - own  # only the scaffold's own fields and derived data
    space = make_space(sc, "-1..1")
    copy = pickle.loads(pickle.dumps(space))  # a worker process gets the space with its group
    assert copy.group.order == 48 and copy.group_order == 24
    assert symmetry_group(lkspace.load("cube")) is group  # another object of the same mesh: found by content
    gone = weakref.ref(sc)
    del sc, space, group
    gc.collect()
    assert gone() is None  # the caches do not keep a scaffold alive


def test_the_same_mesh_loaded_again_shares_its_group_and_another_does_not():
    from lkspace.symmetry.group import symmetry_group

    first, again = lkspace.load("cube"), lkspace.load("cube")
    assert first is not again
    assert symmetry_group(again) is symmetry_group(first)
    moved = Scaffold.from_faces(first.vertices * [1.0, 1.0, 2.0], first.faces())  # a box: fewer symmetries
    assert symmetry_group(moved).order == 16 and symmetry_group(first).order == 48
    assert symmetry_group(first, 0.5) is not symmetry_group(first)  # by tolerance too
