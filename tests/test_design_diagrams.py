"""Many diagrams assembled in one compiled call equal the diagrams assembled one by one.

The pieces are checked against networkx: a graph on the PD code's edges, each crossing
joining its four edges, plus one piece per component that crosses nothing.
"""

from __future__ import annotations

import networkx as nx
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from lkspace import load
from lkspace.knots.assembled import assemble_many
from lkspace.knots.assembly import assemble_one, work_array
from lkspace.knots.design_diagrams import DesignDiagrams
from lkspace.knots.keyed import keys_of

SCAFFOLDS = {name: load(name) for name in ("tetrahedron", "cube", "octahedron", "book:3")}


def reference_pieces(pd: np.ndarray, n_free: int) -> int:
    """Return the pieces of a PD code by networkx: its edges joined at crossings, and each free component."""
    graph = nx.Graph()
    for row in pd.tolist():
        graph.add_nodes_from(row)
        graph.add_edges_from((row[0], other) for other in row[1:])
    return nx.number_connected_components(graph) + n_free


@settings(max_examples=40, deadline=None)
@given(name=st.sampled_from(sorted(SCAFFOLDS)), seed=st.integers(0, 2**32 - 1), n=st.integers(1, 30))
def test_a_batch_assembles_what_each_design_assembles_alone(name, seed, n):
    scaffold = SCAFFOLDS[name]
    rng = np.random.default_rng(seed)
    labels = rng.integers(-2, 3, size=(n, scaffold.n_edges))
    found = keys_of(scaffold, labels)
    arrays, work = found.template.arrays(), work_array(found.template)
    pd, signs, offsets, components, pieces = assemble_many(arrays, np.ascontiguousarray(found.vidx), work)
    assert offsets[0] == 0
    assert offsets[-1] == len(pd) == len(signs)
    for i in range(n):
        one_pd, one_signs, _, n_comp, n_free = assemble_one(arrays, found.vidx[i], work)
        rows = slice(offsets[i], offsets[i + 1])
        np.testing.assert_array_equal(pd[rows], one_pd)
        np.testing.assert_array_equal(signs[rows], one_signs)
        assert components[i] == n_comp
        assert pieces[i] == reference_pieces(one_pd, n_free)
    as_python = assemble_many.py_func(arrays, np.ascontiguousarray(found.vidx), work_array(found.template))
    for compiled, plain in zip((pd, signs, offsets, components, pieces), as_python, strict=True):
        np.testing.assert_array_equal(compiled, plain)  # a few designs are assembled as Python (DesignDiagrams.prepare)


def test_designs_prepared_together_or_alone_have_one_diagram():
    cube = SCAFFOLDS["cube"]
    labels = np.random.default_rng(5).integers(-1, 2, size=(50, cube.n_edges))
    found = keys_of(cube, labels)
    together, alone = DesignDiagrams(found), DesignDiagrams(found)
    together.prepare(list(range(50))[::-1])
    for d in range(50):
        pd, n_comp, signs = found.diagram(d)
        for diagrams in (together, alone):
            got_pd, got_comp, got_signs = diagrams.diagram(d)
            assert got_pd == pd
            assert got_comp == n_comp
            np.testing.assert_array_equal(got_signs, signs)


def test_diagrams_in_pieces_no_free_component_explains_are_counted():
    octahedron = SCAFFOLDS["octahedron"]
    labels = np.random.default_rng(2).integers(-2, 3, size=(3000, octahedron.n_edges))
    found = keys_of(octahedron, labels)
    arrays, work = found.template.arrays(), work_array(found.template)
    pd, _, offsets, _, pieces = assemble_many(arrays, np.ascontiguousarray(found.vidx), work)
    apart = [i for i in range(len(labels)) if pieces[i] > 1 and found.free[i] == 0]
    assert len(apart) >= 3
    for i in apart:
        assert pieces[i] == reference_pieces(pd[offsets[i] : offsets[i + 1]], 0)
