"""Shared pieces of the command line: MESH loading, label options, output, errors."""

from __future__ import annotations

import contextlib
import json
import os
import sys
from collections.abc import Callable, Iterator
from typing import Any

import click
import numpy as np

from ..errors import LabelError, LkspaceError, UsageError
from ..io.sources import load, reads_builtin
from ..io.twists import parse_twist
from ..model.scaffold import Scaffold
from ..model.specs import parse_label_set, parse_nulls
from ..scaffolds import DEFAULT
from ..words import rounded
from .flags import flags_in


class Context:
    """What a command needs to report: the JSON flag and notes for the JSON object."""

    def __init__(self, as_json: bool) -> None:
        self.as_json = as_json
        self.notes: dict[str, Any] = {}


@contextlib.contextmanager
def usage_errors(usage: bool = True) -> Iterator[None]:
    """Mark the lkspace errors raised inside as usage errors (exit 2): the input was an option value."""
    try:
        yield
    except LkspaceError as exc:
        if usage:
            exc.exit_code = 2
        raise


def names_file(text: str) -> bool:
    """Return whether the option or argument value ``text`` names an existing regular file (data, not usage).

    A folder, FIFO or device named where a file belongs is bad usage, like a missing file.
    """
    return os.path.isfile(text)


def load_mesh(ctx: Context, mesh: str | None) -> Scaffold:
    """Load MESH, or the default built-in (said on stderr and in the JSON).

    Errors in a file are bad data (exit 1); a bad built-in name or missing path is bad usage (2).
    """
    if mesh is None:
        click.echo(f"lkspace: no MESH given; using the built-in {DEFAULT!r}", err=True)
        ctx.notes["default_scaffold"] = True
        mesh = DEFAULT
    weld = click.get_current_context(silent=True)
    tol = None if weld is None else weld.meta.get(WELD_KEY)
    reads_file = not reads_builtin(mesh) and names_file(mesh)
    with usage_errors(not reads_file):
        if tol is not None and not reads_file:
            raise UsageError(f"--weld: {mesh!r} is a built-in scaffold, not a file; welding applies to files")
        scaffold = load(mesh, weld=tol)
    ctx.notes["scaffold"] = scaffold.name
    if tol is not None:
        ctx.notes["welded"] = {"tolerance": None if tol is True else tol, "vertices": scaffold.n_vertices}
    given = symmetry_tolerance()
    if given is not None:
        from ..symmetry.tolerance import resolve_tolerance

        try:
            resolve_tolerance(scaffold, given)  # a tolerance past half the shortest edge fails before any work
        except UsageError as exc:
            raise UsageError(f"--{exc}") from None
    return scaffold


def symmetry_facts(scaffold: Scaffold) -> dict[str, Any]:
    """Find the symmetry group with ``--tolerance`` (or the default); say when a larger one was just missed.

    Returns ``group`` (e.g. ``"6 rotations, 12 isometries"``), ``symmetry_group_order``
    (``{"rotations": int, "isometries": int}``), ``symmetry_tolerance``
    (mesh units) and ``symmetry_note`` (``None``, or the line also printed on stderr as a note).
    """
    from ..symmetry.group import symmetry_orders
    from ..symmetry.nearby import near_symmetry
    from ..symmetry.tolerance import resolve_tolerance

    tol = resolve_tolerance(scaffold, symmetry_tolerance())
    isometries, rotations = symmetry_orders(scaffold, tol)  # periodic: without the group's tables
    near = near_symmetry(scaffold, tol)
    note = None if near is None else flags_in(near.message(scaffold.name, rotations, isometries))
    if note is not None:
        click.echo(f"lkspace: note: {note}", err=True)
    return {
        "group": f"{rotations} rotations, {isometries} isometries",
        "symmetry_group_order": {"rotations": rotations, "isometries": isometries},
        "symmetry_tolerance": tol,
        "symmetry_note": note,
    }


def symmetry_tolerance() -> float | None:
    """Return the ``--tolerance T`` of the running command (mesh units), or ``None`` for the default rule."""
    current = click.get_current_context(silent=True)
    value = None if current is None else current.meta.get(TOLERANCE_KEY)
    return None if value is None else float(value)


def labels_of(scaffold: Scaffold, spec: str | None) -> np.ndarray:
    """Return the twist labels of ``--twist SPEC``, else the labels stored in the scaffold file."""
    if spec is None:
        if scaffold.labels is None:
            raise LabelError(f"{scaffold.name}: no --twist given and the scaffold carries no twist labels", usage=True)
        return scaffold.labels
    with usage_errors(not names_file(spec)):
        return parse_twist(scaffold, spec)


def nulls_of(scaffold: Scaffold, spec: str | None) -> np.ndarray | None:
    """Return the null edge-sides ``(n_corners,) bool`` of ``--null SPEC``, else the scaffold's own (or ``None``)."""
    if spec is None:
        return scaffold.nulls
    with usage_errors():  # null edge-sides are always typed on the command line
        return parse_nulls(scaffold, spec)


def label_set(spec: str) -> np.ndarray:
    """Return the label set of ``--labels SET`` as a sorted ``(n,) int64`` array."""
    with usage_errors():
        return parse_label_set(spec)


def emit(ctx: Context, payload: dict[str, Any], human: Callable[[], object] | None, exact: bool = False) -> None:
    """Print ``payload`` as one JSON object (``--json``) or call ``human()`` (``None``: JSON only).

    Floats are measured values: JSON carries them to 12 significant digits (``0.042``, not
    ``0.041999999999999996``); ``exact`` keeps every digit (coordinates of a scaffold).
    """
    if ctx.as_json:
        out = {**ctx.notes, **payload}
        text = json.dumps(out if exact else rounded(out), default=_jsonable) + "\n"
        try:
            sys.stdout.write(text)
            sys.stdout.flush()
        except OSError as exc:  # a full disk or a closed pipe at stdout: say where (EPIPE stays BrokenPipeError)
            raise OSError(exc.errno, exc.strerror, "standard output") from None
    else:
        assert human is not None, "emit: no human-readable output given for a command without --json"
        human()


def print_rows(rows: list[tuple[str, str]]) -> None:
    """Print ``(name, value)`` rows as an aligned two-column list, values whole.

    A table sized to the terminal cut long values (a count of 10^28 designs) with ``…``;
    these lines are as long as their values, whatever the width of the terminal or pipe.
    """
    width = max((len(name) for name, _ in rows), default=0)
    for name, value in rows:
        click.echo(f" {name:<{width}}  {value}".rstrip())


def _jsonable(value: object) -> int | float | list[Any]:
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.floating):
        return float(value)
    if isinstance(value, np.ndarray):
        return value.tolist() if value.dtype.kind != "f" else rounded(value.tolist())
    raise TypeError(f"not JSON serializable: {type(value).__name__}")


json_option = click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout and nothing else.")
WELD_KEY = "lkspace.weld"
"""Key of the ``--weld`` tolerance in ``click.Context.meta`` (``True``: the default tolerance)."""


def _store_weld(ctx: click.Context, _param: click.Parameter, value: str | None) -> None:
    """Check ``--weld [TOL]`` and keep it in the context for :func:`load_mesh`."""
    if value is None:
        return
    if value == "default":
        ctx.meta[WELD_KEY] = True
        return
    try:
        tol = float(value)
    except ValueError:
        raise UsageError(
            f"--weld {value[:40]!r}: TOL must be a number; write --weld after MESH, or --weld=TOL"
        ) from None
    if not 0 <= tol <= 1e12:  # NaN fails too
        raise UsageError(f"--weld {value!r}: TOL must be a finite number >= 0")
    ctx.meta[WELD_KEY] = tol


weld_option = click.option(
    "--weld",
    is_flag=False,
    flag_value="default",
    default=None,
    expose_value=False,
    callback=_store_weld,
    metavar="[TOL]",
    help="Merge vertices of MESH closer than TOL (default 1e-6 x bounding-box diagonal); put it after MESH.",
)


TOLERANCE_KEY = "lkspace.tolerance"
"""Key of the ``--tolerance`` value in ``click.Context.meta`` (read by :func:`symmetry_tolerance`)."""


def _store_tolerance(ctx: click.Context, _param: click.Parameter, value: str | None) -> None:
    """Check ``--tolerance T`` (a finite number > 0) and keep it in the context."""
    if value is None:
        return
    from ..symmetry.tolerance import check_tolerance

    try:
        ctx.meta[TOLERANCE_KEY] = check_tolerance(value)
    except UsageError as exc:
        raise UsageError(f"--{exc}") from None


tolerance_option = click.option(
    "--tolerance",
    default=None,
    expose_value=False,
    callback=_store_tolerance,
    metavar="T",
    help="How far apart two points may be and still count as one for symmetry (mesh units; "
    "default 1/100 of the shortest edge).",
)


def mesh_argument(func: Callable[..., Any]) -> Callable[..., Any]:
    """Add the ``[MESH]`` argument, its ``--weld [TOL]`` and ``--tolerance T`` options (read by :func:`load_mesh`)."""
    return click.argument("mesh", required=False, metavar="[MESH]")(weld_option(tolerance_option(func)))


labels_option = click.option(
    "--labels",
    "--label-set",
    "labels_spec",
    default="-2..2",
    show_default=True,
    metavar="SET",
    help="Label set: a range like -2..2 or a comma list like -2,-1,1,2.",
)
