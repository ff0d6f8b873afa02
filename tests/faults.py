"""Faults injected into a real run, from the tests only (nothing of this ships in lkspace).

``python -m tests.faults FLAG enumerate ...`` runs the ``lkspace`` command line with one
fault: the first catalog part to start on a Dask worker creates the file ``FLAG`` and
kills its own worker process (SIGKILL), as a lost machine would; later parts (and the
part run again) are written normally.  The workers of ``--scheduler dask`` are forked
from this process, so they carry the patched :func:`lkspace.catalog.jobs.write_part_with`.
"""

from __future__ import annotations

import os
import signal
import sys
from typing import Any

from lkspace.catalog import jobs

_write_part_with = jobs.write_part_with
"""The real part writer."""

_FLAG: list[str] = []
"""The path whose creation marks the one kill."""


def write_part_killing_once(job: Any, i: int, on_rows: Any = None) -> Any:
    """Kill this worker if no part has done so yet (creating the flag file atomically), else write part ``i``."""
    try:
        fd = os.open(_FLAG[0], os.O_CREAT | os.O_EXCL | os.O_WRONLY)
    except FileExistsError:
        return _write_part_with(job, i, on_rows)
    os.close(fd)
    os.kill(os.getpid(), signal.SIGKILL)
    raise AssertionError("not reached")


def kill_a_worker_once(flag: str) -> None:
    """From now on, the first part to start kills its worker (see the module docstring)."""
    _FLAG[:] = [flag]
    jobs.write_part_with = write_part_killing_once


if __name__ == "__main__":
    from tests import faults  # this file by its importable name: workers unpickle the patch from there

    faults.kill_a_worker_once(sys.argv[1])
    from lkspace.cli import main

    sys.argv = ["lkspace", *sys.argv[2:]]
    sys.exit(main())
