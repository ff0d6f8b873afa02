"""The model: the scaffold value type, lattices, radial order, and parsing of label specs.

Nothing here depends on the rest of lkspace; everything else builds on it.
"""
