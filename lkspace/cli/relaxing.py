"""The relaxation options of ``lkspace export``: ``--relax`` and the options that refine or bound it."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeVar

import click

from ..errors import UsageError
from .numbers import Count, Finite

if TYPE_CHECKING:
    from ..geometry.realization import Realization

F = TypeVar("F", bound=Callable[..., Any])


def relax_options(func: F) -> F:
    """Add the options --relax, --relax-steps, --relax-time, --relax-fine, --relax-points, --relax-escape and --relax-seed."""
    options = [
        click.option(
            "--relax",
            is_flag=True,
            help="Relax the strands toward a tight shape without changing the link type (finite scaffolds; until it converges).",
        ),
        click.option(
            "--relax-steps",
            type=Count(1),
            metavar="N",
            help="Relax (implies --relax) for at most N steps (default 50,000; designs converge in hundreds to thousands).",
        ),
        click.option(
            "--relax-time",
            type=Finite(0, low_open=True),
            metavar="SECONDS",
            help="Relax (implies --relax) for at most SECONDS of wall-clock time, > 0 (default: no limit; a run it stops depends on the load).",
        ),
        click.option(
            "--relax-fine",
            is_flag=True,
            help="Relax (implies --relax), then refine the converged shape at twice the resolution: tighter, slower.",
        ),
        click.option(
            "--relax-points",
            type=Count(16, 64),
            metavar="N",
            help="Refine (implies --relax-fine) with N flow points per rope diameter in the last pass, 16 to 64 (default 16): tighter, slower.",
        ),
        click.option(
            "--relax-escape",
            type=Count(1),
            metavar="N",
            help="Relax (implies --relax), then N escape rounds: shake the tightest shape smoothly (seeded), relax it again, keep it if tighter.",
        ),
        click.option(
            "--relax-seed",
            type=Count(0),
            metavar="S",
            help="Seed of the --relax-escape rounds' shakes, an integer >= 0 (default 0): another seed, other escapes.",
        ),
    ]
    for option in reversed(options):
        func = option(func)
    return func


def relaxed(
    real: Realization,
    steps: int | None,
    time_limit: float | None,
    fine: bool,
    points: int | None = None,
    escape: int | None = None,
    seed: int | None = None,
) -> Realization:
    """Return ``real`` relaxed (:func:`lkspace.geometry.relax.relax`); say on stderr when a limit stopped it first.

    ``points`` implies ``fine``; ``seed`` needs ``escape`` (:func:`check_seed`, before any work).
    """
    from ..geometry.relax import RELAX_STEPS, relax

    out = relax(
        real,
        RELAX_STEPS if steps is None else steps,
        time_limit,
        fine or points is not None,
        points,
        escape or 0,
        seed or 0,
    )
    note = None if out.relaxation is None else out.relaxation.note()
    if note is not None:
        flag = "--relax-steps" if out.relaxation is not None and out.relaxation.stopped == "steps" else "--relax-time"
        click.echo(f"lkspace: note: {note}; raise {flag} to draw it tighter", err=True)
    return out


def check_seed(seed: int | None, escape: int | None) -> None:
    """Refuse ``--relax-seed`` without ``--relax-escape`` (it seeds nothing else)."""
    if seed is not None and escape is None:
        raise UsageError("--relax-seed seeds the escape rounds: give --relax-escape N too")
