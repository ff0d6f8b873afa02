"""Symmetry group of a scaffold: rigid motions that map it onto itself.

How the group is found
----------------------
1. **Finite scaffolds** (:mod:`~lkspace.symmetry.pointset`, :mod:`~lkspace.symmetry.finite`):
   the vertices in standard position (centroid at 0, RMS radius 1) are welded into
   sites; two anchor sites fix each candidate motion, which is matched on all sites with
   a KD-tree and lifted to a vertex permutation ``sigma`` that must carry edges to edges
   and faces to faces (an automorphism of the coloured incidence graph).  Only generators
   are matched; the group is their closure under composition.  Time and memory are
   linear in the mesh (times the group order for the tables).  When the vertices are
   coplanar both motions of each in-plane map are kept (a flat polygon has the in-plane
   rotations and the half-turns that flip it over).
2. **Periodic scaffolds** (:mod:`~lkspace.symmetry.periodic_search`): every motion
   ``x -> Q x + tau`` carrying the infinite mesh and its lattice onto themselves, modulo
   the lattice.  ``Q`` runs over the lattice's whole point group
   (:mod:`~lkspace.symmetry.lattice_group`: ``B Q^T = N B``, ``N`` integer of any size,
   from the lattice vectors as long as an LLL-reduced basis); ``tau`` is fixed by one
   vertex's image, every vertex is matched by a KD-tree to an exact (vertex, offset) key,
   and every face (a cycle of corners) and edge must land on one.  The translation
   subgroup is closed from verified generators and one motion is verified per point
   operation; the tables are their compositions.
3. **Action on labels.**  Each motion permutes the edges, ``edge_perms[g, e]`` is the
   image of edge ``e``.  A proper motion (rotation, ``det Q = +1``) keeps twist labels: a
   right-handed twist stays right-handed and the rule reads the same from either end; an
   improper one (reflection) maps label ``t`` on ``e`` to ``-t`` on its image edge.

Limitations: an explicit radial order stored in a scaffold file is assumed to agree with
the geometry (the symmetry check is geometric).
"""

from __future__ import annotations

import weakref
from collections import OrderedDict
from dataclasses import dataclass
from functools import cached_property
from typing import Literal, TypeAlias, get_args

import numpy as np

from ..errors import LabelError, ScaffoldError, TooLargeError
from ..model.scaffold import Scaffold
from .finite import MAX_GROUP_ENTRIES, finite_lifts
from .periodic_search import periodic_symmetry
from .tolerance import resolve_tolerance

SymmetryMode: TypeAlias = Literal["rotations", "isometries", "none"]
"""Which symmetries make two designs the same: the proper rotations, every isometry, or none."""
MODES: tuple[SymmetryMode, ...] = get_args(SymmetryMode)


@dataclass(frozen=True, eq=False)
class SymmetryGroup:
    """The rigid motions mapping a scaffold onto itself (identity first).

    Attributes
    ----------
    matrices : (n_elements, 3, 3) float64
        Orthogonal part ``Q`` of each motion.
    translations : (n_elements, 3) float64
        Translation part ``tau`` (modulo the lattice for periodic scaffolds).
    vertex_perms : (n_elements, n_vertices) int64
        Image vertex of each vertex.
    edge_perms : (n_elements, n_edges) int64
        Image edge (class) of each edge.
    proper : (n_elements,) bool
        ``det Q = +1`` (a rotation) or not (a reflection / improper motion).
    """

    matrices: np.ndarray
    translations: np.ndarray
    vertex_perms: np.ndarray
    edge_perms: np.ndarray
    proper: np.ndarray

    @property
    def order(self) -> int:
        """Number of isometries (proper and improper)."""
        return int(len(self.proper))

    @property
    def n_rotations(self) -> int:
        """Number of proper motions (the rotation subgroup's order)."""
        return int(self.proper.sum())

    @cached_property
    def edge_signs(self) -> np.ndarray:
        """(n_elements,) int64: +1 for rotations, -1 for reflections (label ``t -> sign * t``)."""
        return np.where(self.proper, 1, -1).astype(np.int64)

    def mode_order(self, mode: SymmetryMode) -> int:
        """Order of the group used by ``mode`` (``rotations``, ``isometries``, ``none``)."""
        check_mode(mode)
        return {"rotations": self.n_rotations, "isometries": self.order, "none": 1}[mode]

    def action(self, mode: SymmetryMode) -> tuple[np.ndarray, np.ndarray]:
        """Distinct signed edge permutations of ``mode``'s group, identity first.

        Returns
        -------
        perms : (n_actions, n_edges) int64
            ``perms[g, e]``: the edge that edge ``e`` goes to.
        signs : (n_actions,) int64
            Label ``t`` on ``e`` becomes ``signs[g] * t`` on ``perms[g, e]``.

        Motions acting identically on labels (e.g. a half-turn that reverses an edge
        class of a periodic tiling onto itself) appear once, so ``n_actions`` divides
        :meth:`mode_order`.
        """
        check_mode(mode)
        n_edges = self.edge_perms.shape[1]
        if mode == "none":
            return np.arange(n_edges, dtype=np.int64)[None, :], np.ones(1, np.int64)
        keep = self.proper if mode == "rotations" else np.ones(self.order, bool)
        perms = self.edge_perms[keep]
        signs = self.edge_signs[keep] if mode == "isometries" else np.ones(int(keep.sum()), np.int64)
        table = np.column_stack([perms, signs])
        _, first = np.unique(table, axis=0, return_index=True)
        first = np.sort(first)  # identity (element 0) stays first
        return np.ascontiguousarray(perms[first]), np.ascontiguousarray(signs[first])


def check_mode(mode: str) -> SymmetryMode:
    """Return ``mode`` if it is one of :data:`MODES`; raise :class:`~lkspace.errors.LabelError` otherwise."""
    if mode not in MODES:
        raise LabelError(f"unknown symmetry mode {mode!r}; choose one of {', '.join(MODES)}", usage=True)
    return mode


def check_label_set(labels: np.ndarray, mode: SymmetryMode) -> None:
    """Isometries need a label set closed under negation (a mirror maps t to -t)."""
    if mode == "isometries":
        missing = sorted(set((-np.asarray(labels)).tolist()) - set(np.asarray(labels).tolist()))
        if missing:
            raise LabelError(
                f"symmetry='isometries' maps label t to -t under reflections, but the label set "
                f"{np.asarray(labels).tolist()} lacks {missing}; use a set closed under negation or `symmetry='rotations'`",
                usage=True,
                parameter="symmetry",
            )


_GROUPS: weakref.WeakKeyDictionary[Scaffold, dict[float, SymmetryGroup]] = weakref.WeakKeyDictionary()
"""Each live scaffold's symmetry groups by tolerance (a scaffold is compared by identity; its entry goes with it)."""

KEPT_BY_CONTENT = 8
"""Groups kept by the content of their scaffold (:meth:`Scaffold.content_hash`), the latest used last."""

_BY_CONTENT: OrderedDict[tuple[str, float], SymmetryGroup] = OrderedDict()
"""The last groups found, by ``(content hash, tolerance)``: another object of the same mesh (loaded again,
relabelled) shares its group instead of searching again."""


def symmetry_group(scaffold: Scaffold, tolerance: float | None = None) -> SymmetryGroup:
    """Return the rigid symmetry group of ``scaffold`` (found once per scaffold and tolerance).

    ``tolerance`` (mesh units): how far a motion may move a vertex from the vertex it is
    matched with; ``None`` is the default rule of :mod:`lkspace.symmetry.tolerance`
    (1/100 of the shortest edge).  The group's permutations are exact either way.

    Examples
    --------
    >>> from lkspace import load
    >>> g = symmetry_group(load("cube"))
    >>> g.order, g.n_rotations
    (48, 24)
    >>> symmetry_group(load("dihedron:5")).order
    20
    """
    tol = resolve_tolerance(scaffold, tolerance)
    found = _GROUPS.setdefault(scaffold, {})
    if tol not in found:
        key = (scaffold.content_hash(), tol)
        group = _BY_CONTENT.pop(key, None)
        _BY_CONTENT[key] = found[tol] = compute_group(scaffold, tol) if group is None else group
        while len(_BY_CONTENT) > KEPT_BY_CONTENT:
            _BY_CONTENT.popitem(last=False)
    return found[tol]


def symmetry_orders(scaffold: Scaffold, tolerance: float | None = None) -> tuple[int, int]:
    """``(isometries, rotations)``: the orders of the symmetry group, without its tables for periodic scaffolds.

    ``tolerance`` as for :func:`symmetry_group`.

    Examples
    --------
    >>> from lkspace import load
    >>> symmetry_orders(load("tiling:hexagonal@2x1"))
    (16, 8)
    """
    tol = resolve_tolerance(scaffold, tolerance)
    if scaffold.periodic and tol not in _GROUPS.get(scaffold, {}):
        found = periodic_symmetry(scaffold, tol)
        return found.order, found.n_rotations
    group = symmetry_group(scaffold, tol)
    return group.order, group.n_rotations


def compute_group(scaffold: Scaffold, tolerance: float) -> SymmetryGroup:
    """Finite: isometries lifted to automorphisms; periodic: candidates -> rigid motions.  The identity first."""
    if scaffold.periodic:
        sigmas, qs, taus, perms = periodic_tables(scaffold, tolerance)
    else:
        sigmas, qs, taus, perms = finite_tables(scaffold, tolerance)
    proper = np.linalg.det(qs) > 0
    if not len(qs) or not (np.allclose(qs[0], np.eye(3)) and np.array_equal(sigmas[0], np.arange(sigmas.shape[1]))):
        raise ScaffoldError(f"{scaffold.name}: symmetry search failed to find the identity")  # pragma: no cover
    for a in (sigmas, qs, taus, perms, proper):
        a.setflags(write=False)
    return SymmetryGroup(matrices=qs, translations=taus, vertex_perms=sigmas, edge_perms=perms, proper=proper)


Tables4 = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]


def finite_tables(scaffold: Scaffold, tolerance: float) -> Tables4:
    """``(sigmas, Qs, taus, edge_perms)`` of a finite scaffold (every motion fixes the vertex centroid)."""
    v = scaffold.vertices
    scale = max(float(np.abs(v).max()), 1e-300)
    centroid = (v / scale).mean(axis=0)
    sigmas, qs, perms = finite_lifts(scaffold, tolerance)
    with np.errstate(over="ignore", invalid="ignore"):  # translations of a mesh near 1e308 may overflow
        taus = scale * (centroid[None, :] - qs @ centroid)
    return sigmas, qs, taus, perms


def periodic_tables(scaffold: Scaffold, tolerance: float) -> Tables4:
    """``(sigmas, Qs, taus, edge_perms)`` of a periodic scaffold, the identity first.

    Raises :class:`~lkspace.errors.TooLargeError` when the tables would pass
    :data:`~lkspace.symmetry.finite.MAX_GROUP_ENTRIES` entries.
    """
    found = periodic_symmetry(scaffold, tolerance)
    size = scaffold.n_vertices + scaffold.n_edges
    if found.order * size > MAX_GROUP_ENTRIES:
        raise TooLargeError(
            f"{scaffold.name}: its symmetry group has {found.order} motions on {size} vertices and edges: "
            f"its tables would pass {MAX_GROUP_ENTRIES} entries; use `symmetry='none'`",
        )
    sigmas = np.empty((found.order, scaffold.n_vertices), np.int64)
    qs = np.empty((found.order, 3, 3), np.float64)
    taus = np.empty((found.order, 3), np.float64)
    perms = np.empty((found.order, scaffold.n_edges), np.int64)
    for i, motion in enumerate(found.elements()):
        sigmas[i], qs[i], taus[i], perms[i] = motion.sigma, motion.q, motion.tau, motion.edge_perm
    return sigmas, qs, taus, perms
