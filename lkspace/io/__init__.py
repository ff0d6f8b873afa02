"""Readers and writers of scaffolds: OBJ and the lkspace scaffold file (JSON); atomic writes.

:func:`~lkspace.io.sources.load` takes a scaffold, a path or a built-in name;
:func:`~lkspace.io.files.read` and :func:`~lkspace.io.files.write` pick the format by
extension; :mod:`~lkspace.io.atomic` writes every file under a temporary name first;
:func:`weld` merges vertices closer than a tolerance (:mod:`lkspace.io.weld`);
:func:`~lkspace.io.twists.parse_twist` reads a ``--twist`` that may name a twist file.
"""

from .files import read, write
from .sources import load
from .weld import weld

__all__ = ["load", "read", "weld", "write"]
