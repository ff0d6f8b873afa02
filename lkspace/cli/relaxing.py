"""The relaxation options of ``lkspace export`` (``--relax``, ``--relax-steps``, ``--relax-time``, ``--relax-fine``)."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeVar

import click

from .numbers import Finite

if TYPE_CHECKING:
    from ..geometry.realization import Realization

F = TypeVar("F", bound=Callable[..., Any])


def relax_options(func: F) -> F:
    """Add the options --relax, --relax-steps, --relax-time and --relax-fine."""
    options = [
        click.option(
            "--relax",
            is_flag=True,
            help="Relax the strands toward a tight shape without changing the link type (finite scaffolds; until it converges).",
        ),
        click.option(
            "--relax-steps",
            type=click.IntRange(1),
            metavar="N",
            help="Relax (implies --relax) for at most N steps (default 50,000; designs converge in hundreds to thousands).",
        ),
        click.option(
            "--relax-time",
            type=Finite(0, low_open=True),
            metavar="SECONDS",
            help="Relax (implies --relax) for at most SECONDS, > 0 (default: no limit; a run it stops depends on the load).",
        ),
        click.option(
            "--relax-fine",
            is_flag=True,
            help="Relax (implies --relax), then refine the converged shape at twice the resolution: tighter, slower.",
        ),
    ]
    for option in reversed(options):
        func = option(func)
    return func


def relaxed(real: Realization, steps: int | None, time_limit: float | None, fine: bool) -> Realization:
    """Return ``real`` relaxed (:func:`lkspace.geometry.relax.relax`); say on stderr when a limit stopped it first."""
    from ..geometry.relax import RELAX_STEPS, relax

    out = relax(real, RELAX_STEPS if steps is None else steps, time_limit, fine)
    note = None if out.relaxation is None else out.relaxation.note()
    if note is not None:
        flag = "--relax-steps" if out.relaxation is not None and out.relaxation.stopped == "steps" else "--relax-time"
        click.echo(f"lkspace: note: {note}; raise {flag} to draw it tighter", err=True)
    return out
