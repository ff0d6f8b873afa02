"""Running a query: fast path first, then CP-SAT (solve-and-exclude), every design re-traced.

:mod:`lkspace.inverse.cpsat_model` builds the model and states why it is exact;
:mod:`lkspace.inverse.constructive` is the fast path; this module runs them in turn.
:func:`solve` is ``lkspace.solve``.
"""

from __future__ import annotations

import contextlib
import math
import threading
import time
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any, TypeAlias, TypedDict

import numpy as np

from ..errors import LabelError, SolveVerificationError, TooLargeError, UsageError
from ..model.scaffold import Scaffold
from ..model.specs import LabelSetSpec, parse_label_set
from ..runtime.progress import Step, task
from ..strands.tracing import trace
from ..symmetry.edge_orbits import invariant_edge_orbits
from ..symmetry.group import SymmetryMode, symmetry_group
from ..words import plural
from .constructive import spanning_designs
from .cpsat_model import build_model
from .query import Objective, Query, SolveStatus

MAX_COUNT = 10_000
"""Most designs one :func:`solve` call may ask for (``--count``): each is a solve-and-exclude round."""

EdgeAction: TypeAlias = tuple[np.ndarray, int]
"""A signed edge permutation ``(perm (n_edges,) int64, sign)``: label ``t`` on ``e`` becomes ``sign * t`` on ``perm[e]``."""


class SolveStats(TypedDict, total=False):
    """What the CP-SAT model and search measured: ``model_nodes`` (super-nodes), ``fixed_cycles``, ``search_time`` (s)."""

    model_nodes: int
    fixed_cycles: int
    search_time: float


@dataclass(frozen=True)
class Solution:
    """One design: labels ``(n_edges,) int64`` and its traced component count."""

    labels: np.ndarray
    components: int

    def __repr__(self) -> str:
        return f"Solution(components={self.components}, labels={self.labels.tolist()})"

    def to_dict(self) -> dict[str, Any]:
        """Return the JSON form (``labels``, ``components``)."""
        return {"labels": self.labels.tolist(), "components": self.components}


@dataclass(frozen=True)
class SolveResult:
    """The answer to a query: ``status`` and ``solutions`` (JSON fields in ``docs/cli.md``).

    ``status`` is ``"optimal"`` (objective proved optimal), ``"feasible"``, ``"infeasible"``
    (proved: no design exists) or ``"unknown"`` (time ran out before either).  ``method`` is
    ``"fast-path"``, ``"cp-sat"`` or ``"presolve"`` (decided before search).
    """

    status: SolveStatus
    solutions: list[Solution]
    method: str
    wall_time: float
    reason: str = ""
    exhausted: bool = False
    stats: SolveStats = field(default_factory=SolveStats)

    def __repr__(self) -> str:
        found = plural(len(self.solutions), "solution")
        return f"SolveResult({self.status}, {found} by {self.method} in {self.wall_time:.3f}s)"

    def to_dict(self) -> dict[str, Any]:
        """Return the JSON form (``status``, ``solutions``, ``method``, ...)."""
        out = {
            "status": self.status,
            "solutions": [s.to_dict() for s in self.solutions],
            "method": self.method,
            "wall_time": round(self.wall_time, 6),
            "exhausted": self.exhausted,
            **self.stats,
        }
        if self.reason:
            out["reason"] = self.reason
        return out


def verify(scaffold: Scaffold, labels: np.ndarray, components: int) -> Solution:
    """Trace ``labels``; raise :class:`SolveVerificationError` unless it has ``components``."""
    got = trace(scaffold, labels, np.zeros(scaffold.n_corners, bool)).components
    if got != components:
        raise SolveVerificationError(
            f"internal error: solver design {labels.tolist()} on {scaffold.name} traces to {got} "
            f"components, not {components}; please report this bug"
        )
    return Solution(np.asarray(labels, np.int64), got)


def _orbit(residues: np.ndarray, actions: list[EdgeAction], degrees: np.ndarray) -> list[np.ndarray]:
    """Images of a residue vector under edge actions ``(perm, sign)``: ``t'[perm[e]] = sign * t[e]``."""
    images = []
    for perm, sign in actions:
        img = np.empty_like(residues)
        img[perm] = (sign * residues) % degrees[perm]
        images.append(img)
    return images


@dataclass(frozen=True)
class SolveOptions:
    """How :func:`solve` searches: how many designs, told apart how, with what budget.

    Attributes
    ----------
    count : int
        Distinct solutions wanted (different strand connectivity), ``1..MAX_COUNT``.
    distinct_up_to : ``"none"``, ``"rotations"`` or ``"isometries"``
        With a symmetry group, no two solutions lie in one orbit.
    invariant : str, optional
        Only designs fixed by this subgroup of the symmetries (a name of
        :func:`~lkspace.symmetry.subgroups.parse_subgroup`, e.g. ``"C3"``); CP-SAT only.
    tolerance : float, optional
        Symmetry search tolerance for ``distinct_up_to`` and ``invariant``, in mesh units
        (default: 1/100 of the shortest edge).
    time_limit : float, optional
        Seconds for the whole call; running out gives status ``"unknown"`` (or
        ``"feasible"`` if some solutions were found).
    workers, seed : int
        CP-SAT search workers (0: all cores) and random seed.
    fast_path : bool
        Try the spanning-tree/forest construction of :mod:`lkspace.inverse.constructive` first (it
        answers many queries with N <= F in linear time; CP-SAT takes over otherwise).
    """

    count: int = 1
    distinct_up_to: SymmetryMode = "none"
    invariant: str | None = None
    tolerance: float | None = None
    time_limit: float | None = None
    workers: int = 0
    seed: int = 0
    fast_path: bool = True


def solve(
    scaffold: Scaffold,
    components: int,
    *,
    label_set: LabelSetSpec = "-2..2",
    no_zero: bool = False,
    fixes: Mapping[int, int] | None = None,
    parities: Mapping[int, int] | None = None,
    objective: Objective | None = None,
    options: SolveOptions | None = None,
) -> SolveResult:
    """Find up to ``options.count`` designs on ``scaffold`` with exactly ``components`` strands.

    Parameters
    ----------
    scaffold : Scaffold
        ``lkspace.solve`` also takes a path or a built-in name (:func:`lkspace.load`).
    components : int
        The number N of strand components wanted.
    label_set : str or sequence of int
        Labels the designs may use (``"-2..2"``, ``"-1,1"``, or integers).
    no_zero : bool
        Forbid label 0.
    fixes : dict of int -> int, optional
        Edge index -> label.
    parities : dict of int -> {0, 1}, optional
        Edge index -> 0 (even) or 1 (odd).
    objective : None, ``"min-abs"`` or ``"min-nonzero"``
    options : SolveOptions, optional
        How many designs, told apart how, the subgroup they keep, time, workers, seed.

    Examples
    --------
    >>> import lkspace
    >>> lkspace.solve("cube", 1, label_set="-1,1").status
    'infeasible'
    >>> r = lkspace.solve("tetrahedron", 1, no_zero=True)
    >>> r
    SolveResult(feasible, 1 solution by fast-path in ...s)
    >>> r.solutions[0].components
    1
    """
    t0 = time.perf_counter()
    opts = SolveOptions() if options is None else options
    check_budget(opts.count, opts.time_limit)
    labels = parse_label_set(label_set) if isinstance(label_set, str) else np.unique(np.asarray(label_set, np.int64))
    orbits = None if opts.invariant is None else invariant_edge_orbits(scaffold, opts.invariant, opts.tolerance)
    query = Query(int(components), labels, bool(no_zero), dict(fixes or {}), dict(parities or {}), objective, orbits)
    with task(f"solving {scaffold.name} for {plural(query.components, 'component')}") as step:
        step.note("symmetry" if opts.distinct_up_to != "none" else "fast path")
        actions = symmetry_actions(scaffold, opts.distinct_up_to, labels, opts.tolerance)
        found, answer = fast_path_designs(scaffold, query, opts, t0, step)
        if answer is not None:
            return answer
        hint = found[0] % scaffold.edge_degrees if found else None
        result = solve_cp_sat(scaffold, query, opts, actions, t0, hint, step)
    if found and result.status == "infeasible":
        raise SolveVerificationError(
            f"internal error: CP-SAT calls {scaffold.name} infeasible for "
            f"{plural(query.components, 'component')} but {found[0].tolist()} is a design"
        )
    if found and not result.solutions:  # time ran out: the constructed designs still stand
        sols = [verify(scaffold, t, query.components) for t in found]
        return SolveResult(
            "feasible",
            sols,
            "fast-path",
            time.perf_counter() - t0,
            "CP-SAT found no better design in time",
            False,
            result.stats,
        )
    return result


def fast_path_designs(
    scaffold: Scaffold, query: Query, opts: SolveOptions, t0: float, step: Step
) -> tuple[list[np.ndarray], SolveResult | None]:
    """Run the fast path where it applies: the designs it found, and the answer when they settle the query.

    The constructions know nothing of symmetry: no fast path for ``invariant``, nor for
    ``count > 1`` told apart up to symmetry.
    """
    if not opts.fast_path or opts.invariant is not None or (opts.count != 1 and opts.distinct_up_to != "none"):
        return [], None
    step.note("fast path")
    time_limit = opts.time_limit
    deadline = None if not time_limit else t0 + time_limit
    # the local search behind the fast path gets half of the time left (30 s without a limit)
    budget = 0.5 * (time_limit - (time.perf_counter() - t0)) if time_limit else LOCAL_SEARCH_SECONDS
    found, optimal = spanning_designs(scaffold, query, opts.count, opts.seed, budget, deadline, step)
    if len(found) == opts.count and (query.objective is None or optimal):
        sols = [verify(scaffold, t, query.components) for t in found]
        status: SolveStatus = "optimal" if query.objective is not None else "feasible"
        return found, SolveResult(status, sols, "fast-path", time.perf_counter() - t0)
    return found, None


def check_budget(count: int, time_limit: float | None) -> None:
    """Refuse a ``count`` outside ``1..MAX_COUNT`` or a time limit that is not a finite number >= 0."""
    if not 1 <= count <= MAX_COUNT:
        error = UsageError if count < 1 else TooLargeError
        raise error(f"count {count}: ask for 1..{MAX_COUNT:,} designs per call (MAX_COUNT)", parameter="count")
    if time_limit is not None and not (math.isfinite(time_limit) and time_limit >= 0):
        raise UsageError(
            f"time_limit {time_limit}: expected a finite number of seconds >= 0 (0: no limit)", parameter="time_limit"
        )


@contextlib.contextmanager
def heartbeat(step: Step, every: float = 1.0) -> Iterator[None]:
    """Refresh ``step`` every ``every`` seconds from a thread while a long native call runs."""
    stop = threading.Event()

    def beat() -> None:
        while not stop.wait(every):
            step.note(step.text)

    thread = threading.Thread(target=beat, name="lkspace-progress", daemon=True)
    thread.start()
    try:
        yield
    finally:
        stop.set()
        thread.join()


LOCAL_SEARCH_SECONDS = 30.0


def symmetry_actions(
    scaffold: Scaffold, mode: SymmetryMode, label_set: np.ndarray, tolerance: float | None = None
) -> list[EdgeAction]:
    """Edge actions ``(perm (n_edges,) int64, sign)`` of the non-identity symmetries for ``mode`` (``tolerance``: the search's)."""
    if mode == "none":
        return []
    if mode not in ("rotations", "isometries"):
        raise LabelError(
            f"distinct_up_to {mode!r}: expected rotations, isometries or none", usage=True, parameter="distinct_up_to"
        )
    if mode == "isometries" and not np.array_equal(np.sort(-label_set), label_set):
        raise LabelError(
            "distinct_up_to='isometries': the label set must be closed under negation",
            usage=True,
            parameter="distinct_up_to",
        )
    perms, signs = symmetry_group(scaffold, tolerance).action(mode)
    return [(perm, int(sign)) for perm, sign in zip(perms[1:], signs[1:], strict=True)]  # identity first


def solve_cp_sat(
    scaffold: Scaffold,
    query: Query,
    opts: SolveOptions,
    actions: list[EdgeAction],
    t0: float,
    hint: np.ndarray | None = None,
    step: Step | None = None,
) -> SolveResult:
    """Solve ``query`` with CP-SAT, solve-and-exclude, up to ``opts.count`` designs; times count from ``t0``.

    Every solution is re-traced (:func:`verify`) and excluded with its images under
    ``actions``; ``hint`` (a residue vector of a known design) seeds the search.  The time
    limit covers building the model too: if it is spent by then, the status is ``unknown``.
    """
    from ortools.sat.python import cp_model

    count, time_limit = opts.count, opts.time_limit
    if step is not None:
        step.note("building the CP-SAT model")
    dm = build_model(scaffold, query, None if time_limit is None else t0 + time_limit)
    stats: SolveStats = {"model_nodes": dm.n_nodes, "fixed_cycles": dm.n_fixed_cycles}
    if dm.decided == "unknown":
        return SolveResult("unknown", [], "cp-sat", time.perf_counter() - t0, dm.reason, False, stats)
    if dm.decided:
        return SolveResult(dm.decided, [], "presolve", time.perf_counter() - t0, dm.reason, True, stats)
    assert dm.model is not None  # built whenever the query is not decided before search
    if hint is not None:
        dm.hint(hint)
    solver = cp_model.CpSolver()
    # CP-SAT would catch Ctrl-C itself and leave SIGINT at the default action when done (the
    # next Ctrl-C then killed the program without a word): search_interruptibly stops it instead
    solver.parameters.catch_sigint_signal = False
    solver.parameters.num_workers = int(opts.workers)
    solver.parameters.random_seed = int(opts.seed)
    solver.parameters.interleave_search = True  # ties broken alike at any load (for a number of workers)
    degrees = scaffold.edge_degrees
    solutions: list[Solution] = []
    status: SolveStatus = "unknown"
    exhausted = False
    search_time = 0.0
    while len(solutions) < count:
        if time_limit is not None:
            left = time_limit - (time.perf_counter() - t0)
            if left <= 0:
                break
            solver.parameters.max_time_in_seconds = left
        if step is not None:
            step.note(f"CP-SAT search: {len(solutions)} of {plural(count, 'design')} so far")
        with heartbeat(step) if step is not None else contextlib.nullcontext():
            code = search_interruptibly(solver, dm.model)
        search_time += solver.wall_time
        if code in (cp_model.OPTIMAL, cp_model.FEASIBLE):
            residues = dm.residues_from(solver.boolean_value)
            solutions.append(verify(scaffold, dm.labels_of(residues), query.components))
            if len(solutions) == 1:
                status = "optimal" if code == cp_model.OPTIMAL and query.objective else "feasible"
            for res in [residues, *_orbit(residues, actions, degrees)]:
                dm.exclude(res)
        elif code == cp_model.INFEASIBLE:
            exhausted = True
            if not solutions:
                status = "infeasible"
            break
        elif code == cp_model.MODEL_INVALID:  # pragma: no cover - a bug in build_model
            raise SolveVerificationError(f"internal error: invalid CP-SAT model: {dm.model.validate()}")
        else:
            break
    stats["search_time"] = round(search_time, 6)
    return SolveResult(status, solutions, "cp-sat", time.perf_counter() - t0, "", exhausted, stats)


def search_interruptibly(solver: Any, model: Any) -> int:
    """Run ``solver.solve(model)`` in a thread; Ctrl-C or SIGTERM in this thread stops the search and goes on up.

    Python's signal handlers run in the main thread only between bytecodes, never inside a
    C++ search: waiting here in short joins keeps them running.
    """
    codes: list[int] = []
    search = threading.Thread(target=lambda: codes.append(solver.solve(model)), name="cp-sat", daemon=True)
    search.start()
    try:
        while search.is_alive():
            search.join(0.05)
    except BaseException:
        solver.stop_search()
        search.join()
        raise
    return codes[0]
