"""The full cube catalog (10,194,250 rows) through the real CLI and reader (slow: ``-m slow``)."""

import numpy as np
import pytest

import lkspace
from lkspace.cli import main


@pytest.mark.slow
def test_full_cube_catalog_round_trip(tmp_path, capsys):
    out = tmp_path / "cube.parquet"
    assert main(["enumerate", "cube", "--labels", "-2..2", "-o", str(out), "--jobs", "2"]) == 0
    capsys.readouterr()
    catalog = lkspace.read_catalog(out)
    assert catalog.labels.shape == (10_194_250, 12) and catalog.labels.dtype == np.int8
    assert int(catalog.frame.orbit_size.sum()) == 5**12
    knots = catalog[(catalog.frame.components == 1) & (catalog.frame.n_zero == 0)]
    assert len(knots) == 271_392 and int(knots.frame.orbit_size.sum()) == 6_488_064
    for row in np.random.default_rng(0).choice(len(knots), 20, replace=False):
        assert knots.trace(int(row)).components == 1
