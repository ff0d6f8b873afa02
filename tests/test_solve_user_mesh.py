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


def torus_obj(path, around=8, across=4):
    """Write a quad torus (``2 * around * across`` edges, genus 1) as an OBJ file."""
    rows = []
    for i in range(around):
        for j in range(across):
            a, b = 2 * math.pi * i / around, 2 * math.pi * j / across
            rows.append(
                f"v {(2 + 0.7 * math.cos(b)) * math.cos(a):.6f} {(2 + 0.7 * math.cos(b)) * math.sin(a):.6f} {0.7 * math.sin(b):.6f}"
            )

    def at(i, j):
        return (i % around) * across + j % across + 1

    rows += [
        f"f {at(i, j)} {at(i + 1, j)} {at(i + 1, j + 1)} {at(i, j + 1)}" for i in range(around) for j in range(across)
    ]
    path.write_text("\n".join(rows) + "\n")
    return str(path)


def test_on_a_mesh_too_big_to_walk_the_diagram_answers_or_the_refusal_names_the_labels_it_needs(tmp_path):
    """Tori of 36 and 64 edges (3^36, 3^64 designs: too many to walk).  On the first, the trefoil's diagram fits
    with labels -1..1 and its design comes back, said to be perhaps not the simplest; on the second (no
    triangle of faces) the diagram needs labels -3..3: without ``--labels`` the search takes them and says so,
    with ``--labels -1..1`` the refusal names them."""
    topoly = pytest.importorskip("topoly")
    from lkspace import load, realize

    wide = torus_obj(tmp_path / "torus8x4.obj", 8, 4)
    refused = solve(wide, "--type", "m3_1", "--labels", "-1..1")
    assert refused.returncode == 2 and "with labels in -3..3" in refused.stderr, refused.stderr
    widened = solve(wide, "--type", "m3_1")
    assert widened.returncode == 0, widened.stderr
    answer = json.loads(widened.stdout)
    assert answer["status"] == "found" and answer["label_set"] == [-3, -2, -1, 0, 1, 2, 3]
    labels = answer["solutions"][0]["labels"]
    assert max(map(abs, labels)) == 3  # the diagram needs them: none fits in -2..2
    curves = realize(load(wide), np.array(labels)).curves
    assert len(curves) == 1
    assert topoly.homfly(np.asarray(curves[0]).tolist(), closure=0, max_cross=200, chiral=True) == "-3_1"
    human = subprocess.run(
        [sys.executable, "-m", "lkspace", "solve", wide, "--type", "m3_1"], capture_output=True, text=True
    )
    assert "labels -3..3: the diagram of m3_1 needs them on this mesh" in human.stdout, human.stdout
    mesh = torus_obj(tmp_path / "torus6x3.obj", 6, 3)
    done = solve(mesh, "--type", "m3_1")
    assert done.returncode == 0, done.stderr
    data = json.loads(done.stdout)
    assert data["status"] == "found" and "need not be the simplest" in data["reason"]
    labels = data["solutions"][0]["labels"]
    curves = realize(load(mesh), np.array(labels)).curves
    assert len(curves) == 1
    assert topoly.homfly(np.asarray(curves[0]).tolist(), closure=0, max_cross=120, chiral=True) == "-3_1"


def test_a_diagram_without_kinks_on_a_sphere_answers_at_once_as_the_simplest():
    """prism:3 holds the Tait graph of 8_17 with no face left over: sum |t| = 8 = its crossing number,
    as simple as a design of 8_17 can be, so the design built from its diagram answers and no walk runs."""
    done = solve("prism:3", "--type", "8_17", "--labels", "-2..2")
    assert done.returncode == 0, done.stderr
    data = json.loads(done.stdout)
    assert data["status"] == "found" and data["solutions"][0]["sum_abs"] == 8 and "reason" not in data
    assert data["stats"]["designs"] == data["stats"]["designs built from the diagram"]  # the walk never ran
