"""The design-space walk: one row per design up to symmetry.

A **design** is an orbit of label assignments ``t in SET^edges`` under the symmetry group
``G`` of the mode (:mod:`lkspace.symmetry`; a reflection maps ``t`` on ``e`` to ``-t`` on its
image).  The strands depend only on the **residue class** ``t mod K`` per edge (``K`` the
edge's degree), so the walk goes class by class:

1. List the residue classes (product over edges of the residues the label set reaches)
   and let ``G`` act on them.  A class is a **representative class** when its residue
   vector, written as indices into each edge's sorted residues, is the lexicographically
   smallest of its ``G``-orbit; its **stabilizer** ``H`` is the set of group elements
   fixing it.
2. Trace each representative class once (the numba walk of :mod:`lkspace.tracing` on the
   residues, no ``Trace`` objects): components, strand lengths, periods.
3. Expand the class's label assignments (a product set, walked in lexicographic order by
   a numba kernel) and keep those that are the lexicographically smallest under ``H``.

**Canonical representative.**  Of all assignments in an orbit, the row holds the one
that is smallest in the order "residue vector ``t mod K`` in edge order first, then the
labels ``t`` in edge order", both lexicographic.  Because ``G`` maps residue classes to
residue classes, that minimum lies in the orbit's representative class and is the
``H``-smallest there, so testing it needs only ``H`` (usually trivial), never the whole
group.  ``orbit_size = |G| / |Stab(t)|`` with ``Stab(t) = {h in H : h t = t}``, counted
in the same kernel.  ``|G|`` is the number of distinct signed edge permutations
(:meth:`~lkspace.symmetry.SymmetryGroup.action`).

Null edge-sides stored with a scaffold are not part of a design space: the walk traces
every strand closed.

**Counting without listing** (Burnside): the designs in a representative class number
``(1/|H|) sum_{h in H} fix(h)``, where ``fix(h)`` is a product over the cycles of ``h``'s
edge permutation: the class's label count on the cycle's first edge when the signs around
the cycle multiply to ``+1``, else 1 if 0 is such a label (``t = -t``), else 0.
Components are constant on an orbit, so this gives exact counts by component number.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass

import numba
import numpy as np

from .errors import LabelError
from .space import ClassInfo, DesignSpace, canonical_form, make_space  # noqa: F401  (re-exported)

CHUNK = 1 << 20


@numba.njit(cache=True)
def _canonical_block(opts, n_opts, inv_perms, signs, start, stop, out_labels, out_stab):  # pragma: no cover
    """Walk assignments ``start..stop`` of one class (mixed radix, last edge fastest) and keep
    those lexicographically smallest under the stabilizer ``(inv_perms, signs)`` (identity
    excluded); returns the number kept, rows in ``out_labels``, stabilizer sizes in ``out_stab``."""
    n_e = len(n_opts)
    n_h = len(signs)
    digits = np.zeros(n_e, np.int64)
    cur = np.zeros(n_e, np.int64)
    rest = start
    for j in range(n_e - 1, -1, -1):
        digits[j] = rest % n_opts[j]
        rest //= n_opts[j]
        cur[j] = opts[j, digits[j]]
    m = 0
    for _ in range(start, stop):
        canon = True
        stab = 1
        for h in range(n_h):
            cmp = 0
            s = signs[h]
            for j in range(n_e):
                v = s * cur[inv_perms[h, j]]
                if v != cur[j]:
                    cmp = -1 if v < cur[j] else 1
                    break
            if cmp < 0:
                canon = False
                break
            if cmp == 0:
                stab += 1
        if canon:
            for j in range(n_e):
                out_labels[m, j] = cur[j]
            out_stab[m] = stab
            m += 1
        j = n_e - 1
        while j >= 0:
            digits[j] += 1
            if digits[j] < n_opts[j]:
                cur[j] = opts[j, digits[j]]
                break
            digits[j] = 0
            cur[j] = opts[j, 0]
            j -= 1
    return m


@numba.njit(cache=True)
def _holds_together(labels, edge_ptr, edge_strands, n_strands):  # pragma: no cover
    """(m,) bool: strands joined by winding at nonzero-label edges form one piece."""
    m, n_e = labels.shape
    out = np.ones(m, np.bool_)
    if n_strands <= 1:
        return out
    parent = np.empty(n_strands, np.int64)
    for i in range(m):
        for k in range(n_strands):
            parent[k] = k
        pieces = n_strands
        for e in range(n_e):
            if labels[i, e] == 0:
                continue
            a = edge_strands[edge_ptr[e]]
            while parent[a] != a:
                a = parent[a]
            for p in range(edge_ptr[e] + 1, edge_ptr[e + 1]):
                b = edge_strands[p]
                while parent[b] != b:
                    b = parent[b]
                if a != b:
                    parent[b] = a
                    pieces -= 1
        out[i] = pieces == 1
    return out


def holds_together_rows(space: DesignSpace, residues: np.ndarray, info: ClassInfo, labels: np.ndarray) -> np.ndarray:
    """(m,) bool: whether each design of one residue class holds together.

    Finite scaffolds: a numba union-find over the class's strands.  Periodic ones need
    the infinite lift (:mod:`lkspace.connectivity`), which depends only on the residues
    and on which labels are zero: traced once per distinct zero pattern.
    """
    if not space.scaffold.periodic:
        return _holds_together(labels, info.edge_ptr, info.edge_strands, info.components)
    from .tracing import trace

    nonzero = labels != 0
    if len(labels) == 1:
        patterns, inverse = nonzero, np.zeros(1, np.int64)
    else:
        patterns, inverse = np.unique(nonzero, axis=0, return_inverse=True)
    moduli = space.moduli
    verdicts = np.empty(len(patterns), bool)
    for i, pattern in enumerate(patterns):
        # same residues, same zero pattern: a residue of 0 on a nonzero edge becomes K
        stand_in = np.where(pattern & (residues == 0), moduli, residues)
        verdicts[i] = trace(space.scaffold, stand_in).holds_together
    return verdicts[inverse.reshape(-1)]


@dataclass
class Block:
    """Designs of one representative class (or a chunk of it)."""

    class_code: int
    residues: np.ndarray  # (n_edges,)
    info: ClassInfo
    labels: np.ndarray  # (m, n_edges) int8
    orbit_sizes: np.ndarray  # (m,) int64
    holds_together: np.ndarray  # (m,) bool


def class_weights(space: DesignSpace, components: int | None = None) -> np.ndarray:
    """(n_reps,) int64: designs per representative class (0 where ``components`` excludes it)."""
    co = space.classes
    out = np.zeros(len(co.codes), dtype=object)
    for c in range(len(co.codes)):
        if components is not None and space.class_info(co.residues[c]).components != components:
            continue
        out[c] = space.class_design_count(c)
    return out


def walk_blocks(space: DesignSpace, class_ids=None, components: int | None = None) -> Iterator[Block]:
    """Yield the designs of the representative classes ``class_ids`` (default all), in order."""
    co = space.classes
    perms, signs = space.action
    inv = np.argsort(perms, axis=1)
    n_res, values, n_opts_t, opts_t, _ = space.residue_table
    e = np.arange(space.scaffold.n_edges)
    ids = range(len(co.codes)) if class_ids is None else class_ids
    for c in ids:
        info = space.class_info(co.residues[c])
        if components is not None and info.components != components:
            continue
        n_opts = n_opts_t[e, co.indices[c]]
        opts = np.ascontiguousarray(opts_t[e, co.indices[c]])
        h = co.stabilizers[c][1:]
        size = math.prod(n_opts.tolist())
        for start in range(0, size, CHUNK):
            stop = min(size, start + CHUNK)
            out = np.empty((stop - start, len(e)), np.int8)
            stab = np.empty(stop - start, np.int64)
            m = _canonical_block(
                opts, n_opts, np.ascontiguousarray(inv[h]), np.ascontiguousarray(signs[h]), start, stop, out, stab
            )
            labels = out[:m]
            holds = holds_together_rows(space, co.residues[c], info, labels)
            yield Block(int(co.codes[c]), co.residues[c], info, labels, space.n_actions // stab[:m], holds)


def burnside_total(space: DesignSpace) -> int:
    """Designs counted by Burnside's lemma over the whole group (no residue classes)."""
    lab = space.walk_labels
    n_l, zero = len(lab), int(np.any(lab == 0))
    total = sum(math.prod([n_l if ev else zero for ev in even.tolist()]) for _, even in space.cycles)
    return total // space.n_actions


def count(space: DesignSpace, components: int | None = None) -> dict:
    """Exact totals without listing: designs, assignments covered, designs by components.

    Per representative residue class (Burnside over its stabilizer).  When there are too
    many residue classes to list and no component filter is asked for, the total comes
    from Burnside over the whole group and ``by_components`` is ``None``.
    """
    from .space import MAX_CLASSES

    if space.n_classes > MAX_CLASSES and components is None:
        return {
            "designs": burnside_total(space),
            "assignments": space.assignments,
            "assignments_covered": len(space.walk_labels) ** space.scaffold.n_edges,
            "by_components": None,
            "note": f"{space.n_classes} residue classes: too many to split the count by components",
        }
    co = space.classes
    by: dict[int, int] = {}
    covered = 0
    for c in range(len(co.codes)):
        comp = space.class_info(co.residues[c]).components
        if components is not None and comp != components:
            continue
        n = space.class_design_count(c)
        by[comp] = by.get(comp, 0) + n
        covered += space.class_size(c) * int(co.orbit_sizes[c])
    return {
        "designs": sum(by.values()),
        "assignments": space.assignments,
        "assignments_covered": covered,
        "by_components": {str(k): v for k, v in sorted(by.items())},
    }


def design_batches(
    space: DesignSpace,
    class_ids=None,
    components: int | None = None,
    max_designs: int | None = None,
    batch_rows: int | None = None,
):
    """Arrow record batches of designs (catalog schema), streamed class by class."""
    from .catalog import ROW_GROUP, blocks_to_batch

    batch_rows = batch_rows or ROW_GROUP
    n_edges, periodic = space.scaffold.n_edges, space.scaffold.periodic
    pending, n_pending, n_total = [], 0, 0
    for block in walk_blocks(space, class_ids, components):
        if max_designs is not None and n_total + len(block.labels) > max_designs:
            keep = max_designs - n_total
            block = Block(
                block.class_code,
                block.residues,
                block.info,
                block.labels[:keep],
                block.orbit_sizes[:keep],
                block.holds_together[:keep],
            )
        pending.append(block)
        n_pending += len(block.labels)
        n_total += len(block.labels)
        if n_pending >= batch_rows:
            yield blocks_to_batch(pending, n_edges, periodic)
            pending, n_pending = [], 0
        if max_designs is not None and n_total >= max_designs:
            break
    if pending:
        yield blocks_to_batch(pending, n_edges, periodic)


def residue_row(space: DesignSpace, indices: np.ndarray, stabilizer, info: ClassInfo | None = None) -> dict:
    """One ``--mode residues`` row for the class orbit of ``indices`` (a representative)."""
    from .catalog import label_stats

    e = np.arange(len(indices))
    residues = space.residue_table[1][e, indices]
    info = info or space.class_info(residues)
    labels = space.representative_labels(indices)
    holds = bool(holds_together_rows(space, residues, info, labels[None, :])[0])
    stats = label_stats(labels[None, :])
    n_classes = space.n_actions // len(stabilizer)
    big = 2**63 - 1  # counts past int64 are stored as -1 (possible only for huge spaces)
    assignments = space.size_of(indices) * n_classes
    designs = space.design_count(indices, stabilizer)
    row = {
        "residues": residues.astype(np.int8).tolist(),
        "labels": labels.tolist(),
        "components": info.components,
        "orbit_size": assignments if assignments <= big else -1,
        "designs": designs if designs <= big else -1,
        "classes": n_classes,
        "holds_together": holds,
        "n_zero": int(stats["n_zero"][0]),
        "n_odd": int(np.sum(residues % 2 != 0)),
        "residue_class": space.class_code(indices),
        "strand_lengths": info.strand_lengths.tolist(),
    }
    if space.scaffold.periodic:
        row["n_infinite"] = int(np.sum(np.any(info.periods != 0, axis=1)))
        row["strand_periods"] = info.periods.tolist()
    return row


def residue_batches(
    space: DesignSpace,
    class_ids=None,
    components: int | None = None,
    max_designs: int | None = None,
    batch_rows: int | None = None,
):
    """Record batches of ``--mode residues`` rows: one per residue-class orbit."""
    from .catalog import ROW_GROUP, residue_rows_to_batch

    batch_rows = batch_rows or ROW_GROUP
    co = space.classes
    rows: list[dict] = []
    n_total = 0
    for c in range(len(co.codes)) if class_ids is None else class_ids:
        info = space.class_info(co.residues[c])
        if components is not None and info.components != components:
            continue
        rows.append(residue_row(space, co.indices[c], co.stabilizers[c], info))
        n_total += 1
        if len(rows) >= batch_rows:
            yield residue_rows_to_batch(rows, space.scaffold.periodic)
            rows = []
        if max_designs is not None and n_total >= max_designs:
            break
    if rows:
        yield residue_rows_to_batch(rows, space.scaffold.periodic)


MODES = ("designs", "residues", "spanning-trees")


def enumerate_designs(
    scaffold,
    labels="-2..2",
    symmetry: str = "rotations",
    *,
    mode: str = "designs",
    components: int | None = None,
    no_zero: bool = False,
    max_designs: int | None = None,
    sample: int | None = None,
    seed: int = 0,
    batch_rows: int | None = None,
    as_arrow: bool = False,
):
    """Walk a design space and yield its catalog rows in batches (no files).

    Parameters
    ----------
    scaffold : Scaffold or str
        A scaffold or a built-in name / path.
    labels : str or sequence of int
        The label set ``SET`` (``"-2..2"``, ``"-2,2"``, or a list).
    symmetry : {"rotations", "isometries", "none"}
    mode : {"designs", "residues", "spanning-trees"}
        One row per design, per residue-class orbit, or per spanning-tree class.
    components, no_zero, max_designs
        Filters applied during the walk.
    sample, seed
        ``spanning-trees`` only: sample ``sample`` uniform spanning trees instead of all.
    batch_rows : int, optional
        Rows per batch (default 262,144).
    as_arrow : bool
        Yield ``pyarrow.RecordBatch`` instead of pandas DataFrames.

    Yields
    ------
    pandas.DataFrame or pyarrow.RecordBatch
        Columns as in :mod:`lkspace.catalog`.

    Examples
    --------
    >>> import lkspace
    >>> df = next(lkspace.enumerate("tetrahedron", "-2,2"))
    >>> len(df), int(df.orbit_size.sum())
    (12, 64)
    """
    space = make_space(scaffold, labels, symmetry, no_zero)
    if mode not in MODES:
        raise LabelError(f"unknown mode {mode!r}; choose one of {', '.join(MODES)}")
    if mode == "designs":
        batches = design_batches(space, None, components, max_designs, batch_rows)
    elif mode == "residues":
        batches = residue_batches(space, None, components, max_designs, batch_rows)
    else:
        from .spanning import spanning_tree_batches

        batches = spanning_tree_batches(space, sample=sample, seed=seed, max_designs=max_designs)
    for batch in batches:
        yield batch if as_arrow else batch.to_pandas()
