"""Symmetry: the rigid motions mapping a scaffold onto itself, and how they act on edges.

:mod:`~lkspace.symmetry.motions` finds candidate symmetries (igraph) and the rigid motions
realizing them; :mod:`~lkspace.symmetry.group` assembles :class:`SymmetryGroup` and its
signed edge permutations, which design spaces and solve use.
"""
