"""``lkspace enumerate MESH --dna NM``: the command of :mod:`~lkspace.cli.enumerate` restricted to DNA-buildable designs.

With ``--dna NM`` (nm per mesh unit) the catalog holds every label assignment within
``--dna-window`` half turns of each edge's natural twist at that scale whose strands run
antiparallel (:mod:`lkspace.catalog.dna_catalog`, ``docs/dna.md``): one Parquet file, one
row per assignment (no symmetry reduction), its ``lkspace`` metadata recording the scale
and windows so that ``lkspace verify`` recomputes the rows.  ``--components``,
``--max-designs``, ``--count-only`` and ``--identify`` apply as usual; the options that
choose labels, symmetry or how a large walk runs are refused.
"""

from __future__ import annotations

import contextlib
import time
from typing import Any

import click
from click.core import ParameterSource

from ..errors import UsageError
from ..words import plural
from .common import Context, emit, load_mesh, print_rows
from .dna_options import DNA_OPTIONS
from .enumerate import enumerate_cmd as plain_enumerate

DNA_KEEPS = {"mesh", "weld", "output", "components", "max_designs", "count_only", "identify", "as_json"}
"""Parameters of the plain enumerate that a DNA catalog reads; any other one given is refused."""

WHY = {
    "labels_spec": "each edge's labels are its window about its natural twist (--dna-window)",
    "symmetry": "it lists every buildable assignment (symmetry none: each edge's window depends on its length)",
    "no_zero": "its labels are all positive",
    "invariant": "it lists every buildable assignment, with no symmetry",
    "tolerance": "it lists every buildable assignment, with no symmetry",
    "mode": "its rows are designs, one per buildable assignment",
    "sample": "its rows are designs, one per buildable assignment",
    "seed": "its rows are designs, one per buildable assignment",
}
"""Why an option is refused with ``--dna`` (default: a DNA catalog is one file, written in this process)."""


def dna_enumerate(ctx: Context, kw: dict[str, Any], scale: float, window: float) -> None:
    """Write or count the DNA catalog and report it as enumerate does (``-o``: under the catalog's lock)."""
    output = None if kw["count_only"] else kw["output"]
    with contextlib.ExitStack() as held:
        if output is not None:  # a bad -o fails, and a second run on it stops, before any work
            from ..catalog.lock import catalog_lock
            from ..catalog.remote import remote_url
            from ..catalog.transaction import catalog_target

            if remote_url(output) is not None:
                raise UsageError(f"-o {output}: a --dna catalog is one local .parquet file")
            target = catalog_target(output, (kw["mesh"],), "-o")
            held.enter_context(catalog_lock(target.lock, target.shown))  # held again by the writer: a no-op
        _dna_run(ctx, kw, scale, window, output)


def _dna_run(ctx: Context, kw: dict[str, Any], scale: float, window: float, output: str | None) -> None:
    """Load the mesh, then write (``output``) or count the DNA catalog and report it."""
    import numpy as np

    from ..catalog.dna_catalog import DnaReport, count_dna, write_dna_catalog
    from ..catalog.dna_rows import dna_space
    from ..dna.search import natural_twist

    if kw["identify"] and output is None:
        raise UsageError("--identify names the rows of a written catalog: give -o CATALOG.parquet")
    scaffold = load_mesh(ctx, kw["mesh"])
    started = time.perf_counter()
    space = dna_space(scaffold, scale, window)
    components, max_designs = kw["components"], kw["max_designs"]
    if output is None:
        totals = count_dna(space, components, max_designs)
        if not kw["count_only"]:
            ctx.notes["note"] = "no -o given: counted, nothing written"
    else:
        totals = write_dna_catalog(space, output, components, max_designs)
    identified = None
    if output is not None and kw["identify"]:
        from ..catalog.identified import identify_catalog

        identified = identify_catalog(output, scaffold)
    natural = np.round(natural_twist(scaffold, scale, space.setting.bp_per_turn), 3)
    report = DnaReport(
        totals,
        space.setting.to_json(),
        tuple(natural.tolist()),
        len(space.patterns),
        round(time.perf_counter() - started, 3),
        identified,
    )

    def human() -> None:
        windows = sorted({(lo, hi) for lo, hi in space.setting.labels})
        shown = ", ".join(f"{lo}..{hi}" if lo < hi else str(lo) for lo, hi in windows)
        click.echo(f"{scaffold.name} at {scale:g} nm per unit (DNA, window {window:g}): labels {shown}, symmetry none")
        rows = [
            ("designs", f"{totals.designs:,}"),
            ("assignments", f"{totals.assignments:,}"),
            *[(f"  {plural(int(k), 'component')}", f"{v:,}") for k, v in totals.by_components.items()],
            ("written", str(totals.written or "- (count only; give -o FILE to write)")),
        ]
        if identified is not None:
            top = ", ".join(f"{k} ({v})" for k, v in list(identified.names.items())[:6])
            rows.append(("identified", f"{identified.named:,} of {identified.rows:,} named: {top}"))
        print_rows([*rows, ("seconds", str(report.seconds))])

    emit(ctx, report.to_json(), human)


def dna_callback(**kw: Any) -> None:
    """Send ``--dna`` runs to :func:`dna_enumerate`, the rest to the plain enumerate."""
    scale, window = kw.pop("dna_scale"), kw.pop("dna_window")
    if scale is None:
        if window is not None:
            raise UsageError("--dna-window needs --dna NM")
        assert plain_enumerate.callback is not None
        plain_enumerate.callback(**kw)
        return
    click_ctx = click.get_current_context()
    for param in plain_enumerate.params:
        name = param.name or ""
        given = click_ctx.get_parameter_source(name) not in (ParameterSource.DEFAULT, None)
        if name in DNA_KEEPS or not given or (name == "symmetry" and kw[name] == "none"):
            continue
        flag = next((o for o in param.opts if o.startswith("--")), param.opts[0])
        why = WHY.get(name, "a --dna catalog is one file, written in this process")
        raise UsageError(f"{flag} does not apply to a --dna catalog: {why}")
    dna_enumerate(Context(kw["as_json"]), kw, scale, 1.0 if window is None else window)


enumerate_cmd = click.Command(
    name=plain_enumerate.name,
    params=[*plain_enumerate.params[:-1], *DNA_OPTIONS, plain_enumerate.params[-1]],
    callback=dna_callback,
    help=(plain_enumerate.help or "").replace(
        "      lkspace enumerate cube --labels -1..1 --invariant C3:vertex=0 -o cube-c3.parquet\n",
        "      lkspace enumerate cube --labels -1..1 --invariant C3:vertex=0 -o cube-c3.parquet\n"
        "      lkspace enumerate cube --dna 5.3 -o cube-dna.parquet     # buildable as B-DNA (docs/dna.md)\n",
    ),
    context_settings=plain_enumerate.context_settings,
)
