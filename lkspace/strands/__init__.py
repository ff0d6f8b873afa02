"""Strands: the port model, the strand walk, traces and whether they hold together.

:mod:`~lkspace.strands.ports` (label-independent arrays) -> :mod:`~lkspace.strands.walk`
(the compiled walk) -> :mod:`~lkspace.strands.tracing` (:func:`trace`, :class:`Trace`),
with :mod:`~lkspace.strands.holding_together` deciding whether strands hold together.
"""
