"""The design space: a scaffold, a label set and a symmetry mode, and its residue classes.

:class:`DesignSpace` holds what the walk of :mod:`lkspace.design.walk` needs: the group's
signed edge permutations, the residues ``t mod K`` each edge can take with the label
options of each, the residue classes under the group (representatives, stabilizers),
one trace per class (:class:`ClassInfo`), and exact Burnside counts per class.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Literal, TypeAlias, get_args

import numpy as np
from numpy.typing import ArrayLike

from ..errors import LabelError, TooLargeError
from ..model.counts import count_text
from ..model.scaffold import Scaffold
from ..model.specs import LabelSetSpec, parse_label_set
from ..model.validation import validate_labels
from ..strands.walk import walk
from ..symmetry.group import SymmetryGroup, SymmetryMode, check_label_set, check_mode, symmetry_group
from .orbit_kernels import MinimaOut, ResidueCodes, SignedPerms, orbit_minima, stabilizer_ids

MAX_CLASSES = 1 << 21
WALK_ADVICE = "; use `mode='spanning-trees'` or a smaller label set"
"""The end of :func:`class_orbits`' refusal: what a catalog can do instead (a caller without modes says its own)."""
MAX_COUNT_DIGITS = 4000
"""Most decimal digits of ``|SET| ** n_edges``: every count of a space (designs, assignments,
orbit sizes) is written exactly, and Python writes integers of at most 4,300 digits."""
WalkMode: TypeAlias = Literal["designs", "residues", "spanning-trees"]
"""Row kinds of a walk: one per design, per residue-class orbit, per dual spanning-tree class."""
WALK_MODES: tuple[WalkMode, ...] = get_args(WalkMode)


@dataclass(frozen=True, eq=False)
class ClassInfo:
    """Label-independent facts of one residue class (from one trace)."""

    components: int
    strand_lengths: np.ndarray  # (n_strands,) int64, descending
    periods: np.ndarray  # (n_strands, dim) int64, same order
    edge_ptr: np.ndarray  # (n_edges + 1,) strands through each edge (CSR)
    edge_strands: np.ndarray


@dataclass(frozen=True, eq=False)
class ResidueTable:
    """The residues ``t mod K`` the walk labels reach on each edge, and the labels of each.

    Attributes
    ----------
    n_res : (n_edges,) int64
        Number of residues the walk labels reach on each edge.
    values : (n_edges, max_r) int64
        The residues, sorted (zero-padded).
    n_opts : (n_edges, max_r) int64
        Number of walk labels in each residue class.
    opts : (n_edges, max_r, max_o) int64
        Those labels (zero-padded).
    lookup : (n_edges, max_K) int64
        Residue value -> its index in ``values``, -1 where not reached.
    """

    n_res: np.ndarray
    values: np.ndarray
    n_opts: np.ndarray
    opts: np.ndarray
    lookup: np.ndarray


@dataclass(frozen=True, eq=False)
class DesignSpace:
    """A scaffold, a label set and a symmetry mode: the space ``lkspace enumerate`` walks.

    Parameters
    ----------
    scaffold : Scaffold
    label_set : (n_labels,) int64
        The label set ``SET`` (sorted, unique).
    mode : SymmetryMode
        ``"rotations"``, ``"isometries"`` or ``"none"``.
    no_zero : bool
        Leave label 0 out of the walk (a filter: ``assignments`` still counts ``|SET|^edges``).
    tolerance : float or None
        Symmetry search tolerance in mesh units (:func:`~lkspace.symmetry.group.symmetry_group`);
        ``None``: the default rule.
    """

    scaffold: Scaffold
    label_set: np.ndarray
    mode: SymmetryMode = "rotations"
    no_zero: bool = False
    tolerance: float | None = None

    def __post_init__(self) -> None:
        labels = np.unique(np.asarray(self.label_set, dtype=np.int64))
        if labels.size == 0:
            raise LabelError("label set is empty")
        if np.abs(labels).max() > 127:
            raise LabelError(
                f"labels must lie in -127..127 for a catalog, got {labels.min()}..{labels.max()}", usage=True
            )
        check_count_digits(self.scaffold, len(labels))
        object.__setattr__(self, "label_set", labels)
        check_mode(self.mode)
        check_label_set(labels, self.mode)
        _ = self.group  # the symmetry search runs here: a scaffold past its bounds fails at once
        if len(self.walk_labels) == 0:
            raise LabelError("no_zero leaves no labels to walk", parameter="no_zero")

    @cached_property
    def group(self) -> SymmetryGroup | None:
        """The scaffold's symmetry group (kept with the space, also in worker processes); ``None`` for mode ``"none"``."""
        return None if self.mode == "none" else symmetry_group(self.scaffold, self.tolerance)

    @property
    def group_order(self) -> int:
        """Order of the group of :attr:`mode` (1 for ``"none"``)."""
        return self.group.mode_order(self.mode) if self.group is not None else 1

    @cached_property
    def walk_labels(self) -> np.ndarray:
        """(n_walk,) int64: the labels the walk uses (the label set, without 0 under ``no_zero``)."""
        return self.label_set[self.label_set != 0] if self.no_zero else self.label_set

    @cached_property
    def action(self) -> tuple[np.ndarray, np.ndarray]:
        """``(perms (n_g, n_edges), signs (n_g,))``: distinct signed edge permutations, identity first."""
        if self.group is None:
            n = self.scaffold.n_edges
            return np.arange(n, dtype=np.int64)[None, :], np.ones(1, np.int64)
        return self.group.action(self.mode)

    @property
    def n_actions(self) -> int:
        """Number of distinct signed edge permutations in :attr:`action` (it divides ``group_order``)."""
        return int(len(self.action[1]))

    @property
    def assignments(self) -> int:
        """``|SET| ** n_edges`` (exact Python int)."""
        return len(self.label_set) ** self.scaffold.n_edges

    # ---- residues -------------------------------------------------------------
    @cached_property
    def moduli(self) -> np.ndarray:
        """(n_edges,) int64: ``K`` per edge (residues are ``t mod K``)."""
        return np.asarray(self.scaffold.edge_degrees, np.int64)

    @cached_property
    def residue_table(self) -> ResidueTable:
        """Per edge: residues reached (sorted), label options per residue, lookup value -> index."""
        k = self.moduli
        n_e = len(k)
        per_k = {}
        for kk in np.unique(k).tolist():
            res = np.unique(self.walk_labels % kk)
            per_k[kk] = (res, [self.walk_labels[self.walk_labels % kk == r] for r in res])
        max_r = max(len(v[0]) for v in per_k.values())
        max_o = max(len(o) for v in per_k.values() for o in v[1])
        n_res = np.array([len(per_k[kk][0]) for kk in k.tolist()], np.int64)
        values = np.zeros((n_e, max_r), np.int64)
        n_opts = np.zeros((n_e, max_r), np.int64)
        opts = np.zeros((n_e, max_r, max_o), np.int64)
        lookup = np.full((n_e, int(k.max())), -1, np.int64)
        for e, kk in enumerate(k.tolist()):
            res, options = per_k[kk]
            values[e, : len(res)] = res
            lookup[e, res] = np.arange(len(res))
            for i, o in enumerate(options):
                n_opts[e, i] = len(o)
                opts[e, i, : len(o)] = o
        return ResidueTable(n_res, values, n_opts, opts, lookup)

    @property
    def n_classes(self) -> int:
        """Number of residue classes: the product over edges of the residues reached (exact)."""
        return math.prod(self.residue_table.n_res.tolist())

    @cached_property
    def classes(self) -> ClassOrbits:
        """Residue classes, their representatives and stabilizers."""
        return class_orbits(self)

    def class_info(self, residues: np.ndarray) -> ClassInfo:
        """Trace residue vector ``residues (n_edges,)`` once: components, strand lengths, periods."""
        sc = self.scaffold
        _, (_, starts, _, periods, port_strand, _) = walk(sc, residues)
        lengths = np.diff(starts)
        order = np.argsort(-lengths, kind="stable")
        edge_of_port = np.repeat(sc.side_edge, 2)
        pairs = np.unique(np.column_stack([edge_of_port, port_strand]), axis=0)
        ptr = np.searchsorted(pairs[:, 0], np.arange(sc.n_edges + 1))
        return ClassInfo(len(lengths), lengths[order], periods[order], ptr, pairs[:, 1].copy())

    def class_design_count(self, c: int) -> int:
        """Designs in representative class ``c`` (Burnside over its stabilizer), exact."""
        co = self.classes
        return self.design_count(co.indices[c], co.stabilizers[c])

    def design_count(self, indices: np.ndarray, stabilizer: Sequence[int] | np.ndarray) -> int:
        """Designs in the class with residue ``indices (n_edges,)`` fixed by the actions ``stabilizer``."""
        table = self.residue_table
        n_opts, opts = table.n_opts, table.opts
        e_range = np.arange(len(indices))
        counts = n_opts[e_range, indices]
        has_zero = np.any((opts[e_range, indices] == 0) & (np.arange(opts.shape[2]) < counts[:, None]), axis=1)
        total = 0
        for h in stabilizer:
            heads, even = self.cycles[h]
            total += math.prod(np.where(even, counts[heads], has_zero[heads]).tolist())
        return total // len(stabilizer)

    def canonical_class(self, residues: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Smallest image of residue vector ``residues`` under the group and its stabilizer.

        Returns ``(indices (n_edges,) int64, stabilizer (n_h,) int64)`` without listing classes.
        """
        values, lookup = self.residue_table.values, self.residue_table.lookup
        k = self.moduli
        perms, signs = self.action
        idx = lookup[np.arange(len(k)), np.asarray(residues) % k]
        if np.any(idx < 0):
            raise LabelError("residue vector not reachable with this label set")
        val = values[np.arange(len(k)), idx]
        images = np.empty((len(signs), len(k)), np.int64)
        images[np.arange(len(signs))[:, None], perms] = lookup[perms, (signs[:, None] * val[None, :]) % k[perms]]
        best = images[np.lexsort(images.T[::-1])[0]]
        # stabilizer of the best image: conjugate by any element mapping idx to it
        return best, self._stabilizer(best)

    def _stabilizer(self, indices: np.ndarray) -> np.ndarray:
        values, lookup = self.residue_table.values, self.residue_table.lookup
        k = self.moduli
        perms, signs = self.action
        val = values[np.arange(len(k)), indices]
        images = np.empty((len(signs), len(k)), np.int64)
        images[np.arange(len(signs))[:, None], perms] = lookup[perms, (signs[:, None] * val[None, :]) % k[perms]]
        return np.flatnonzero(np.all(images == indices[None, :], axis=1))

    def representative_labels(self, indices: np.ndarray) -> np.ndarray:
        """(n_edges,) int8: per edge the option of the class with the smallest ``|t|`` (ties: positive)."""
        n_opts, opts = self.residue_table.n_opts, self.residue_table.opts
        out = np.empty(len(indices), np.int8)
        for e, i in enumerate(indices.tolist()):
            o = opts[e, i, : n_opts[e, i]]
            out[e] = o[np.lexsort((-o, np.abs(o)))[0]]
        return out

    def class_code(self, indices: np.ndarray) -> int:
        """Mixed-radix code of a class (edge 0 most significant); exact Python int."""
        n_res = self.residue_table.n_res.tolist()
        code = 0
        for i, r in zip(indices.tolist(), n_res, strict=True):
            code = code * r + i
        return code

    def size_of(self, indices: np.ndarray) -> int:
        """Label assignments in the class with residue ``indices`` (exact)."""
        n_opts = self.residue_table.n_opts
        return math.prod(n_opts[np.arange(len(indices)), indices].tolist())

    @cached_property
    def cycles(self) -> list[tuple[np.ndarray, np.ndarray]]:
        """Per group action: first edge of each cycle and whether its signs multiply to +1."""
        perms, signs = self.action
        out = []
        for perm, s in zip(perms, signs, strict=True):
            seen = np.zeros(len(perm), bool)
            heads, even = [], []
            for e in range(len(perm)):
                if seen[e]:
                    continue
                n, x = 0, e
                while not seen[x]:
                    seen[x] = True
                    x = perm[x]
                    n += 1
                heads.append(e)
                even.append(s == 1 or n % 2 == 0)
            out.append((np.array(heads, np.int64), np.array(even, bool)))
        return out


@dataclass(frozen=True, eq=False)
class ClassOrbits:
    """Residue classes under the group.

    Attributes
    ----------
    indices : (n_reps, n_edges) int64
        Residue index per edge (into the edge's sorted residues) of each representative.
    residues : (n_reps, n_edges) int64
        Residue values ``t mod K``.
    codes : (n_reps,) int64
        Mixed-radix code of the class (edge 0 most significant): the ``residue_class`` key.
    orbit_sizes : (n_reps,) int64
        Classes in each representative's orbit.
    stab_ptr, stab_ids : (n_reps + 1,), (n_fix,) int64
        The group actions fixing each representative (identity first), as CSR:
        ``stab_ids[stab_ptr[c]:stab_ptr[c + 1]]``.
    """

    indices: np.ndarray
    residues: np.ndarray
    codes: np.ndarray
    orbit_sizes: np.ndarray
    stab_ptr: np.ndarray
    stab_ids: np.ndarray

    @cached_property
    def stabilizers(self) -> list[np.ndarray]:
        """Group actions fixing each representative, identity first (one array per class)."""
        return np.split(self.stab_ids, self.stab_ptr[1:-1])


def class_orbits(space: DesignSpace) -> ClassOrbits:
    """Find the representatives (lexicographically smallest residue vector) of the class orbits."""
    table = space.residue_table
    n_res, values, lookup = table.n_res, table.values, table.lookup
    n_cls = space.n_classes
    if n_cls > MAX_CLASSES:
        raise TooLargeError(
            f"{space.scaffold.name}: {count_text(n_cls)} residue classes (label set {space.label_set.tolist()}) are too many to walk "
            f"(limit {MAX_CLASSES}){WALK_ADVICE}",
        )
    dims = tuple(n_res.tolist())
    k = space.moduli
    perms, signs = space.action
    is_rep = np.empty(n_cls, np.bool_)
    n_fix = np.empty(n_cls, np.int64)
    residues, group = ResidueCodes(n_res, values, lookup, k), SignedPerms(perms, signs)
    orbit_minima(0, n_cls, residues, group, MinimaOut(is_rep, n_fix))
    reps = np.flatnonzero(is_rep)
    idx = np.stack(np.unravel_index(reps, dims), axis=1).astype(np.int64)
    e = np.arange(len(dims))
    val = values[e, idx]
    ptr = np.zeros(len(reps) + 1, np.int64)
    np.cumsum(n_fix[reps], out=ptr[1:])
    orbit_sizes = len(perms) // n_fix[reps]
    stab_ids = np.empty(ptr[-1], np.int64)  # per class, ascending (identity first)
    stabilizer_ids(idx, residues, group, ptr, stab_ids)
    return ClassOrbits(idx, val, reps, orbit_sizes.astype(np.int64), ptr, stab_ids)


def canonical_form(space: DesignSpace, labels: ArrayLike) -> tuple[np.ndarray, int]:
    """Canonical representative of the design of ``labels`` and its orbit size.

    The representative is the catalog row's ``labels``: the orbit member smallest in
    (residue indices per edge, then labels per edge), lexicographically.

    Examples
    --------
    >>> from lkspace import load
    >>> sp = make_space(load("tetrahedron"), "-2,2")
    >>> canonical_form(sp, [2, 2, 2, 2, 2, -2])
    (array([-2,  2,  2,  2,  2,  2], dtype=int8), 6)
    """
    t = validate_labels(space.scaffold, labels)
    if not np.all(np.isin(t, space.walk_labels)):
        raise LabelError(f"labels {t.tolist()} are not all in the label set {space.walk_labels.tolist()}")
    perms, signs = space.action
    k = space.moduli
    lookup = space.residue_table.lookup
    images = np.empty((len(signs), len(t)), np.int64)
    images[np.arange(len(signs))[:, None], perms] = signs[:, None] * t[None, :]
    res = lookup[np.arange(len(t))[None, :], images % k[None, :]]
    keys = np.concatenate([res, images], axis=1)
    order = np.lexsort(keys.T[::-1])
    best = keys[order[0]]
    stab = int(np.sum(np.all(keys == best[None, :], axis=1)))
    return images[order[0]].astype(np.int8), space.n_actions // stab


def count_digits(n_labels: int, n_edges: int) -> float:
    """Decimal digits of ``n_labels ** n_edges`` (a float, without building the number)."""
    return n_edges * math.log10(max(n_labels, 1))


def check_count_digits(scaffold: Scaffold, n_labels: int) -> None:
    """Refuse a space whose ``|SET| ** n_edges`` has more than :data:`MAX_COUNT_DIGITS` digits (before any work).

    Raises :class:`~lkspace.errors.TooLargeError` (a usage error) naming the size.
    """
    digits = count_digits(n_labels, scaffold.n_edges)
    if digits > MAX_COUNT_DIGITS:
        raise TooLargeError(
            f"{scaffold.name}: {n_labels}^{scaffold.n_edges} label assignments (about 10^{digits:,.0f}) are past "
            f"10^{MAX_COUNT_DIGITS} (MAX_COUNT_DIGITS), too many to count or list; use a smaller scaffold or label set"
        )


def make_space(
    scaffold: Scaffold,
    label_set: LabelSetSpec = "-2..2",
    symmetry: SymmetryMode = "rotations",
    no_zero: bool = False,
    tolerance: float | None = None,
) -> DesignSpace:
    """Build a :class:`DesignSpace` from user-level arguments (label SET or array, tolerance).

    ``symmetry`` is checked here (:func:`~lkspace.symmetry.group.check_mode`).
    """
    sc = scaffold
    lab = parse_label_set(label_set) if isinstance(label_set, str) else np.asarray(label_set, np.int64)
    return DesignSpace(sc, lab, check_mode(symmetry), no_zero, tolerance)
