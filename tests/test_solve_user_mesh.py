"""``solve MESH --type NAME`` on a user's own mesh, through the CLI: simplest designs first, time limit kept."""

from __future__ import annotations

import itertools
import json
import math
import subprocess
import sys

import numpy as np
import pytest

pytest.importorskip("snappy")


def prism_obj(path, n):
    """Write an ``n``-gonal prism (``3 n`` edges) as an OBJ file."""
    top = [(math.cos(2 * math.pi * k / n), math.sin(2 * math.pi * k / n)) for k in range(n)]
    lines = [f"v {x:.6f} {y:.6f} {z}" for z in (0, 1) for x, y in top]
    lines.append("f " + " ".join(str(k) for k in range(n, 0, -1)))
    lines.append("f " + " ".join(str(k + n) for k in range(1, n + 1)))
    for k in range(1, n + 1):
        nxt = k % n + 1
        lines.append(f"f {k} {nxt} {nxt + n} {k + n}")
    path.write_text("\n".join(lines) + "\n")
    return str(path)


def solve(*args):
    return subprocess.run([sys.executable, "-m", "lkspace", "solve", *args, "--json"], capture_output=True, text=True)


def test_a_trefoil_on_a_users_prism_is_among_the_simplest_designs(tmp_path):
    from lkspace import load
    from lkspace.knots.batch import identify_batch

    mesh = prism_obj(tmp_path / "prism3.obj", 3)
    done = solve(mesh, "--type", "3_1", "--labels", "-1..1")
    assert done.returncode == 0, done.stderr
    data = json.loads(done.stdout)
    assert data["status"] == "found" and data["solutions"][0]["name"] == "3_1"
    best = data["solutions"][0]["sum_abs"]
    # independently: no design with a smaller sum |t| is a trefoil (every one named by key)
    scaffold = load(mesh)
    smaller = [
        [dict(zip(support, signs, strict=True)).get(e, 0) for e in range(scaffold.n_edges)]
        for k in range(best)
        for support in itertools.combinations(range(scaffold.n_edges), k)
        for signs in itertools.product((-1, 1), repeat=k)
    ]
    names = identify_batch(scaffold, np.array(smaller), progress=False)["knot_name"]
    assert "3_1" not in set(names.dropna())


def test_a_time_limit_on_a_big_user_mesh_ends_the_search_as_unknown(tmp_path):
    mesh = prism_obj(tmp_path / "prism6.obj", 6)
    done = solve(mesh, "--type", "13a_1", "--labels", "-2..2", "--time-limit", "1")
    assert done.returncode == 0, done.stderr
    data = json.loads(done.stdout)
    assert data["status"] == "unknown" and not data["solutions"] and not data["exhausted"]
    assert "time ran out" in data["reason"]
