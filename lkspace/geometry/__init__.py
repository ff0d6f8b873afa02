"""Geometry: strands of a labelled scaffold as 3D curves, checked to be an embedding.

:mod:`~lkspace.geometry.tracks` (per face-side tracks, helper curves) ->
:mod:`~lkspace.geometry.realization` (:func:`realize`, :class:`Realization`), checked by
:mod:`~lkspace.geometry.clearance` (smallest distance between distinct pieces).
"""
