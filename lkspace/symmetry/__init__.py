"""Symmetry: the rigid motions mapping a scaffold onto itself, and how they act on edges.

:mod:`~lkspace.symmetry.pointset` finds the isometries of a finite scaffold's vertex
positions (KD-tree, linear memory); :mod:`~lkspace.symmetry.finite` lifts them to
incidence automorphisms; :mod:`~lkspace.symmetry.motions` handles periodic scaffolds
(igraph candidates, lattice point group); :mod:`~lkspace.symmetry.group` assembles
:class:`SymmetryGroup` and its signed edge permutations, which design spaces and solve use.
"""
