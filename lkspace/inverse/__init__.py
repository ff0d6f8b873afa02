"""Inverse design: twist labels with exactly N components.

:mod:`~lkspace.inverse.query` (what a design must satisfy) ·
:mod:`~lkspace.inverse.constructive` (spanning-tree fast path) ·
:mod:`~lkspace.inverse.local_search` (heuristic where the fast path gets stuck) ·
:mod:`~lkspace.inverse.cpsat_model` (the exact CP-SAT model) ·
:mod:`~lkspace.inverse.pipeline` (:func:`solve`: all of them in turn, every answer re-traced).
"""
