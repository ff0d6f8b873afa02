"""Design spaces: residue classes under symmetry, the walk over designs, exact counts.

:mod:`~lkspace.design.space` (:class:`DesignSpace`, residue classes) ->
:mod:`~lkspace.design.walk` (canonical designs, class by class) ·
:mod:`~lkspace.design.counting` (Burnside counts, :func:`count_designs`) ·
:mod:`~lkspace.design.spanning` (one-component seeds from dual spanning trees).
"""
