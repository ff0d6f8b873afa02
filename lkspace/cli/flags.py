"""The command line's flag for each parameter of the Python API, and errors in those words.

Library errors name the parameter at fault (``LkspaceError.parameter``) and start their
message with it: ``"max_designs: must be at least 1, got 0"``.  The command line shows
the flag a user typed instead: ``"--max-designs: must be at least 1, got 0"``.  Other
parameters a message names (``LkspaceError.mentions``) become flags too: ``symmetry='none'``
-> ``--symmetry none``, ``count_only=True`` and a bare ``count_only`` -> ``--count-only``.
"""

from __future__ import annotations

import re

from ..errors import LkspaceError

FLAGS = {
    "fixes": "--fix",
    "label_set": "--labels",
    "labels": "--twist",
    "nulls": "--null",
    "parities": "--parity",
    "subgroup": "--invariant",
    "type_name": "--type",
}
"""Parameters whose flag is not ``--`` and the name with dashes (``max_designs`` -> ``--max-designs``)."""


def flag(parameter: str) -> str:
    """Return the command-line flag of a Python API parameter: ``"label_set"`` -> ``"--labels"``."""
    return FLAGS.get(parameter, "--" + parameter.replace("_", "-"))


def in_flags(exc: LkspaceError) -> str:
    """Return the message of ``exc`` as the command line shows it: parameter names become flags.

    A leading ``exc.parameter`` becomes its flag, and so does each name in ``exc.mentions``
    wherever it stands as a word; ``name=value`` becomes the flag and the value, unquoted.
    """
    message = str(exc)
    parameter = getattr(exc, "parameter", None)
    if parameter:
        message = _mention(parameter, "^").sub(_as_flag, message, count=1)
    for name in getattr(exc, "mentions", ()):
        message = _mention(name, r"(?<![\w.-])").sub(_as_flag, message)
    return message


def _mention(name: str, before: str) -> re.Pattern[str]:
    """``name`` as a word after ``before``, with an optional ``=value`` (quoted, or up to a space or ``,;:)``)."""
    return re.compile(before + re.escape(name) + r"(?:=('[^']*'|[^\s,;:)]+))?(?!\w)")


def _as_flag(mention: re.Match[str]) -> str:
    """``name`` or ``name=True`` -> ``--flag``; ``name='v'`` or ``name=v`` -> ``--flag v``."""
    name = mention.group(0).split("=", 1)[0]
    value = mention.group(1)
    if value is None or value == "True":
        return flag(name)
    return flag(name) + " " + value.strip("'")
