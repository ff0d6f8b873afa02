"""``lkspace solve MESH --dna NM``: the command of :mod:`~lkspace.cli.solve` restricted to DNA-buildable designs.

With ``--dna NM`` (nm per mesh unit) the answer comes from :mod:`lkspace.dna.search`: every
label vector within ``--dna-window`` half turns of each edge's natural twist at that scale
whose strands run antiparallel (``docs/dna.md``), with ``--components`` strands or of
``--type`` (either mirror image), up to ``--count``.  The search is exhaustive, so the status
is ``feasible``/``infeasible`` (``--components``) or ``found``/``exhausted`` (``--type``).
"""

from __future__ import annotations

from typing import Any

import click

from ..errors import UsageError
from .common import Context, emit, load_mesh
from .dna_options import DNA_OPTIONS
from .solve import solve_cmd as plain_solve

DNA_KEEPS = {"mesh", "components", "type_name", "count", "as_json"}
"""Parameters of the plain solve that a DNA search reads; any other one set is refused."""


def dna_search(ctx: Context, kw: dict[str, Any], scale: float, window: float) -> None:
    """Search the buildable designs and print them as solve does."""
    import numpy as np

    from ..dna.search import DnaSearchResult, DnaSolution, buildable_designs, natural_twist
    from ..strands.tracing import trace

    if kw["components"] is None and kw["type_name"] is None:
        raise UsageError("--dna: give --components N or --type NAME")
    scaffold = load_mesh(ctx, kw["mesh"])
    wanted = None if kw["type_name"] is None else kw["type_name"].lstrip("m")
    solutions: list[DnaSolution] = []
    for labels in buildable_designs(scaffold, scale, components=kw["components"], window=window):
        name = None
        if wanted is not None:
            import lkspace

            name = lkspace.identify(scaffold, labels).name
            if name is None or name.lstrip("m") != wanted:
                continue
        solutions.append(DnaSolution(tuple(int(x) for x in labels), trace(scaffold, labels).components, name))
        if len(solutions) >= kw["count"]:
            break
    if wanted is None:
        status = "feasible" if solutions else "infeasible"
    else:
        status = "found" if solutions else "exhausted"
    natural = tuple(float(x) for x in np.round(natural_twist(scaffold, scale), 3))
    result = DnaSearchResult(status, tuple(solutions), scale, window, natural)
    lines = [f"{scaffold.name} at {scale:g} nm per unit (DNA, window {window:g}): {status}"]
    lines += [f"  {','.join(map(str, s.labels))}" + (f"  {s.name}" if s.name else "") for s in solutions]
    emit(ctx, result.to_json(), lambda: click.echo("\n".join(lines)))


def dna_callback(**kw: Any) -> None:
    """Send ``--dna`` searches to :func:`dna_search`, the rest to the plain solve."""
    scale, window = kw.pop("dna_scale"), kw.pop("dna_window")
    if scale is None:
        if window is not None:
            raise UsageError("--dna-window needs --dna NM")
        assert plain_solve.callback is not None
        plain_solve.callback(**kw)
        return
    defaults = {p.name: p.default for p in plain_solve.params}
    flags = {p.name: p.opts[0] for p in plain_solve.params}
    for name, value in kw.items():
        if name not in DNA_KEEPS and value not in (None, False, (), defaults.get(name)):
            raise UsageError(f"{flags[name]} is not an option of a --dna search")
    dna_search(Context(kw["as_json"]), kw, scale, 1.0 if window is None else window)


solve_cmd = click.Command(
    name=plain_solve.name,
    params=[*plain_solve.params[:-1], *DNA_OPTIONS, plain_solve.params[-1]],
    callback=dna_callback,
    help=(plain_solve.help or "").rstrip() + "\n      lkspace solve figure-eight --components 1 --dna 6.1\n",
    context_settings=plain_solve.context_settings,
)
