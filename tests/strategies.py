"""Hypothesis strategies: random non-manifold scaffolds and labels."""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st

from lkspace import Scaffold


@st.composite
def scaffolds(draw, max_vertices: int = 8, max_faces: int = 7):
    """Random polygon meshes with generic vertex positions (unambiguous radial order).

    Faces are random vertex cycles, so edges of any degree, boundary, vertex-only
    contacts and two-sided polygons all occur.
    """
    n = draw(st.integers(3, max_vertices))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    vertices = rng.normal(size=(n, 3))
    n_faces = draw(st.integers(1, max_faces))
    faces = []
    for _ in range(n_faces):
        size = draw(st.integers(3, min(n, 6)))
        faces.append(draw(st.permutations(range(n)))[:size])
    if draw(st.booleans()) and faces:  # a two-sided polygon now and then
        faces.append(list(reversed(faces[0])))
    return Scaffold.from_faces(vertices, faces, name="random")


def _traceable(scaffold) -> bool:
    from lkspace.errors import RadialOrderError

    try:
        scaffold.radial
    except RadialOrderError:  # two faces at one angle around an edge of degree >= 3
        return False
    return True


def traceable_scaffolds(**kwargs):
    """Random scaffolds whose radial order is unambiguous."""
    return scaffolds(**kwargs).filter(_traceable)
