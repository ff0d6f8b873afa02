"""Diagrams from labels against the geometric path (realize, project) it replaces.

The reference is independent of the template: it realizes each design's own curves
(:func:`lkspace.realize`), projects them (:func:`lkspace.knots.diagram.project_generic`)
and lets regina compute the Jones polynomial of that PD code.  The template's PD code
must give the same components, linking matrix and Jones polynomial on random scaffolds
(manifold and not) and labels.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from lkspace import load
from lkspace.errors import GeometryError, LkspaceError
from lkspace.geometry.params import GeometryParams
from lkspace.geometry.realization import realize
from lkspace.knots.assembly import assemble_pd
from lkspace.knots.diagram import project_generic
from lkspace.knots.labels_diagram import build_template

from .strategies import traceable_scaffolds

regina = pytest.importorskip("regina")


def geometric(scaffold, labels):
    """Components, linking matrix and Jones polynomial (regina) of the realized, projected curves."""
    curves = realize(scaffold, labels, params=GeometryParams(smooth=False)).curves
    d = project_generic(curves, seed=3)
    return len(curves), d.linking_matrix().tolist(), _jones(d.pd, len(curves))


def _jones(pd, n_components):
    """Jones polynomial (regina, in x = sqrt(t)) of the link, free components included."""
    if len(pd):
        link = regina.Link.fromPD([[int(v) for v in x] for x in pd])
        poly, drawn = link.jones(), link.countComponents()
    else:
        poly, drawn = regina.Laurent(0, [1]), 1
    for _ in range(n_components - drawn):
        poly = poly * regina.Laurent(-1, [-1, 0, -1])
    return str(poly)


def combinatorial(scaffold, labels, seed=0):
    d = assemble_pd(scaffold, labels, seed)
    return d.n_components, d.linking_matrix().tolist(), _jones(d.pd, d.n_components)


@pytest.mark.parametrize(
    "name", ["tetrahedron", "cube", "octahedron", "dihedron:5", "book:4", "figure-eight", "whitehead", "cubes:vertex"]
)
def test_builtin_designs_match_the_geometric_path(name):
    scaffold = load(name)
    rng = np.random.default_rng(7)
    for _ in range(4):
        labels = rng.integers(-2, 3, scaffold.n_edges)
        assert combinatorial(scaffold, labels) == geometric(scaffold, labels), labels.tolist()


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(traceable_scaffolds(max_vertices=7, max_faces=5), st.integers(0, 2**32 - 1))
def test_random_scaffolds_match_the_geometric_path(scaffold, seed):
    labels = np.random.default_rng(seed).integers(-2, 3, scaffold.n_edges)
    try:
        want = geometric(scaffold, labels)
    except (GeometryError, LkspaceError):
        assume(False)  # no embedded reference for this mesh (intersecting faces)
    assert combinatorial(scaffold, labels) == want


def test_the_projection_seed_changes_the_diagram_not_the_link():
    cube = load("cube")
    labels = [1, -1, 2, 0, 0, 1, -2, 1, 0, 1, 1, -1]
    a, b = assemble_pd(cube, labels, 0), assemble_pd(cube, labels, 5)
    assert a.pd.tolist() != b.pd.tolist()
    assert combinatorial(cube, labels, 0) == combinatorial(cube, labels, 5)


def test_hand_checked_designs():
    # dihedron:3 with twist 1 everywhere: the right-handed trefoil, V = t + t^3 - t^4 (x = sqrt(t))
    d = assemble_pd(load("dihedron:3"), [1, 1, 1])
    assert d.n_components == 1 and _jones(d.pd, 1) == "-x^8 + x^6 + x^2"
    d = assemble_pd(load("dihedron:3"), [-1, -1, -1])
    assert _jones(d.pd, 1) == "x^-2 + x^-6 - x^-8"
    # twist 0 everywhere: every face its own unknotted loop, unlinked
    cube = load("cube")
    d = assemble_pd(cube, np.zeros(12, np.int64))
    assert d.n_components == 6 and not d.linking_matrix().any()
    # dihedron:4, one edge with two half-twists (a full turn of the two strands): the Hopf link
    d = assemble_pd(load("dihedron:4"), [2, 0, 0, 0])
    assert d.n_components == 2 and abs(d.linking_matrix()[0, 1]) == 1


def test_labels_outside_the_template_are_refused():
    cube = load("cube")
    tmpl = build_template(cube, [-1, 0, 1])
    with pytest.raises(LkspaceError, match="labels: twist 2"):
        tmpl.value_index([2] * 12)
