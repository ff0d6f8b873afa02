"""lkspace in Blender: the add-on and the parts of it that need no Blender.

=========================  ==============================================================
:mod:`.meshdata`           a Blender mesh (as arrays) -> a scaffold, edge and corner maps
:mod:`.editing`            what the buttons do to labels: orbit fill, random labels, colours
:mod:`.bundle`             the installable add-on zip (``python -m lkspace.blender build``)
:mod:`.headless`           render a design with Blender (``python -m lkspace.blender render``)
:mod:`.engines`            render engines and which run here (EEVEE needs a GPU; else Cycles)
``addon/``                 the add-on itself (imports ``bpy``; installed as ``lkspace_blender``)
=========================  ==============================================================

Nothing here imports ``bpy`` at import time except ``addon/``; ``docs/blender.md`` is the
user's guide.
"""
