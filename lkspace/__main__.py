"""The ``lkspace`` program (``python -m lkspace`` too): Ctrl-C stops it quietly from its first line on.

Python turns a Ctrl-C into a traceback wherever it lands, and the command line catches it
only once a command runs (:func:`lkspace.cli.main`).  Before that (while click and the
command line import) and after it (while the interpreter winds down) nothing is under
way, so here Ctrl-C ends the program at once: one line, status 130, as an interrupted
command.  What Python does before this module runs (its own start-up) is out of reach.

Python's cyclic garbage collector runs after every 700 new container objects by default;
a command makes millions (PD codes as lists, rows as dicts) that are freed by reference
counting, so here it runs after :data:`GC_EVERY` (15% of the CPU of ``enumerate cube
--labels -1..1 --identify``, the same memory).  Once the command is done, what it left is
frozen (:func:`gc.freeze`): the interpreter's teardown then frees it by reference counting
and the operating system, without the collector's passes over it (0.2 s of ``enumerate
cube --labels -1..1 --identify``'s 1.7 s); exit handlers still run.
"""

import gc
import os
import signal
import sys
from types import FrameType
from typing import NoReturn

GC_EVERY = 50_000
"""New container objects between runs of the garbage collector's youngest generation (Python's default 700)."""


def _stop(signum: int, frame: FrameType | None) -> NoReturn:
    """Ctrl-C outside a command: say so as an interrupted command does, and exit 130."""
    os.write(2, b"lkspace: error: interrupted\n")
    if "--json" in sys.argv[1:]:
        os.write(1, b'{"error": {"type": "Interrupted", "message": "interrupted", "exit_code": 130}}\n')
    os._exit(128 + signum)


def main() -> None:
    """Run the command line on ``sys.argv`` and exit with its status."""
    signal.signal(signal.SIGINT, _stop)
    gc.set_threshold(GC_EVERY, *gc.get_threshold()[1:])
    from .cli import main as run

    try:
        signal.signal(signal.SIGINT, signal.default_int_handler)  # the command line's own handling
        code = run()
    except KeyboardInterrupt:  # the instant before the command line's handling starts
        _stop(signal.SIGINT, None)
    signal.signal(signal.SIGINT, _stop)  # the interpreter's teardown
    gc.freeze()
    sys.exit(code)


if __name__ == "__main__":
    main()
