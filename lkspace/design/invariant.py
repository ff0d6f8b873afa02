"""Symmetric designs: the label assignments fixed by a subgroup ``H`` of the symmetries.

Fixed assignments
-----------------
A group element ``h`` maps label ``t`` on edge ``e`` to ``s(h) t`` on edge ``h(e)``, with
``s(h) = +1`` for a rotation and ``-1`` for a mirror (:mod:`lkspace.symmetry.group`).
An assignment is **fixed** by ``H`` when ``t[h(e)] = s(h) t[e]`` for every ``h`` in ``H``
and every edge ``e``.  On an edge orbit ``O = H e0`` a fixed assignment is therefore
given by ``u = t[e0]``: ``t[h e0] = s(h) u``.  This is consistent exactly when
``s(h1) u = s(h2) u`` whenever ``h1 e0 = h2 e0``, i.e. when ``u = -u`` or no element of
the stabilizer ``H_e0`` is a mirror.  So

* an orbit whose edge stabilizer contains a mirror (a mirror mapping an edge of ``O`` to
  itself) forces ``t = 0`` on all of ``O``;
* any other orbit carries one free label ``u``, with ``t[e] = rel[e] u`` for the sign
  ``rel[e] = s(h)`` of any ``h`` with ``h e0 = e``; ``u`` ranges over the labels ``x``
  with ``rel[e] x`` in the label set for every ``e`` of ``O``.

The fixed assignments are the product of these per-orbit choices, :attr:`n_fixed` of them
(an exponentially smaller space: one label per orbit instead of per edge).  The same
rule over the connected pieces of the generators' edge graph (union-find with signs,
:func:`~lkspace.symmetry.edge_orbits.signed_components`) gives the fixed points of any generated group.

Up to what
----------
An element ``g`` of the ``--symmetry`` group ``G`` maps an ``H``-fixed assignment to a
``gHg^-1``-fixed one, so the elements that keep ``Fix(H)`` for every label set are the
**normalizer** ``N = N_G(H) = {g in G : gHg^-1 = H}``.  Designs are the orbits of ``N`` on
``Fix(H)``: a row stands for ``orbit_size = |N| / |Stab_N(t)|`` fixed assignments (``|N|``
counted as distinct signed edge permutations), and the rows' ``orbit_size`` add up to
:attr:`n_fixed`.  ``H`` acts trivially on ``Fix(H)``, so only ``N / H`` moves designs.  Two
rows may still be related by an element of ``G`` outside ``N`` (when the design is fixed by
more than ``H``); ``--symmetry none`` lists every fixed assignment.  The row holds the
orbit member smallest in (``t mod K`` per edge, then ``t`` per edge), the same rule as
:mod:`lkspace.design.walk`; with ``H`` trivial the rows are those of the plain walk.

Counting without listing is Burnside over ``N``: ``|Fix(H) / N| = (1/|N|) sum_g |Fix(<H, g>)|``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..model.scaffold import Scaffold
from ..symmetry.edge_orbits import SignedOrbits, orbit_options, signed_components
from ..symmetry.group import SymmetryGroup, SymmetryMode, check_label_set, check_mode, symmetry_group
from ..symmetry.subgroups import GroupTable, parse_subgroup
from .space import DesignSpace


@dataclass(frozen=True, eq=False)
class InvariantSpace:
    """The designs fixed by a subgroup ``H``, up to the normalizer of ``H`` in the ``mode`` group.

    Parameters
    ----------
    scaffold : Scaffold
    label_set : (n_labels,) int64
    mode : SymmetryMode
        ``"rotations"``, ``"isometries"`` or ``"none"`` (whose group's
        normalizer of ``H`` identifies designs).
    subgroup : str
        The subgroup's name (:func:`~lkspace.symmetry.subgroups.parse_subgroup`).
    no_zero : bool
        Leave label 0 out.
    tolerance : float, optional
        Symmetry search tolerance in mesh units (default: 1/100 of the shortest edge).
    """

    scaffold: Scaffold
    label_set: np.ndarray
    mode: SymmetryMode
    subgroup: str
    no_zero: bool = False
    tolerance: float | None = None

    def __post_init__(self) -> None:
        check_mode(self.mode)
        check_label_set(self.base.label_set, self.mode)
        object.__setattr__(self, "label_set", self.base.label_set)  # sorted, unique: normalised as built

    @cached_property
    def base(self) -> DesignSpace:
        """The design space of all assignments (mode ``"none"``): the label set checked, residues, moduli."""
        return DesignSpace(self.scaffold, self.label_set, "none", self.no_zero)

    @cached_property
    def group(self) -> SymmetryGroup:
        """The scaffold's symmetry group."""
        return symmetry_group(self.scaffold, self.tolerance)

    @cached_property
    def elements(self) -> np.ndarray:
        """(n_h,) int64: indices of ``H``'s elements in :attr:`group` (identity first)."""
        return parse_subgroup(self.subgroup, self.scaffold, self.group)

    @cached_property
    def normalizer(self) -> np.ndarray:
        """(n_n,) int64: indices of the ``mode`` group's elements normalizing ``H``."""
        g = self.group
        within = {"rotations": np.flatnonzero(g.proper), "isometries": np.arange(g.order), "none": np.zeros(1, int)}
        return GroupTable(g).normalizer(self.elements, within[self.mode].astype(np.int64))

    @cached_property
    def action(self) -> tuple[np.ndarray, np.ndarray]:
        """``(perms (n_a, n_edges), signs (n_a,))``: the distinct signed edge permutations of ``N``, identity first."""
        g = self.group
        perms = g.edge_perms[self.normalizer]
        signs = g.edge_signs[self.normalizer]
        _, first = np.unique(np.column_stack([perms, signs]), axis=0, return_index=True)
        first = np.sort(first)
        return np.ascontiguousarray(perms[first]), np.ascontiguousarray(signs[first])

    @cached_property
    def orbits(self) -> SignedOrbits:
        """The signed edge orbits of ``H`` (:func:`signed_components`)."""
        g = self.group
        return signed_components(g.edge_perms[self.elements], g.edge_signs[self.elements], self.scaffold.n_edges)

    @cached_property
    def options(self) -> list[np.ndarray]:
        """Per ``H``-orbit, the labels of its representative edge."""
        return orbit_options(self.orbits, self.base.walk_labels)

    @property
    def n_orbits(self) -> int:
        """Number of edge orbits of ``H`` (free labels of a fixed assignment, at most)."""
        return len(self.options)

    @property
    def n_fixed(self) -> int:
        """Assignments fixed by ``H`` (exact): the product of the per-orbit options."""
        return math.prod(len(o) for o in self.options)

    @property
    def assignments(self) -> int:
        """``|SET| ** n_edges``, all assignments (exact)."""
        return self.base.assignments

    def count_designs(self) -> int:
        """Designs (orbits of ``N`` on the fixed assignments), exact, by Burnside over ``N``."""
        g = self.group
        hp, hs = g.edge_perms[self.elements], g.edge_signs[self.elements]
        perms, signs = self.action
        total = 0
        for p, s in zip(perms, signs, strict=True):
            fixed = signed_components(np.vstack([hp, p]), np.append(hs, s), self.scaffold.n_edges)
            total += math.prod(len(o) for o in orbit_options(fixed, self.base.walk_labels))
        return total // len(signs)

    def summary(self) -> dict[str, object]:
        """JSON facts of the subgroup: name, orders, orbits, fixed assignments (the catalog's ``invariant`` key).

        ``vertex_perms`` (the elements' vertex images) is ``None`` past 10,000 numbers.
        """
        small = len(self.elements) * self.scaffold.n_vertices <= 10_000
        return {
            "subgroup": self.subgroup,
            "order": int(len(self.elements)),
            "proper": bool(self.group.proper[self.elements].all()),
            "vertex_perms": self.group.vertex_perms[self.elements].tolist() if small else None,
            "normalizer_order": int(len(self.normalizer)),
            "acting_order": int(len(self.action[1])),
            "edge_orbits": self.n_orbits,
            "zero_orbits": int(sum(1 for o in self.options if o.tolist() == [0])),
            "fixed_assignments": self.n_fixed,
        }


def make_invariant_space(
    scaffold: Scaffold,
    label_set: np.ndarray,
    mode: SymmetryMode,
    subgroup: str,
    no_zero: bool = False,
    tolerance: float | None = None,
) -> InvariantSpace:
    """Build an :class:`InvariantSpace`, parsing the subgroup at once (a bad name fails here).

    Examples
    --------
    >>> from lkspace import load
    >>> sp = make_invariant_space(load("cube"), np.array([-1, 0, 1]), "rotations", "C3")
    >>> sp.n_orbits, sp.n_fixed, sp.count_designs()
    (4, 81, 54)
    """
    space = InvariantSpace(scaffold, np.asarray(label_set, np.int64), check_mode(mode), subgroup, no_zero, tolerance)
    _ = space.elements  # parse the name now: a bad one fails here, before any work
    return space
