"""Formats: strand geometry written to files, one module per file type (see :mod:`~lkspace.formats.registry`)."""
