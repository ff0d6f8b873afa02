"""Catalogs: the only code that knows Arrow and Parquet.

:mod:`~lkspace.catalog.schema` (columns, versioned) ·
:mod:`~lkspace.catalog.batches` (designs -> record batches) ·
:mod:`~lkspace.catalog.listing` (:func:`designs`, batches in memory) ·
:mod:`~lkspace.catalog.writer` / :mod:`~lkspace.catalog.reader` (one Parquet file) ·
:mod:`~lkspace.catalog.shards` (whole runs: shards, jobs, resume) ·
:mod:`~lkspace.catalog.metadata` / :mod:`~lkspace.catalog.records` (the wire formats as records) ·
:mod:`~lkspace.catalog.identified` (knot/link columns).  Users read ``docs/catalog.md``.
"""
