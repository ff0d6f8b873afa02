"""The next chunk's keys computed while this one is named (:class:`KeysAhead`).

Keying runs in compiled code without Python's lock (:func:`lkspace.knots.keyed.design_keys`);
naming by key is Python (regina's simplifications, the cache).  So a background thread
keys chunk ``i + 1`` while the caller names chunk ``i``.  A chunk is keyed in units of
:data:`UNIT` designs: the thread takes them from the front, and a caller that asks for
the keys before they are all done keys the units not yet started itself, from the back,
so that both cores key while there is nothing to name.  The names are those of keying
each chunk when it is named: keys depend on the labels alone.
"""

from __future__ import annotations

import threading
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass
from types import TracebackType
from typing import Any

import numpy as np

from ..model.scaffold import Scaffold
from .keyed import DesignKeys, KeyingStopped, design_keys, joined, key_part, keying_input, keys_record
from .labels_diagram import DiagramTemplate

UNIT = 512
"""Designs per call of the kernel (about 10 ms): a stop is seen, and work is shared, at this grain."""


@dataclass
class _Chunk:
    """A chunk being keyed: its template, value indices ``(n, n_edges)``, units and their futures."""

    tmpl: DiagramTemplate
    vidx: np.ndarray
    units: list[np.ndarray]
    futures: list[Future[tuple[np.ndarray, ...]]]


class KeysAhead:
    """Keys chunks of one scaffold in a background thread, one chunk ahead (use as a context manager).

    Leaving the block (Ctrl-C, a time limit, an error) stops the keying within one unit
    (about 10 ms), before the block's exception goes on.
    """

    def __init__(self, scaffold: Scaffold, seed: int, label_values: Any) -> None:
        self.scaffold, self.seed, self.label_values = scaffold, seed, label_values
        self._stop = threading.Event()
        self._pool: ThreadPoolExecutor | None = None
        self._chunk: _Chunk | None = None
        self.futures: list[Future[tuple[np.ndarray, ...]]] = []
        """The futures of the units of the chunk submitted last (earlier chunks' keys are not held)."""

    def __enter__(self) -> KeysAhead:
        self._pool = ThreadPoolExecutor(1, thread_name_prefix="lkspace-keys")
        return self

    def __exit__(self, kind: type[BaseException] | None, exc: BaseException | None, tb: TracebackType | None) -> None:
        self._stop.set()
        if self._pool is not None:
            self._pool.shutdown(wait=True, cancel_futures=True)
        for future in self.futures:
            if future.done() and not future.cancelled():
                error = future.exception()
                if error is not None and not isinstance(error, KeyingStopped) and kind is None:
                    raise error

    def submit(self, labels_2d: np.ndarray) -> None:
        """Start keying ``labels_2d`` ``(n, n_edges)`` (the previous chunk's keys must have been taken)."""
        assert self._pool is not None and self._chunk is None, "one chunk ahead at a time"
        _ = design_keys.compiled  # loaded here, once, not by the thread and the caller at once
        tmpl, vidx = keying_input(self.scaffold, labels_2d, self.seed, self.label_values)
        units = [vidx[start : start + UNIT] for start in range(0, len(vidx), UNIT)] or [vidx]
        futures = [self._pool.submit(self._key_unit, tmpl, unit) for unit in units]
        self.futures = futures
        self._chunk = _Chunk(tmpl, vidx, units, futures)

    def result(self) -> DesignKeys:
        """Return the keys of the chunk submitted last: the units the thread has not started are keyed here."""
        assert self._chunk is not None, "nothing submitted"
        chunk, self._chunk = self._chunk, None
        parts: list[tuple[np.ndarray, ...] | None] = [None] * len(chunk.units)
        for i in reversed(range(len(parts))):
            if chunk.futures[i].cancel():
                parts[i] = key_part(chunk.tmpl, chunk.units[i])
        done = [
            part if part is not None else future.result() for part, future in zip(parts, chunk.futures, strict=True)
        ]
        return keys_record(chunk.tmpl, chunk.vidx, joined(done))

    def _key_unit(self, tmpl: DiagramTemplate, unit: np.ndarray) -> tuple[np.ndarray, ...]:
        """Key one unit in the thread, unless the block was left (:class:`KeyingStopped`)."""
        if self._stop.is_set():
            raise KeyingStopped
        return key_part(tmpl, unit)
