import numpy as np
import pytest

import lkspace


@pytest.fixture
def tetra():
    return lkspace.load("tetrahedron")


@pytest.fixture
def cube():
    return lkspace.load("cube")


@pytest.fixture
def rng():
    return np.random.default_rng(12345)
