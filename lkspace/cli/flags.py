"""The command line's flag for each parameter of the Python API, and errors in those words.

Library errors name the parameter at fault (``LkspaceError.parameter``) and start their
message with it: ``"max_designs: must be at least 1, got 0"``.  The command line shows
the flag a user typed instead: ``"--max-designs: must be at least 1, got 0"``.
"""

from __future__ import annotations

from ..errors import LkspaceError

FLAGS = {
    "label_set": "--labels",
    "labels": "--twist",
    "nulls": "--null",
}
"""Parameters whose flag is not ``--`` and the name with dashes (``max_designs`` -> ``--max-designs``)."""


def flag(parameter: str) -> str:
    """Return the command-line flag of a Python API parameter: ``"label_set"`` -> ``"--labels"``."""
    return FLAGS.get(parameter, "--" + parameter.replace("_", "-"))


def in_flags(exc: LkspaceError) -> str:
    """Return the message of ``exc`` as the command line shows it: a leading parameter name becomes its flag."""
    message = str(exc)
    parameter = getattr(exc, "parameter", None)
    if parameter and message.startswith(parameter):
        return flag(parameter) + message[len(parameter) :]
    return message
