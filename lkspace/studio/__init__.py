"""The studio: design knots and links live in the browser (``lkspace studio``, ``docs/studio.md``).

A small Starlette app (:mod:`~lkspace.studio.app`) served by uvicorn
(:mod:`~lkspace.studio.server`) and one static page drawing with a vendored three.js
build (``static/``).  The page only draws and edits; every answer comes from the public
API through these modules:

======================================  ==================================================
:mod:`~lkspace.studio.scaffolds`        the scaffolds the page may use (built-in names,
                                        files named on the command line, uploads)
:mod:`~lkspace.studio.designs`          labels -> trace + strand curves (binary), the
                                        embedding check, export to bytes
:mod:`~lkspace.studio.jobs`             identify, relax, solve and exports in worker
                                        processes (cancellable, bounded)
:mod:`~lkspace.studio.lanes`            the line exports wait in; the busy answer (429)
:mod:`~lkspace.studio.browse`           catalog filter / sort / page over Arrow data
:mod:`~lkspace.studio.requests`         every request body as a frozen record (one
                                        validating ``from_json`` each)
:mod:`~lkspace.studio.answers`          every answer and job state as a record (one
                                        ``to_json`` each) or a ``TypedDict`` view
:mod:`~lkspace.studio.wire`             bodies read up to a limit, content types, JSON
                                        errors, the local-host guard
======================================  ==================================================

Nothing here is imported by ``import lkspace`` or ``lkspace --help``.
"""
