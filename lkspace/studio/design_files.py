"""Save, open and name designs: the studio's design files (:mod:`lkspace.io.design_json`).

``/api/design-file`` writes the page's design (scaffold, labels, nulls, block, camera) as a
design file download; ``/api/open-design`` (in ``app.py``, a raw body like an upload) reads
one with :func:`open_upload` and answers what the page loads; ``/api/filename`` gives the
stem every download is named with (:func:`~lkspace.studio.filenames.design_stem`).  A design on a built-in scaffold names
it; any other scaffold (a file, an upload, a catalog's) is embedded, so the file opens anywhere.
"""

from __future__ import annotations

import json
import os
from typing import TYPE_CHECKING

import numpy as np
from starlette.responses import Response

from .. import Scaffold
from ..errors import LkspaceError, ScaffoldError, TooLargeError
from ..io.design_json import Design, design_to_dict, format_design, is_design, read_design
from ..io.text import read_text
from .answers import OpenedDesign, Stem
from .designs import labels_from_page, parse_block, parse_nulls
from .filenames import design_stem
from .requests import DesignFileRequest, DesignRequest
from .scaffolds import Registry

if TYPE_CHECKING:
    from .app import Studio


def stem_of(studio: Studio, request: DesignRequest) -> str:
    """Return the file name stem of the design a request names (``key``, ``labels``, ``nulls``)."""
    held = studio.registry.get(request.key)
    labels = labels_from_page(held.scaffold, request.labels)
    nulls = parse_nulls(held.scaffold, request.nulls)
    return design_stem(held.scaffold.name, labels, [] if nulls is None else np.flatnonzero(nulls))


def filename(studio: Studio, request: DesignRequest) -> Stem:
    """Answer ``{"stem": ...}``: the name the page gives its own downloads (PNG of the view, videos)."""
    return Stem(stem_of(studio, request))


def save_design(studio: Studio, request: DesignFileRequest) -> Response:
    """Return the page's design as a design file download (``key``, ``labels``, ``nulls``, ``block``, ``view``)."""
    ref = request.design
    held = studio.registry.get(ref.key)
    sc = held.scaffold
    labels = labels_from_page(sc, ref.labels)
    nulls = parse_nulls(sc, ref.nulls)
    parse_block(sc, ref.block)  # the sizes a redraw accepts
    builtin = held.key if held.origin == "built-in" else None
    block = ref.block if sc.periodic and ref.block else None
    data = design_to_dict(sc, builtin, labels, nulls, block, dict(request.view) if request.view else None)
    name = stem_of(studio, ref) + ".design.json"
    return Response(
        format_design(data),
        media_type="application/json",
        headers={"Content-Disposition": f'attachment; filename="{name}"'},
    )


def open_text(registry: Registry, text: str, name: str, pinned: bool = False) -> OpenedDesign:
    """Read design file ``text`` and hold its scaffold: answer what the page loads (key, labels, nulls, block, view)."""

    def resolve(builtin: str) -> Scaffold:
        try:
            return registry.get(builtin).scaffold
        except TooLargeError as exc:
            raise TooLargeError(f"{name}: scaffold: {exc}") from None
        except LkspaceError:
            raise ScaffoldError(
                f"{name}: scaffold {builtin[:60]!r} is not a built-in scaffold: name one (like 'cube') "
                "or embed the scaffold file object"
            ) from None

    found: Design = read_design(text, name, resolve)
    if found.block is not None:
        try:
            parse_block(found.scaffold, found.block)
        except LkspaceError as exc:
            raise type(exc)(f"{name}: {exc}") from None
    if found.builtin is not None:
        key = registry.get(found.builtin).key
    else:
        key = registry.hold(found.scaffold, f"design {name}", pinned=pinned).key
    nulls = () if found.nulls is None else tuple(np.flatnonzero(found.nulls).tolist())
    block = None if found.block is None else tuple(found.block)
    return OpenedDesign(key, tuple(int(t) for t in found.labels), nulls, block, found.view, name)


def is_design_file(path: str) -> bool:
    """Whether the file at ``path`` is a design file (a ``.json`` whose format is ``lkspace-design``)."""
    if not path.lower().endswith(".json"):
        return False
    try:
        return is_design(json.loads(read_text(path, "design")))
    except (LkspaceError, ValueError, RecursionError):
        return False  # not readable as JSON: the scaffold reader says why


def open_path(registry: Registry, path: str) -> OpenedDesign:
    """Read a design file named on the command line (see :func:`open_text`; its scaffold stays held)."""
    return open_text(registry, read_text(path, "design"), os.path.basename(path), pinned=True)


def open_upload(registry: Registry, filename: str, data: bytes) -> OpenedDesign:
    """Open the bytes of an uploaded design file (see :func:`open_text`)."""
    name = os.path.basename(filename.replace("\\", "/"))[:200] or "design.json"
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        raise ScaffoldError(f"{name}: not a text file (UTF-8 expected)") from None
    return open_text(registry, text, name)
