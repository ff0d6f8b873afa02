"""Design to a target: knot and link types asked for by name or by linking matrix, and atlases.

:mod:`~lkspace.linktypes.spelling` (the one spelling of table names; ``Chirality``) ·
:mod:`~lkspace.linktypes.names` (a type name -> :class:`~lkspace.linktypes.names.LinkType`) ·
:mod:`~lkspace.linktypes.linking` (linking matrices up to renumbering) ·
:mod:`~lkspace.linktypes.screen` (cheap filters, then identification, for one design) ·
:mod:`~lkspace.linktypes.candidates` (designs in order of simplicity) ·
:mod:`~lkspace.linktypes.search` (:func:`~lkspace.linktypes.search.solve_target`) ·
:mod:`~lkspace.linktypes.atlas` (:func:`~lkspace.linktypes.atlas.atlas`: every type of a space) ·
:mod:`~lkspace.linktypes.gallery` (the atlas written: Parquet, Markdown, pictures) ·
:mod:`~lkspace.linktypes.records`, :mod:`~lkspace.linktypes.answers` (the payloads as frozen wire records).
"""
