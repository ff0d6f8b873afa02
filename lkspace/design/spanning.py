"""``--mode spanning-trees``: one-component designs seeded from spanning trees of the dual graph.

The **dual graph** has a node per face and, for every edge of degree 2, a dual edge
joining its two faces.  With every label even (``t = 0 mod 2``) each face is its own strand;
an odd label on an edge of degree 2 whose two faces lie on different strands merges them
into one.  So odd labels on the edges of a spanning tree of the dual graph and even
labels elsewhere give a single strand (checked by tracing every class; a class that
does not trace to one component, possible when edges of other degrees interfere, is
dropped and counted).  Edges of degree other than 2 get residue 0.

Trees are listed exhaustively (up to ``MAX_TREES``) or sampled uniformly with Wilson's
algorithm (``sample`` trees, ``seed``), then merged up to symmetry: each row is a residue
class orbit (the schema of ``--mode residues``), with a representative label row.
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from ..compiled.loops import UnionFind
from ..errors import LabelError
from .space import DesignSpace
from .walk import ResidueRow, residue_row

MAX_TREES = 200_000


def dual_edges(space: DesignSpace) -> tuple[np.ndarray, np.ndarray]:
    """Edges of degree 2 between two different faces: ``(edge ids (m,), face pairs (m, 2))``."""
    sc = space.scaffold
    sides = sc.radial.edge_sides
    starts = sc.radial.edge_starts
    ids, pairs = [], []
    for e in np.flatnonzero(sc.edge_degrees == 2).tolist():
        f, g = sc.corner_face[sides[starts[e]]], sc.corner_face[sides[starts[e] + 1]]
        if f != g:
            ids.append(e)
            pairs.append((int(f), int(g)))
    return np.array(ids, np.int64), np.array(pairs, np.int64).reshape(-1, 2)


def all_spanning_trees(n_nodes: int, pairs: np.ndarray, limit: int = MAX_TREES) -> Iterator[tuple[int, ...]]:
    """Yield every spanning tree of a multigraph as a sorted tuple of edge positions."""
    m = len(pairs)
    chosen: list[int] = []
    count = 0

    ends = [(int(a), int(b)) for a, b in pairs.tolist()]

    def connected(allowed: list[int]) -> bool:
        pieces = UnionFind(n_nodes)
        for i in allowed:
            pieces.join(*ends[i])
        return pieces.pieces == 1

    def rec(i: int, pieces: UnionFind) -> Iterator[tuple[int, ...]]:
        nonlocal count
        if len(chosen) == n_nodes - 1:
            count += 1
            if count > limit:
                raise LabelError(f"more than {limit} spanning trees; use `sample=N`")
            yield tuple(chosen)
            return
        if i == m or m - i < n_nodes - 1 - len(chosen):
            return
        if pieces.find(ends[i][0]) != pieces.find(ends[i][1]):
            joined = pieces.copy()
            joined.join(*ends[i])
            chosen.append(i)
            yield from rec(i + 1, joined)
            chosen.pop()
        if connected(chosen + list(range(i + 1, m))):
            yield from rec(i + 1, pieces)

    if n_nodes == 1:
        yield ()
        return
    if not connected(list(range(m))):
        return
    yield from rec(0, UnionFind(n_nodes))


def spanning_tree_rows(
    space: DesignSpace,
    sample: int | None = None,
    seed: int = 0,
    max_designs: int | None = None,
    stats: dict[str, int] | None = None,
) -> list[ResidueRow]:
    """One-component residue-class rows (``--mode residues`` form) seeded from dual spanning trees."""
    sc = space.scaffold
    ids, pairs = dual_edges(space)
    k = space.moduli
    lookup = space.residue_table.lookup
    if np.any(lookup[np.arange(len(k)), 0] < 0):
        raise LabelError(
            f"mode='spanning-trees' needs even labels (t = 0 mod K); {space.walk_labels.tolist()} has none",
            parameter="mode",
        )
    if len(ids) and np.any(lookup[ids, 1] < 0):
        raise LabelError(
            f"mode='spanning-trees' needs odd labels; {space.walk_labels.tolist()} has none", parameter="mode"
        )
    if len(ids) == 0 and sc.n_faces > 1:
        raise LabelError(f"{sc.name}: the dual graph has no edges of degree 2; no spanning trees")
    trees: Iterator[tuple[int, ...]]
    if sample is not None:
        rng = np.random.default_rng(seed)
        trees = (uniform_spanning_tree(sc.n_faces, pairs, rng) for _ in range(sample))
    else:
        trees = all_spanning_trees(sc.n_faces, pairs)
    seen: set[bytes] = set()
    rows: list[ResidueRow] = []
    stats = stats if stats is not None else {}
    stats.update(trees=0, rejected=0, classes=0)
    for tree in trees:
        stats["trees"] += 1
        residues = np.zeros(len(k), np.int64)
        residues[ids[list(tree)]] = 1
        indices, stab = space.canonical_class(residues)
        key = indices.tobytes()
        if key in seen:
            continue
        seen.add(key)
        row = residue_row(space, indices, stab)
        if row["components"] != 1:
            stats["rejected"] += 1
            continue
        rows.append(row)
        stats["classes"] += 1
        if max_designs is not None and len(rows) >= max_designs:
            break
    return rows


def uniform_spanning_tree(n_nodes: int, pairs: np.ndarray, rng: np.random.Generator) -> tuple[int, ...]:
    """Draw one uniformly random spanning tree of a multigraph as sorted edge positions.

    Wilson's algorithm: loop-erased random walks into the growing tree.
    """
    incident: list[list[tuple[int, int]]] = [[] for _ in range(n_nodes)]
    for i, (a, b) in enumerate(pairs.tolist()):
        incident[a].append((i, b))
        incident[b].append((i, a))
    if any(not inc for inc in incident) and n_nodes > 1:
        raise LabelError("the dual graph is disconnected; no spanning tree")
    in_tree = [False] * n_nodes
    in_tree[int(rng.integers(n_nodes))] = True
    nxt: dict[int, tuple[int, int]] = {}
    edges = []
    for start in range(n_nodes):
        x = start
        while not in_tree[x]:  # walk, overwriting exits: the last exit erases loops
            nxt[x] = incident[x][int(rng.integers(len(incident[x])))]
            x = nxt[x][1]
        x = start
        while not in_tree[x]:
            in_tree[x] = True
            edges.append(nxt[x][0])
            x = nxt[x][1]
    return tuple(sorted(edges))
