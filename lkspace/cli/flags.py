"""The command line's flag for each parameter of the Python API, and errors in those words.

Library errors name the parameter at fault (``LkspaceError.parameter``) and start their
message with it: ``"max_designs: must be at least 1, got 0"``.  The command line shows
the flag a user typed instead: ``"--max-designs: must be at least 1, got 0"``.  A
parameter named further on stands in backquotes, alone or with a value
(``"use a smaller `thickness`"``, ``"use `symmetry='none'`"``), and becomes its flag too
(``"use a smaller --thickness"``, ``"use --symmetry none"``).
"""

from __future__ import annotations

import re

from ..errors import LkspaceError

QUOTED = re.compile(r"`([a-z][a-z0-9_]*)(?:=([^`]*))?`")
"""A parameter named inside a message: a Python name in backquotes, with an optional ``=value``."""

FLAGS = {
    "fixes": "--fix",
    "label_set": "--labels",
    "labels": "--twist",
    "nulls": "--null",
    "parities": "--parity",
    "subgroup": "--invariant",
    "type_name": "--type",
    "window": "--dna-window",
    "max_points": "MAX_POINTS",
    "name": "NAME",
}
"""Parameters whose flag is not ``--`` and the name with dashes (``max_designs`` -> ``--max-designs``).

``max_points`` has no flag: the command line sets it from the bound :data:`~lkspace.geometry.limits.MAX_POINTS`.
"""


def flag(parameter: str) -> str:
    """Return the command-line flag of a Python API parameter: ``"label_set"`` -> ``"--labels"``."""
    return FLAGS.get(parameter, "--" + parameter.replace("_", "-"))


def in_flags(exc: LkspaceError) -> str:
    """Return the message of ``exc`` as the command line shows it: parameter names become their flags.

    The leading name of the parameter at fault (as a word, optionally ``name=value``), and
    every name in backquotes; ``name=value`` becomes the flag and the value, unquoted.
    """
    message = flags_in(str(exc))
    parameter = getattr(exc, "parameter", None)
    if parameter:
        leading = re.compile("^" + re.escape(parameter) + r"(?:=('[^']*'|[^\s,;:)]+))?(?!\w)")
        message = leading.sub(lambda m: _as_flag(parameter, m[1]), message, count=1)
    return message


def flags_in(text: str) -> str:
    """Return ``text`` (a message, a note, a warning) with every backquoted parameter as its flag."""
    return QUOTED.sub(lambda m: _as_flag(m[1], m[2]), text)


def _as_flag(name: str, value: str | None) -> str:
    """``name`` or ``name=True`` -> ``--flag``; ``name='v'`` or ``name=v`` -> ``--flag v``."""
    if value is None or value == "True":
        return flag(name)
    return flag(name) + " " + value.strip("'\"")
