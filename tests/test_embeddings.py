"""Surfaces of one graph and radial orders (``lkspace.design.embeddings``) against brute force.

The brute force works on vertex tuples only: automorphisms from all vertex permutations,
cycles from all vertex sequences, covers from all subsets of cycles, structures as
``{edge: (cyclic order of face cycles, value)}`` pushed around by the permutations.
"""

from __future__ import annotations

import itertools

import pytest

from lkspace import load, trace
from lkspace.design.embeddings import (
    FaceStructure,
    count_structures,
    graph_surfaces,
    list_structures,
    scaffold_structure,
)
from lkspace.design.graph_faces import cycle_space, named_graph, scaffold_of


def brute_automorphisms(n, edges):
    es = {frozenset(e) for e in edges}
    return [p for p in itertools.permutations(range(n)) if {frozenset((p[a], p[b])) for a, b in edges} == es]


def cycle_key(cycle):
    """A cycle as the set of its edges."""
    return frozenset(frozenset((cycle[i], cycle[(i + 1) % len(cycle)])) for i in range(len(cycle)))


def brute_cycles(n, edges, max_length):
    es = {frozenset(e) for e in edges}
    found = set()
    for k in range(3, max_length + 1):
        for seq in itertools.permutations(range(n), k):
            if all(frozenset((seq[i], seq[(i + 1) % k])) in es for i in range(k)):
                found.add(cycle_key(seq))
    return found


def brute_cover_classes(n, edges, max_length, per_edge):
    cycles = sorted(brute_cycles(n, edges, max_length), key=sorted)
    auts = brute_automorphisms(n, edges)
    classes = set()
    for r in range(1, len(cycles) + 1):
        for subset in itertools.combinations(cycles, r):
            if all(sum(frozenset(e) in c for c in subset) == per_edge for e in edges):
                orbit = frozenset(
                    frozenset(frozenset(frozenset(p[v] for v in e) for e in c) for c in subset) for p in auts
                )
                classes.add(orbit)
    return classes


@pytest.mark.parametrize(("name", "max_length"), [("K4", 3), ("K4", 4), ("K3,3", 6), ("cube", 4)])
def test_covers_up_to_automorphism_match_brute_force(name, max_length):
    n, edges = named_graph(name)
    space = cycle_space(n, edges, max_length)
    assert {cycle_key(c) for c in space.cycles} == brute_cycles(n, edges, max_length)
    assert len(space.automorphisms) == len(brute_automorphisms(n, edges))
    surfaces = graph_surfaces((n, edges), max_length)
    classes = brute_cover_classes(n, edges, max_length, 2)
    assert len(surfaces) == len(classes)
    assert sorted(s.covers for s in surfaces) == sorted(len(c) for c in classes)


def brute_structure_orbits(faces, auts, values_of):
    """Orbits of ``{edge: (cyclic face order, value)}`` on a face set (faces as vertex tuples)."""
    on_edge = {}
    for f in faces:
        for i in range(len(f)):
            a, b = sorted((f[i], f[(i + 1) % len(f)]))
            on_edge.setdefault((a, b), []).append(cycle_key(f))
    edges = sorted(on_edge)

    def norm(seq):
        seq = list(seq)
        i = min(range(len(seq)), key=lambda j: sorted(map(sorted, seq[j])))
        return tuple(seq[i:] + seq[:i])

    options = []
    for e in edges:
        first, *rest = on_edge[e]
        orders = {norm((first, *p)) for p in itertools.permutations(rest)}
        options.append([(o, v) for o in orders for v in values_of(len(on_edge[e]))])
    keep = [p for p in auts if {cycle_key([p[v] for v in f]) for f in faces} == {cycle_key(f) for f in faces}]
    seen, orbits = set(), 0
    for states in itertools.product(*options):
        design = dict(zip(edges, states, strict=True))
        key = frozenset(design.items())
        if key in seen:
            continue
        orbits += 1
        for p in keep:
            image = {}
            for (a, b), (order, value) in design.items():
                moved = [frozenset(frozenset(p[v] for v in s) for s in c) for c in order]
                if p[a] > p[b]:
                    moved = moved[::-1]
                image[tuple(sorted((p[a], p[b])))] = (norm(moved), value)
            seen.add(frozenset(image.items()))
    return orbits


def _k4_with_a_quad():
    n, edges = named_graph("K4")
    space = cycle_space(n, edges, 4)
    return space, tuple(i for i, c in enumerate(space.cycles) if len(c) == 3) + (4,)


@pytest.mark.parametrize("label_set", [None, (-1, 1)])
def test_radial_orders_and_values_match_brute_force(label_set):
    space, faces = _k4_with_a_quad()  # four triangles and a quad: four edges of degree 3
    st = FaceStructure.of(space, faces)
    assert sorted(len(o) for o in st.orders) == [1, 1, 2, 2, 2, 2]
    auts = brute_automorphisms(space.n_vertices, space.edges)
    values = (lambda k: range(k)) if label_set is None else (lambda k: label_set)
    expected = brute_structure_orbits([space.cycles[f] for f in faces], auts, values)
    assert count_structures(st, label_set) == expected
    listed = list_structures(st, label_set)
    assert len(listed) == expected
    assert sum(size for *_, size in listed) == 2**4 * (3**4 * 2**2 if label_set is None else 2**6)


def test_combinatorial_counts_agree_with_the_geometric_walk():
    # with every edge of degree 2 the structures are residue classes, up to graph automorphisms
    # (here the full symmetry group): lkspace enumerate --mode residues --symmetry isometries says 11 and 144
    assert count_structures(scaffold_structure(load("tetrahedron"))) == 11
    assert count_structures(scaffold_structure(load("cube"))) == 144


def test_a_chosen_radial_order_makes_a_scaffold_that_traces():
    space, faces = _k4_with_a_quad()
    st = FaceStructure.of(space, faces)
    degree3 = [int(e) for e, o in zip(st.edges, st.orders, strict=True) if len(o) == 2]
    counts = set()
    for choice in itertools.product(range(2), repeat=len(degree3)):
        orders = {e: st.orders[list(st.edges).index(e)][c] for e, c in zip(degree3, choice, strict=True)}
        sc = scaffold_of(space, faces, orders)
        assert trace(sc, 0).components == len(faces)  # zero twists: one strand per face
        counts.add(trace(sc, 1).components)
    assert len(counts) > 1  # the radial order changes the strands


def test_cli_surfaces_lists_covers_and_structures(capsys):
    import json

    from tests.cli_calls import one_line_error, run

    code, out, _ = run(capsys, "surfaces", "K3,3", "--max-length", 6, "--labels", "-1..1", "--json")
    assert code == 0
    payload = json.loads(out)
    n, edges = named_graph("K3,3")
    assert len(payload["surfaces"]) == len(brute_cover_classes(n, edges, 6, 2))
    assert payload["structures"] == sum(s["structures"] for s in payload["surfaces"])
    assert all(s["radial_orders"] == 1 for s in payload["surfaces"])  # every edge on two faces
    code, out, err = run(capsys, "surfaces", "K4", "--max-length", 40)
    assert code == 2 and out == ""
    one_line_error(err, "--max-length")


def test_cli_own_faces_counts_radial_orders(capsys):
    import json

    from tests.cli_calls import run

    code, out, _ = run(capsys, "surfaces", "book:3", "--own-faces", "--json")
    assert code == 0
    (surface,) = json.loads(out)["surfaces"]
    # three pages on one edge: 2 cyclic orders, swapped by a transposition of two pages;
    # 3 residues mod 3 on that edge, the other edges have degree 1
    assert surface["radial_orders"] == 2 and surface["structures"] == 3
