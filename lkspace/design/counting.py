"""Counting designs without listing them (Burnside's lemma).

**Counting without listing** (Burnside): the designs in a representative class number
``(1/|H|) sum_{h in H} fix(h)``, where ``fix(h)`` is a product over the cycles of ``h``'s
edge permutation: the class's label count on the cycle's first edge when the signs around
the cycle multiply to ``+1``, else 1 if 0 is such a label (``t = -t``), else 0.
Components are constant on an orbit, so this gives exact counts by component number.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..model.scaffold import Scaffold
from ..model.specs import LabelSetSpec
from ..runtime.schedulers import is_dask
from ..symmetry.group import SymmetryMode
from ..words import plural
from .batch import class_components, design_counts
from .census import census
from .space import MAX_CLASSES, DesignSpace, make_space

CENSUS_AUTO = 1 << 24
"""Residue vectors a count splits by components unasked (about ten seconds on one core)."""


@dataclass(frozen=True)
class DesignCount:
    """Exact counts of a design space (Python ints: they may exceed int64).

    Attributes
    ----------
    designs : int
        Designs (orbits of assignments) counted.
    assignments : int
        ``|label set| ** n_edges``.
    assignments_covered : int
        Assignments the counted designs stand for (fewer with filters).
    by_components : dict of int -> int or None
        Designs by number of components; ``None`` when there are too many residue classes
        to split the count.
    note : str
    """

    designs: int
    assignments: int
    assignments_covered: int
    by_components: dict[int, int] | None
    note: str = ""

    def __repr__(self) -> str:
        by = "" if self.by_components is None else f"; by components {self.by_components}"
        return f"DesignCount({plural(self.designs, 'design')} of {plural(self.assignments, 'assignment')}{by})"

    def to_dict(self) -> dict[str, Any]:
        """Return the JSON form (``by_components`` keyed by strings, as in the CLI)."""
        by = None if self.by_components is None else {str(k): v for k, v in self.by_components.items()}
        out: dict[str, Any] = {
            "designs": self.designs,
            "assignments": self.assignments,
            "assignments_covered": self.assignments_covered,
            "by_components": by,
        }
        if self.note:
            out["note"] = self.note
        return out


def class_weights(space: DesignSpace, components: int | None = None) -> np.ndarray:
    """(n_reps,) designs per representative class (0 where ``components`` excludes it).

    int64, or an object array of exact ints when counts may pass int64.
    """
    weights = design_counts(space, np.arange(len(space.classes.codes)))
    if components is not None:
        weights = np.where(class_components(space) == components, weights, 0)
    return weights


def burnside_total(space: DesignSpace) -> int:
    """Designs counted by Burnside's lemma over the whole group (no residue classes)."""
    lab = space.walk_labels
    n_l, zero = len(lab), int(np.any(lab == 0))
    total = sum(math.prod([n_l if ev else zero for ev in even.tolist()]) for _, even in space.cycles)
    return total // space.n_actions


def census_planned(space: DesignSpace, components: int | None, scheduler: str, jobs: int) -> bool:
    """Whether :func:`count_space` counts ``space`` by a census (see there)."""
    wanted = components is not None or jobs > 1 or is_dask(scheduler)
    return space.n_classes > MAX_CLASSES and (wanted or space.n_classes <= CENSUS_AUTO)


def count_space(
    space: DesignSpace, components: int | None = None, scheduler: str = "local", jobs: int = 1
) -> DesignCount:
    """Exact totals without listing: designs, assignments covered, designs by components.

    Per representative residue class (Burnside over its stabilizer), batched
    (:mod:`lkspace.design.batch`).  Past :data:`~lkspace.design.space.MAX_CLASSES` residue
    classes the count is a census (:mod:`lkspace.design.census`: Burnside by components
    over every residue vector, in shards on ``scheduler`` with ``jobs`` workers) when a
    component filter, ``jobs > 1`` or a Dask scheduler asks for it or when it is small
    (:data:`CENSUS_AUTO` vectors); otherwise the total comes from Burnside over the whole
    group and ``by_components`` is ``None``.
    """
    if space.n_classes > MAX_CLASSES:
        if not census_planned(space, components, scheduler, jobs):
            return DesignCount(
                burnside_total(space),
                space.assignments,
                len(space.walk_labels) ** space.scaffold.n_edges,
                None,
                f"{space.n_classes:,} residue classes: too many to split the count by components in one "
                "process; `jobs=N` or `scheduler='dask'` splits them (a census, in shards)",
            )
        found = census(space, scheduler, jobs)
        by = found.by_components
        if components is not None:
            by = {c: n for c, n in by.items() if c == components}
        covered = sum(n for c, n in found.assignments_by_components.items() if c in by)
        return DesignCount(
            sum(by.values()), space.assignments, covered, by, f"census in {plural(found.shards, 'part')}"
        )
    co = space.classes
    comps = class_components(space)
    keep = np.arange(len(comps)) if components is None else np.flatnonzero(comps == components)
    counts = design_counts(space, keep)
    n_opts = space.residue_table.n_opts
    e = np.arange(space.scaffold.n_edges)
    if counts.dtype != object:
        sizes = np.prod(n_opts[e[None, :], co.indices[keep]], axis=1) * co.orbit_sizes[keep]
        by = {int(c): int(counts[comps[keep] == c].sum(dtype=object)) for c in np.unique(comps[keep])}
        covered = int(sizes.sum(dtype=object))
    else:
        by = {}
        for c, n in zip(comps[keep].tolist(), counts.tolist(), strict=True):
            by[c] = by.get(c, 0) + n
        covered = sum(space.size_of(co.indices[c]) * int(co.orbit_sizes[c]) for c in keep.tolist())
    return DesignCount(sum(by.values()), space.assignments, covered, dict(sorted(by.items())))


def count_designs(
    scaffold: Scaffold,
    label_set: LabelSetSpec = "-2..2",
    symmetry: SymmetryMode = "rotations",
    *,
    components: int | None = None,
    no_zero: bool = False,
    tolerance: float | None = None,
) -> DesignCount:
    """Count the designs of a space exactly, without listing them.

    Parameters
    ----------
    scaffold : Scaffold
        ``lkspace.count_designs`` also takes a path or a built-in name (:func:`lkspace.load`).
    label_set : str or sequence of int
        ``"-2..2"``, ``"-2,-1,1,2"`` or integers.
    symmetry : {"rotations", "isometries", "none"}
    components : int, optional
        Count only designs with this many components.
    no_zero : bool
        Leave label 0 out.
    tolerance : float, optional
        Symmetry search tolerance in mesh units (default: 1/100 of the shortest edge).

    Examples
    --------
    >>> import lkspace
    >>> lkspace.count_designs("cube", "-1..1")
    DesignCount(22,815 designs of 531,441 assignments; by components {1: 8800, 2: 9837, 3: 3534, 4: 641, 5: 2, 6: 1})
    """
    return count_space(make_space(scaffold, label_set, symmetry, no_zero, tolerance), components)
