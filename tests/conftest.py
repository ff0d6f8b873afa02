import numpy as np
import pytest
from hypothesis import settings

import lkspace

# no per-example deadline: on a loaded machine an example may take seconds (tests set their own sizes)
settings.register_profile("lkspace", deadline=None)
settings.load_profile("lkspace")


@pytest.fixture
def tetra():
    return lkspace.load("tetrahedron")


@pytest.fixture
def cube():
    return lkspace.load("cube")


@pytest.fixture
def rng():
    return np.random.default_rng(12345)
