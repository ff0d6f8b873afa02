"""Checks on the files lkspace reads and writes, made before any work is done.

Inputs must be regular files (a FIFO or a device would block or never end); outputs
must be writable files in an existing folder, never a device or a folder, and never a
symbolic link: lkspace does not write through a link (the file it points to would be
replaced without a word), so an output named by a link is refused.  An output is never one
of the command's inputs (the same file by any name: a symlink or a hard link too), and
never a name that is only an extension (``.obj`` would be a hidden file).
"""

from __future__ import annotations

import os
import stat
from collections.abc import Iterable

from ..errors import ExportError, ScaffoldError


def input_file(path: str | os.PathLike[str], what: str = "input") -> str:
    """Return ``path`` if it names a readable regular file; raise a one-line error otherwise."""
    text = os.fspath(path)
    try:
        mode = os.stat(text).st_mode
    except FileNotFoundError:
        raise ScaffoldError(f"{text}: no such {what} file") from None
    except OSError as exc:
        raise ScaffoldError(f"{text}: cannot read {what}: {exc.strerror}") from None
    if stat.S_ISDIR(mode):
        raise ScaffoldError(f"{text}: is a folder, not a {what} file")
    if not stat.S_ISREG(mode):
        raise ScaffoldError(f"{text}: not a regular file (a FIFO, socket or device); give a {what} file")
    if not os.access(text, os.R_OK):
        raise ScaffoldError(f"{text}: cannot read {what}: permission denied")
    return text


def output_file(
    path: str | os.PathLike[str], extensions: tuple[str, ...] = (), inputs: Iterable[str | None] = ()
) -> str:
    """Return the file to write for output ``path``: checked, its folders' symlinks resolved.

    ``extensions`` (lower case, with the dot) are the ones the format may have; another
    extension is an error naming them.  The folder must exist and be writable; an
    existing target must be a regular file and none of ``inputs`` (paths the command
    reads; names of no file are ignored).
    """
    text = os.fspath(path)
    if not text.strip():
        raise ExportError("output path is empty")
    if text.endswith(("/", os.sep)):
        raise ExportError(f"{text}: output path names a folder; give a file name")
    only_extension(text, extensions)
    not_a_link(text)
    not_an_input(text, inputs)
    target = os.path.realpath(text)
    if os.path.lexists(target):
        mode = os.stat(target).st_mode
        if stat.S_ISDIR(mode):
            raise ExportError(f"{text}: is a folder; give a file name")
        if not stat.S_ISREG(mode):
            raise ExportError(f"{text}: is a device, FIFO or socket, not a file lkspace may replace")
    output_folder(os.path.dirname(target) or ".", text)
    ext = os.path.splitext(text)[1].lower()
    if extensions and ext not in extensions:
        raise ExportError(
            f"{text}: extension {ext or '(none)'!r} does not match the format; use {', '.join(extensions)}"
        )
    return target


def output_folder(folder: str, shown: str | None = None) -> None:
    """Raise unless ``folder`` exists, is a folder and is writable (``shown``: the path to name)."""
    name = shown or folder
    if not os.path.exists(folder):
        raise ExportError(f"{name}: folder {folder} does not exist")
    if not os.path.isdir(folder):
        raise ExportError(f"{name}: {folder} is not a folder")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise ExportError(f"{name}: cannot write in folder {folder} (permission denied)")


def not_a_link(path: str) -> None:
    """Raise if ``path`` (its last name; links among its folders are fine) is a symbolic link, dangling or not."""
    bare = path.rstrip("/" + os.sep) or path
    if os.path.islink(bare):
        raise ExportError(
            f"{path}: is a symbolic link (to {os.readlink(bare)}); lkspace does not write through links, "
            "so the file it points to is not replaced: give that path itself, or remove the link"
        )


def only_extension(path: str, extensions: Iterable[str]) -> None:
    """Raise if the file name of ``path`` is only one of ``extensions`` (``.parquet``: a hidden file, no name)."""
    name = os.path.basename(path.rstrip("/" + os.sep)).lower()
    if name in extensions:
        raise ExportError(f"{path}: a name that is only an extension; give a name such as design{name}")


def same_file(a: str, b: str) -> bool:
    """Whether ``a`` and ``b`` are the same existing file or folder (through symlinks and hard links)."""
    try:
        return os.path.samefile(a, b)
    except (OSError, ValueError):
        return False


def not_an_input(output: str, inputs: Iterable[str | None]) -> None:
    """Raise if ``output`` is one of ``inputs`` (by any name); ``None`` and names of no file are skipped."""
    for source in inputs:
        if source is not None and same_file(output, source):
            raise ExportError(
                f"{output}: is the input {source}; lkspace never writes over its input: choose another output"
            )
