"""Write files atomically: to a temporary name beside the target, renamed when complete."""

from __future__ import annotations

import contextlib
import errno
import os
import sys
from collections.abc import Iterator


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str], suffix: str = "") -> Iterator[str]:
    """Yield a temporary path beside ``path``; rename it onto ``path`` on success.

    On error the temporary file is removed and ``path`` is left untouched.  A symlink
    at ``path`` is followed: the file it points to is replaced and the link kept.
    """
    path = os.path.realpath(os.fspath(path))
    directory = os.path.dirname(os.path.abspath(path))
    import tempfile  # here: tempfile imports random, which commands that write nothing need not load

    fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(path) + ".", suffix=suffix or ".tmp", dir=directory)
    os.close(fd)
    try:
        yield tmp
        umask = os.umask(0)
        os.umask(umask)
        if os.path.isfile(tmp):  # mkstemp makes 0600 files: give the usual permissions
            os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.remove(tmp)
        raise


def write_text(path: str | os.PathLike, text: str) -> None:
    """Write ``text`` to ``path`` atomically."""
    with atomic_path(path) as tmp:
        with open(tmp, "w", encoding="utf-8") as fh:
            fh.write(text)


def write_bytes(path: str | os.PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically."""
    with atomic_path(path) as tmp:
        with open(tmp, "wb") as fh:
            fh.write(data)


def remove_path(path: str) -> None:
    """Remove the file or folder ``path`` if it exists."""
    if os.path.isdir(path) and not os.path.islink(path):
        import shutil

        shutil.rmtree(path, ignore_errors=True)
    else:
        with contextlib.suppress(FileNotFoundError):
            os.remove(path)


def _exchange(src: str, dst: str) -> bool:
    """Swap ``src`` and ``dst`` in one step (Linux ``renameat2(RENAME_EXCHANGE)``); ``False`` if unsupported."""
    if not sys.platform.startswith("linux"):
        return False
    import ctypes

    try:
        renameat2 = ctypes.CDLL(None, use_errno=True).renameat2
    except (OSError, AttributeError):  # an old C library
        return False
    at_fdcwd, rename_exchange = -100, 2
    if renameat2(at_fdcwd, os.fsencode(src), at_fdcwd, os.fsencode(dst), rename_exchange) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.EINVAL, errno.ENOSYS, errno.EOPNOTSUPP, errno.EPERM):  # file system or kernel without it
        return False
    raise OSError(err, os.strerror(err), dst)


def replace_path(src: str, dst: str, aside: str) -> None:
    """Put the file or folder ``src`` at ``dst``, then remove what was at ``dst`` before.

    Readers of ``dst`` see the old content or the new, never a mix: files are replaced
    with one rename; a folder (or a file replaced by a folder, or the reverse) is
    swapped with one ``renameat2(RENAME_EXCHANGE)`` on Linux.  Elsewhere the old content
    is first renamed to ``aside`` (a name in the same folder), which leaves ``dst``
    absent for the moment between two renames.
    """
    if not os.path.lexists(dst):
        os.rename(src, dst)
        return
    if os.path.isfile(src) and os.path.isfile(dst):
        os.replace(src, dst)
        return
    if _exchange(src, dst):
        remove_path(src)  # now the old content
        return
    remove_path(aside)
    os.rename(dst, aside)
    os.rename(src, dst)
    remove_path(aside)
