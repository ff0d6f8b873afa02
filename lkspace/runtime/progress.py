"""Progress of long steps, reported on stderr by the command line and silent elsewhere.

Library code marks a long step with :func:`task` and advances it; nothing is shown
unless a reporter is installed (the command line installs :func:`stderr_reporter`) and
the step has lasted :data:`DELAY` seconds, so short runs stay quiet::

    with task("symmetry search", total=n_candidates) as step:
        for ...:
            step.advance()
            step.note(f"{found} motions")

This module imports nothing of lkspace, so every layer may use it.
"""

from __future__ import annotations

import contextlib
import os
import sys
import time
from collections.abc import Callable, Iterator
from typing import Any, Protocol

DELAY = 2.0
"""Seconds a step runs before its progress is shown."""

PLAIN_EVERY = 10.0
"""Seconds between progress lines when stderr is not a terminal."""


class Reporter(Protocol):
    """What shows a step: called with its state whenever it changes."""

    def show(self, step: Step) -> None:
        """Show (or refresh) ``step``."""

    def close(self, step: Step) -> None:
        """Remove ``step`` from the display; it has ended."""


class Step:
    """One long step: a description, work done so far, the total (or ``None``) and a note."""

    def __init__(self, description: str, total: float | None, reporter: Reporter | None) -> None:
        self.description = description
        self.total = total
        self.completed = 0.0
        self.text = ""
        self.started = time.monotonic()
        self._reporter = reporter

    @property
    def elapsed(self) -> float:
        """Seconds since the step began."""
        return time.monotonic() - self.started

    @property
    def done(self) -> str:
        """Work done so far as text: ``"1,200"`` or ``"1,200/5,000"``; ``""`` for a step that counts nothing."""
        if not self.completed and not self.total:
            return ""
        return f"{self.completed:,.0f}" + (f"/{self.total:,.0f}" if self.total else "")

    def advance(self, amount: float = 1) -> None:
        """Count ``amount`` more units of work done."""
        self.completed += amount
        self._refresh()

    def update(self, completed: float | None = None, total: float | None = None) -> None:
        """Set the work done and/or the total."""
        if completed is not None:
            self.completed = completed
        if total is not None:
            self.total = total
        self._refresh()

    def note(self, text: str) -> None:
        """Set the short note shown after the bar (e.g. the best answer so far)."""
        self.text = text
        self._refresh()

    def _refresh(self) -> None:
        if self._reporter is not None and self.elapsed >= DELAY:
            self._reporter.show(self)


_reporter: Reporter | None = None


def install(reporter: Reporter | None) -> None:
    """Show progress through ``reporter`` from now on (``None``: show nothing)."""
    global _reporter
    _reporter = reporter


@contextlib.contextmanager
def task(description: str, total: float | None = None) -> Iterator[Step]:
    """Mark a long step; yield its :class:`Step` to advance."""
    step = Step(description, total, _reporter)
    try:
        yield step
    finally:
        if _reporter is not None:
            _reporter.close(step)


class PlainReporter:
    """One line per step every :data:`PLAIN_EVERY` seconds (for logs and pipes)."""

    def __init__(self, write: Callable[[str], Any]) -> None:
        self._write = write
        self._last: dict[int, float] = {}

    def show(self, step: Step) -> None:
        """Write a line for ``step`` unless one was written recently."""
        now = time.monotonic()
        if now - self._last.get(id(step), 0.0) < PLAIN_EVERY:
            return
        self._last[id(step)] = now
        what = ", ".join(part for part in (step.done, step.text) if part) or "working"
        self._write(f"lkspace: {step.description}: {what} ({step.elapsed:.0f} s)\n")

    def close(self, step: Step) -> None:
        """Forget ``step``."""
        self._last.pop(id(step), None)


class RichReporter:
    """A rich progress bar per step on the terminal, removed when the step ends."""

    def __init__(self) -> None:
        from rich.console import Console
        from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

        self._progress = Progress(
            TextColumn("{task.description}"),
            BarColumn(),
            TextColumn("{task.fields[done]}"),
            TextColumn("{task.fields[note]}"),
            TimeElapsedColumn(),
            console=Console(stderr=True),
            transient=True,
        )
        self._ids: dict[int, Any] = {}

    def show(self, step: Step) -> None:
        """Draw or refresh the bar of ``step``."""
        done = step.done
        if id(step) not in self._ids:
            if not self._ids:
                self._progress.start()
            self._ids[id(step)] = self._progress.add_task(step.description, total=step.total, done=done, note="")
        self._progress.update(
            self._ids[id(step)], completed=step.completed, total=step.total, done=done, note=step.text
        )

    def close(self, step: Step) -> None:
        """Remove the bar of ``step``; stop drawing when no bar is left."""
        task_id = self._ids.pop(id(step), None)
        if task_id is not None:
            self._progress.remove_task(task_id)
            if not self._ids:
                self._progress.stop()


def stderr_reporter() -> Reporter | None:
    """Return the reporter for stderr: rich on a terminal, plain lines otherwise.

    ``LKSPACE_PROGRESS=0`` turns progress off, ``=1`` forces plain lines.
    """
    setting = os.environ.get("LKSPACE_PROGRESS", "")
    if setting == "0":
        return None
    if setting != "1" and sys.stderr.isatty():
        return RichReporter()
    return PlainReporter(sys.stderr.write)
