"""Geometry: strands of a labelled scaffold as 3D curves, checked to be an embedding.

:mod:`~lkspace.geometry.params` (the shape :class:`GeometryParams`, the options
:class:`RealizeOptions`, resolved once per mesh) -> :mod:`~lkspace.geometry.tracks` (per
face-side tracks) -> :mod:`~lkspace.geometry.construction` (corner turns and edge
helices) -> :mod:`~lkspace.geometry.realization` (:func:`realize`, :class:`Realization`),
bounded by :mod:`~lkspace.geometry.limits` and checked by
:mod:`~lkspace.geometry.clearance` (smallest distance between distinct pieces).
"""
