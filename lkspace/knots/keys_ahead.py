"""The next chunk's keys computed while this one is named (:class:`KeysAhead`).

Keying runs in compiled code without Python's lock (:func:`lkspace.knots.keyed.keys_of`);
naming by key is Python (regina's simplifications, the cache).  So a background thread
keys chunk ``i + 1`` while the caller names chunk ``i``: on two cores the keying of all
but the first chunk hides behind the naming.  The first chunk is keyed with every core
(nothing else is running), the next ones with one thread (the naming keeps its core).  The names are those of keying each chunk
when it is named: keys depend on the labels alone.
"""

from __future__ import annotations

import threading
from concurrent.futures import Future, ThreadPoolExecutor
from types import TracebackType
from typing import Any

import numpy as np

from ..model.scaffold import Scaffold
from .keyed import DesignKeys, KeyingStopped, keys_of


class KeysAhead:
    """Keys chunks of one scaffold in a background thread, one chunk ahead (use as a context manager).

    Leaving the block (Ctrl-C, a time limit, an error) stops the keying within one call
    of the kernel (about 0.1 s), before the block's exception goes on.
    """

    def __init__(self, scaffold: Scaffold, seed: int, label_values: Any) -> None:
        self.scaffold, self.seed, self.label_values = scaffold, seed, label_values
        self._stop = threading.Event()
        self._pool: ThreadPoolExecutor | None = None
        self._future: Future[DesignKeys] | None = None
        self._submitted = 0

    def __enter__(self) -> KeysAhead:
        self._pool = ThreadPoolExecutor(1, thread_name_prefix="lkspace-keys")
        return self

    def __exit__(self, kind: type[BaseException] | None, exc: BaseException | None, tb: TracebackType | None) -> None:
        self._stop.set()
        if self._pool is not None:
            self._pool.shutdown(wait=True, cancel_futures=True)
        if self._future is not None and self._future.done() and not self._future.cancelled():
            error = self._future.exception()
            if error is not None and not isinstance(error, KeyingStopped) and kind is None:
                raise error

    def submit(self, labels_2d: np.ndarray) -> None:
        """Start keying ``labels_2d`` ``(n, n_edges)`` (the previous chunk's keys must have been taken)."""
        assert self._pool is not None and self._future is None, "one chunk ahead at a time"
        threads = None if self._submitted == 0 else 1
        args = (self.scaffold, labels_2d, self.seed, self.label_values, self._stop, threads)
        self._future = self._pool.submit(keys_of, *args)
        self._submitted += 1

    def result(self) -> DesignKeys:
        """Return the keys of the chunk submitted last (waiting for them; Ctrl-C is seen while waiting)."""
        assert self._future is not None, "nothing submitted"
        future, self._future = self._future, None
        return future.result()
