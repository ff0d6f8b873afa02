"""Design to a target: knot and link types asked for by name or by linking matrix, and atlases.

:mod:`~lkspace.target.names` (a type name -> :class:`~lkspace.target.names.Target`) ·
:mod:`~lkspace.target.linking` (linking matrices up to renumbering) ·
:mod:`~lkspace.target.screen` (cheap filters, then identification, for one design) ·
:mod:`~lkspace.target.candidates` (designs in order of simplicity) ·
:mod:`~lkspace.target.search` (:func:`~lkspace.target.search.solve_target`) ·
:mod:`~lkspace.target.atlas` (:func:`~lkspace.target.atlas.atlas`: every type of a space) ·
:mod:`~lkspace.target.gallery` (the atlas written: Parquet, Markdown, pictures).
"""
