"""The installable add-on zip: ``python -m lkspace.blender build -o dist/lkspace_blender.zip``.

The zip holds one folder, ``lkspace_blender/``, with the modules of
:mod:`lkspace.blender.addon` (a legacy add-on with ``bl_info``, which Blender 4.2 installs
from Edit > Preferences > Add-ons > Install from Disk).  The add-on imports lkspace from
Blender's Python; it does not bundle it.
"""

from __future__ import annotations

import os
import zipfile
from pathlib import Path

from ..io.atomic import atomic_path
from ..io.paths import output_file

ADDON = Path(__file__).resolve().parent / "addon"
"""Where the add-on's modules live in the lkspace package."""
FOLDER = "lkspace_blender"
"""The add-on's module name inside Blender (the zip's top folder)."""


def build(path: str | os.PathLike[str]) -> list[str]:
    """Write the add-on zip to ``path`` (creating its folder); return the names it holds.

    Examples
    --------
    >>> import tempfile
    >>> names = build(os.path.join(tempfile.mkdtemp(), "dist", "lkspace_blender.zip"))
    >>> "lkspace_blender/__init__.py" in names
    True
    """
    folder = os.path.dirname(os.path.abspath(os.fspath(path)))
    os.makedirs(folder, exist_ok=True)
    target = output_file(path, (".zip",))
    names = []
    with atomic_path(target) as tmp, zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as archive:
        for module in sorted(ADDON.glob("*.py")):
            name = f"{FOLDER}/{module.name}"
            archive.write(module, name)
            names.append(name)
    return names
