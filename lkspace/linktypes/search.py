"""Search a design space for a knot or link type or a linking matrix: ``lkspace solve --type/--linking-matrix``.

Designs with the right number of components come simplest first
(:class:`~lkspace.linktypes.candidates.OrderedWalk`), a batch at a time; each batch is
screened from its labels alone by cheap filters and, where they survive, identified by
invariant key (:func:`~lkspace.linktypes.screen.screen_batch`; names in ``processes``
worker processes).  Every match is **re-identified** on the geometric path (the design
realized and projected along another direction, :func:`~lkspace.linktypes.screen.screen`)
before it is reported.

On a closed scaffold (every edge between two faces) a table type is also built from its
diagram (:mod:`~lkspace.linktypes.tait_embedding`), screened the same way, before the walk.
Such a design with sum |t| equal to the crossing number on a scaffold of genus 0 is as simple
as any can be, so it answers at once; others are kept and reported after the walk's, or alone
when the space is too big to walk (``reason`` says they need not be the simplest).

Status: ``found`` (``count`` designs, or fewer when the space ran out), ``exhausted``
(the whole space walked and every design proved to be something else: the type is
absent), ``unknown`` (time ran out, or some designs could not be identified).
"""

from __future__ import annotations

import time
from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass, field, replace
from typing import Any, Literal, TypeAlias

import numpy as np

from ..design.space import WALK_ADVICE
from ..errors import SolveVerificationError, TooLargeError, UsageError
from ..model.scaffold import Scaffold
from ..runtime.progress import task
from ..strands.tracing import trace
from ..words import plural
from .answers import TargetSolution
from .candidates import Candidates, OrderedWalk
from .fields import Json, JsonObject
from .screen import Goal, Screening, screen, screen_batch

TargetStatus: TypeAlias = Literal["found", "exhausted", "unknown"]
"""A target search's answer: designs found, none in the space (proved), or not decided."""
CHECK_SEED_SHIFT = 1009
"""Seed offset of the projection used to re-identify an answer (independent of the search's)."""


@dataclass(frozen=True)
class TargetResult:
    """The answer: ``status``, ``solutions`` and counts (``stats``: designs per verdict and reason)."""

    status: TargetStatus
    solutions: tuple[TargetSolution, ...]
    goal: Goal
    wall_time: float
    complete: bool
    stats: JsonObject = field(default_factory=dict)
    reason: str = ""
    label_set: tuple[int, ...] = ()

    def __repr__(self) -> str:
        return f"TargetResult({self.status}, {plural(len(self.solutions), 'solution')} for {self.goal.label})"

    def to_dict(self) -> JsonObject:
        """Return the JSON form (``status``, ``solutions``, ``target``, ``stats`` ...)."""
        out: JsonObject = {
            "status": self.status,
            "solutions": [s.to_json() for s in self.solutions],
            "components": self.goal.components,
            "exhausted": self.status == "exhausted",
            "space_complete": self.complete,
            "wall_time": round(self.wall_time, 3),
            "stats": self.stats,
        }
        if self.label_set:
            out["label_set"] = list(self.label_set)
        if self.goal.target is not None:
            out["target"] = self.goal.target.to_dict()
        if self.goal.linking is not None:
            out["linking_matrix"] = np.asarray(self.goal.linking).tolist()
            out["signed"] = self.goal.signed
        if self.reason:
            out["reason"] = self.reason
        return out


def check_answer(scaffold: Scaffold, labels: np.ndarray, goal: Goal, seed: int, time_limit: float | None) -> Screening:
    """Re-trace and re-identify a match with another projection; raise if it is not the goal."""
    components = trace(scaffold, labels).components
    if components != goal.components:
        raise SolveVerificationError(
            f"internal error: {labels.tolist()} on {scaffold.name} traces to {components} components, "
            f"not {goal.components}; please report this bug"
        )
    again = screen(scaffold, labels, goal, seed + CHECK_SEED_SHIFT, time_limit)
    return again


@dataclass(frozen=True)
class SearchOptions:
    """How :func:`solve_target` walks the space (every field optional).

    Attributes
    ----------
    no_zero : bool
        Leave label 0 out of the space.
    fixes : tuple of (int, int)
        ``(edge, label)`` pairs every design keeps.
    count : int
        Designs wanted (>= 1).
    time_limit : float or None
        Seconds for the whole search (``None``: no limit).
    identify_time_limit : float or None
        Seconds per identification.
    processes : int
        Worker processes naming designs (>= 1).
    seed : int
        Projection seed.
    tolerance : float or None
        The symmetry search's, in mesh units (default: 1/100 of the shortest edge).
    widen : bool
        When the space is too big to walk and the target's diagram fits the mesh only with
        labels past the label set, search ``-k..k`` with the least ``k`` that fits instead
        of refusing (``label_set`` of the result says which).
    """

    no_zero: bool = False
    fixes: tuple[tuple[int, int], ...] = ()
    count: int = 1
    time_limit: float | None = None
    identify_time_limit: float | None = 60.0
    processes: int = 1
    seed: int = 0
    tolerance: float | None = None
    widen: bool = False

    def __post_init__(self) -> None:
        for name in ("count", "processes"):
            if getattr(self, name) < 1:
                raise UsageError(f"{name} {getattr(self, name)}: at least 1", parameter=name)


def solve_target(
    scaffold: Scaffold, goal: Goal, *, label_set: np.ndarray, options: SearchOptions = SearchOptions()
) -> TargetResult:
    """Find up to ``options.count`` designs of ``goal``, simplest first (see the module docstring).

    Examples
    --------
    >>> from lkspace import load
    >>> from lkspace.linktypes.names import parse_type
    >>> r = solve_target(load("dihedron:3"), Goal(1, parse_type("3_1")), label_set=np.arange(-1, 2))
    >>> r.status, r.solutions[0].labels, r.solutions[0].name
    ('found', (-1, -1, -1), '3_1')
    """
    o = options
    t0 = time.monotonic()
    deadline = None if not o.time_limit else t0 + o.time_limit
    fixes = dict(o.fixes) or None
    walk = OrderedWalk(
        scaffold, label_set, goal.components, no_zero=o.no_zero, fixes=fixes, deadline=deadline, tolerance=o.tolerance
    )
    tally: Counter[str] = Counter()
    solutions: list[TargetSolution] = []
    undetermined: list[Json] = []
    timed_out = False
    walked = True
    with (
        task(f"searching {scaffold.name} for {goal.label}") as step,
        _screener(scaffold, goal, o, label_set) as run,
    ):
        built, wider = _from_diagram(scaffold, goal, o, label_set, run, tally)
        simplest = [b for b in built if goal.target is not None and b.sum_abs == goal.target.crossings]
        if _genus(scaffold) == 0 and len(simplest) >= o.count:
            solutions = simplest[: o.count]
        try:
            pieces = _pieces(walk) if len(solutions) < o.count else iter(())
            for batch, rows, orbits in pieces:
                if deadline is not None and time.monotonic() > deadline:
                    timed_out = True
                    break
                for labels, orbit, verdict in run(rows, orbits):
                    tally["designs"] += 1
                    tally[f"{verdict.verdict}: {verdict.reason}"] += 1
                    if verdict.verdict == "undetermined":
                        undetermined.append(labels.tolist())
                    elif verdict.verdict == "match":
                        again = check_answer(scaffold, labels, goal, o.seed, o.identify_time_limit)
                        if again.verdict != "match":
                            tally["re-identification disagreed"] += 1
                            undetermined.append(labels.tolist())
                            continue
                        solutions.append(_solution(labels, orbit, goal, again))
                        if len(solutions) >= o.count:
                            break
                    if deadline is not None and time.monotonic() > deadline:
                        timed_out = True
                        break
                step.note(f"{tally['designs']:,} designs screened (|t| <= {batch.shell}), {len(solutions)} found")
                if len(solutions) >= o.count or timed_out:
                    break
        except TooLargeError as exc:
            if not built and wider is not None and o.widen:
                walked = False
            elif not built:
                hint = (
                    "" if wider is None else f"; the diagram of {goal.label} fits here with labels in -{wider}..{wider}"
                )
                refusal = str(exc).removesuffix(WALK_ADVICE)  # this search has no mode to switch to
                raise TooLargeError(f"{refusal}; use a smaller `label_set`{hint}") from None
            else:
                walked = False
    if not walked and not built and wider is not None:  # widen: the diagram's labels
        wide = solve_target(scaffold, goal, label_set=np.arange(-wider, wider + 1), options=replace(o, widen=False))
        return replace(wide, wall_time=time.monotonic() - t0)
    complete = walk.complete and not timed_out and len(solutions) < o.count
    more = [b for b in built if all(b.labels != s.labels for s in solutions)] if not walk.complete else []
    from_diagram = len(solutions) < o.count and bool(more)
    solutions += more[: o.count - len(solutions)]
    status: TargetStatus
    if from_diagram:
        why = "the space is too big to walk" if not walked else "the walk did not reach them"
        status, reason = "found", f"designs built from the diagram of {goal.label} need not be the simplest ({why})"
    elif solutions:
        status, reason = "found", ""
    elif complete and not undetermined:
        status, reason = "exhausted", "every design of the space is proved to be another type"
    elif undetermined:
        status, reason = "unknown", f"{plural(len(undetermined), 'design')} could not be told apart from the target"
    else:
        status, reason = "unknown", "time ran out before the space was searched"
    stats: JsonObject = dict(sorted(tally.items()))
    stats["undetermined_examples"] = undetermined[:5]
    labels = tuple(int(v) for v in label_set)
    return TargetResult(status, tuple(solutions), goal, time.monotonic() - t0, complete, stats, reason, labels)


FIRST_PIECE = 64
"""Designs screened in the first call; each next call screens 4 times more, up to :data:`PIECE`."""
PIECE = 2048
"""Most designs screened in one call: the time limit and signals are looked at between calls."""


def _pieces(walk: OrderedWalk) -> Iterator[tuple[Candidates, np.ndarray, np.ndarray]]:
    """Yield ``(batch, labels, orbit sizes)``: the walk's designs in order, few at first (simplest first, answered soon)."""
    size = FIRST_PIECE
    for batch in walk:
        start = 0
        while start < len(batch.labels):
            yield batch, batch.labels[start : start + size], batch.orbit_sizes[start : start + size]
            start += size
            size = min(4 * size, PIECE)


def _solution(labels: np.ndarray, orbit: int, goal: Goal, again: Screening) -> TargetSolution:
    a = np.abs(labels)
    return TargetSolution(
        labels=tuple(int(x) for x in labels),
        components=goal.components,
        sum_abs=int(a.sum()),
        max_abs=int(a.max()) if len(a) else 0,
        nonzero=int((labels != 0).sum()),
        orbit_size=int(orbit),
        linking_matrix=None if again.linking_matrix is None else tuple(tuple(r) for r in again.linking_matrix),
        identified=again.identified,
        name=again.name,
        chiral_name=again.chiral_name,
        mirror=again.mirror,
        table=again.table,
        crossings=again.crossings,
    )


class _screener:
    """A context giving ``run(labels, orbits)``: ``(labels, orbit, verdict)`` per row, in order.

    A batch is screened from its labels alone (:func:`~lkspace.linktypes.screen.screen_batch`);
    the keys judged are shared with every run (:func:`~lkspace.knots.key_names.disk_cache`).
    """

    def __init__(self, scaffold: Scaffold, goal: Goal, options: SearchOptions, label_set: np.ndarray) -> None:
        from ..knots.batch import Namer
        from ..knots.key_names import disk_cache

        self.scaffold, self.goal, self.seed, self.label_set = scaffold, goal, options.seed, label_set
        self.namer = Namer(options.processes, False, options.identify_time_limit)
        self.cache = disk_cache()
        self.deadline = None if not options.time_limit else time.monotonic() + options.time_limit

    def __enter__(self) -> Any:
        self.namer.__enter__()
        return self.run

    def run(self, labels: np.ndarray, orbits: np.ndarray) -> Iterator[tuple[np.ndarray, int, Screening]]:
        """Screen the rows of one batch of the walk (names within the search's time left, 1 s at least)."""
        if self.deadline is not None:
            self.namer.within(max(1.0, self.deadline - time.monotonic()))
        verdicts = screen_batch(self.scaffold, labels, self.goal, self.seed, self.cache, self.namer, self.label_set)
        for i, verdict in enumerate(verdicts):
            yield labels[i].astype(np.int64), int(orbits[i]), verdict

    def __exit__(self, *exc: object) -> None:
        self.namer.__exit__(*exc)  # a found answer or Ctrl-C: the workers stop at once


def _from_diagram(
    scaffold: Scaffold, goal: Goal, o: SearchOptions, label_set: np.ndarray, run: Any, tally: Counter[str]
) -> tuple[list[TargetSolution], int | None]:
    """Return the designs built from the target's diagram that name right twice, simplest first (``run``: the screener).

    And ``wider``: the least largest ``|t|`` of the designs ``label_set`` left out (``None``: none left out).
    """
    rows, orbits, wider = _diagram_candidates(scaffold, goal, o, label_set)
    matches = []
    for labels, orbit, verdict in run(rows, orbits):
        tally["designs"] += 1
        tally["designs built from the diagram"] += 1
        if verdict.verdict == "match":
            matches.append((int(np.abs(labels).sum()), int((labels != 0).sum()), labels.tobytes(), labels, orbit))
    built: list[TargetSolution] = []
    for *_, labels, orbit in sorted(matches, key=lambda m: m[:3]):
        again = check_answer(scaffold, labels, goal, o.seed, o.identify_time_limit)
        if again.verdict == "match":
            built.append(_solution(labels, orbit, goal, again))
        if len(built) >= o.count:
            break
    return built, wider


def _genus(s: Scaffold) -> int | None:
    """Return the genus of a closed connected scaffold (``None`` when ``2 - V + E - F`` is odd or negative)."""
    twice = 2 - s.n_vertices + s.n_edges - s.n_faces
    return twice // 2 if twice >= 0 and twice % 2 == 0 else None


def _diagram_candidates(
    scaffold: Scaffold, goal: Goal, options: SearchOptions, label_set: np.ndarray
) -> tuple[np.ndarray, np.ndarray, int | None]:
    """``(labels (n, n_edges) int64, orbit sizes (n,), wider)``: the target's diagram embedded in ``scaffold``, and mirrored.

    Kept: designs in ``label_set`` that keep ``options``' fixes (none with ``no_zero``: they
    have labels 0).  Empty unless the target is a table type and the scaffold closed; then
    ``wider`` is the least largest ``|t|`` of the designs ``label_set`` left out (else ``None``).
    """
    from ..scaffolds.constructed import table
    from .tait_embedding import embedded_designs

    empty = np.zeros((0, scaffold.n_edges), np.int64), np.zeros(0, np.int64)
    entry = table().get(goal.target.name) if goal.target is not None else None
    if entry is None or entry.components != goal.components or options.no_zero:
        return *empty, None
    fixes = dict(options.fixes)
    found = [x for _, labels in embedded_designs(scaffold, entry.pd) for x in (labels, -labels)]
    found = [x for x in found if all(x[e] == t for e, t in fixes.items())]
    kept = [x for x in found if np.isin(x, label_set).all()]
    if not kept:
        return *empty, min((int(np.abs(x).max()) for x in found), default=None)
    rows = np.array(kept, np.int64)
    return rows, _orbit_sizes(scaffold, rows, options), None


def _orbit_sizes(scaffold: Scaffold, rows: np.ndarray, options: SearchOptions) -> np.ndarray:
    """Return the size of each design's orbit under the scaffold's rotations (1 each with fixes)."""
    from ..symmetry.group import symmetry_group

    if options.fixes:
        return np.ones(len(rows), np.int64)
    perms, signs = symmetry_group(scaffold, options.tolerance).action("rotations")
    sizes = []
    for labels in rows:
        images = np.zeros((len(perms), len(labels)), np.int64)
        np.put_along_axis(images, perms, signs[:, None] * labels[None, :], axis=1)
        sizes.append(len(np.unique(images, axis=0)))
    return np.array(sizes, np.int64)
