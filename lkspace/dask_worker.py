"""Start a Dask worker that can also import SnapPy: ``python -m lkspace.dask_worker tcp://HOST:8786 [options]``.

The options are those of ``dask worker``.  SnapPy (extra ``lkspace[knots]``) installs a
module named ``snappy``, which ``distributed`` mistakes for the python-snappy compressor
when it is imported in a fresh interpreter; this entry point imports ``distributed``
beside it (:func:`lkspace.runtime.schedulers.import_distributed`) and has the worker processes forked
from it.  See ``docs/scale.md``.
"""

from __future__ import annotations


def main() -> None:
    """Run ``dask worker`` with ``distributed`` imported beside SnapPy."""
    from .runtime.schedulers import import_distributed

    import_distributed("python -m lkspace.dask_worker")
    import dask
    from distributed.cli.dask_worker import main as dask_worker

    dask.config.set({"distributed.worker.multiprocessing-method": "fork", "distributed.worker.daemon": False})
    dask_worker()


if __name__ == "__main__":
    main()
