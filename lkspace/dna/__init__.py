"""DNA strands of a design: antiparallel B-DNA duplexes along the edges, written for oxDNA and oxView.

:mod:`~lkspace.dna.model` decides whether a design is buildable and orients its strands
5' -> 3'; :mod:`~lkspace.dna.helix` places the nucleotides; :mod:`~lkspace.dna.sequences`
chooses the bases; :mod:`~lkspace.dna.oxdna` writes the files.  ``docs/dna.md`` explains
the model.
"""
