"""Knots: planar diagrams of realized strands, the KnotInfo/LinkInfo tables, and naming.

:mod:`~lkspace.knots.diagram` (projection, PD code) ·
:mod:`~lkspace.knots.tables` (indexed tables) ·
:mod:`~lkspace.knots.naming` (PD code -> name) ·
:mod:`~lkspace.knots.recognition` (:func:`identify`: realize, project, name) ·
:mod:`~lkspace.knots.identification` (the records it hands on, to and from JSON).
"""
