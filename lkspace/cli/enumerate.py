"""``lkspace enumerate``: walk a design space, write a Parquet catalog or count it."""

from __future__ import annotations

import contextlib
import time
from typing import TYPE_CHECKING, Any

import click

from ..catalog.options import Execution, Selection
from ..catalog.plan import MAX_JOBS, MAX_SHARDS
from ..design.space import WALK_MODES, DesignSpace, WalkMode, make_space
from ..errors import CatalogError, TooLargeError, UsageError
from ..symmetry.group import MODES as SYMMETRY_MODES
from ..symmetry.group import SymmetryMode
from ..words import plural
from .common import (
    Context,
    emit,
    json_option,
    label_set,
    labels_option,
    load_mesh,
    mesh_argument,
    print_rows,
    symmetry_facts,
    symmetry_tolerance,
)
from .flags import flags_in
from .numbers import Count

if TYPE_CHECKING:
    from ..catalog.transaction import Destination


def _count_payload(space: DesignSpace, selection: Selection, scheduler: str = "local", jobs: int = 1) -> dict[str, Any]:
    from ..design.counting import census_planned, count_space

    if selection.mode == "designs":
        if census_planned(space, selection.components, scheduler, jobs):  # the cost up front, then progress
            from ..design.census import census_estimate

            estimate = census_estimate(space)
            split = f"; {jobs} workers share it" if jobs > 1 else ""
            click.echo(f"lkspace: note: counting by {estimate}{split}; progress follows", err=True)
        totals = count_space(space, selection.components, scheduler, jobs).to_dict()
        if totals.get("note"):
            totals["note"] = flags_in(totals["note"])
        if selection.max_designs is not None:
            totals["designs"] = min(totals["designs"], selection.max_designs)
        return totals
    from ..catalog.listing import designs  # pyarrow and pandas: only where rows are listed to count them

    rows = 0
    by: dict[str, int] = {}
    sc, tolerance = space.scaffold, space.tolerance
    for df in designs(sc, space.label_set, space.mode, selection=selection, no_zero=space.no_zero, tolerance=tolerance):
        rows += len(df)
        for c, n in df.components.value_counts().items():
            by[str(int(c))] = by.get(str(int(c)), 0) + int(n)
    return {
        "designs": rows,
        "assignments": space.assignments,
        "by_components": dict(sorted(by.items(), key=lambda kv: int(kv[0]))),
    }


def _where_it_ran(
    engine: str, payload: dict[str, Any], counted: bool, identify: bool, output: str | None
) -> str | None:
    """Say where a run on a Dask ``engine`` ran (``None`` for the local scheduler); note it when Dask went unused.

    A census and every part of a sharded, remote or identified catalog are Dask tasks; a
    one-file catalog and a count that needs no census run in this process.
    """
    from ..runtime.schedulers import is_dask

    if not is_dask(engine):
        return None
    from ..catalog.remote import remote_url

    if counted:
        on_dask = str(payload.get("note", "")).startswith("census")
    else:
        on_dask = payload["shards"] > 1 or identify or (output is not None and remote_url(output) is not None)
    if on_dask:
        return "a Dask LocalCluster" if engine == "dask" else f"Dask at {engine}"
    unused = "was not started" if engine == "dask" else "answered but was not used"
    click.echo(
        f"lkspace: note: ran in this process: too small to split into parts, so --scheduler {engine} {unused}", err=True
    )
    return "this process"


@click.command("enumerate")
@mesh_argument
@labels_option
@click.option(
    "--symmetry",
    type=click.Choice(SYMMETRY_MODES),
    default="rotations",
    show_default=True,
    help="Designs related by these rigid motions are one design.",
)
@click.option("-o", "--output", type=click.Path(), help="Catalog to write (.parquet file, or a folder when sharded).")
@click.option(
    "--mode",
    type=click.Choice(WALK_MODES),
    default="designs",
    show_default=True,
    help="One row per design, per residue-class orbit (topology), or per dual spanning tree.",
)
@click.option("--components", type=Count(min=1), metavar="N", help="Keep designs with N components.")
@click.option("--no-zero", is_flag=True, help="Leave out designs with a zero label.")
@click.option("--max-designs", type=Count(min=1), metavar="M", help="Stop after M rows.")
@click.option("--count-only", is_flag=True, help="Print exact totals (Burnside) without writing rows.")
@click.option(
    "--sample",
    type=Count(min=1),
    metavar="N",
    help="spanning-trees mode: sample N uniform spanning trees instead of listing all.",
)
@click.option("--seed", type=Count(min=0), default=0, show_default=True, help="Random seed for --sample.")
@click.option("--jobs", type=Count(1, MAX_JOBS), default=1, show_default=True, help="Parallel worker processes.")
@click.option(
    "--shards",
    type=Count(1, MAX_SHARDS),
    help="Parts of the catalog (default: one per million designs; one file up to a million).",
)
@click.option(
    "--scheduler",
    metavar="local|dask|tcp://HOST:PORT",
    help="Where parts run: this machine's processes (local), a Dask LocalCluster (dask) or a running "
    "Dask scheduler; default $DASK_SCHEDULER_ADDRESS or local.",
)
@click.option("--resume", is_flag=True, help="Keep the verified parts of an interrupted run and do the rest.")
@click.option("--yes", is_flag=True, help="Go ahead with a catalog estimated past 10^8 rows or 2 GB.")
@click.option("--identify", is_flag=True, help="Add knot/link names and invariants to every row (extra [knots]; slow).")
@click.option(
    "--identify-by-key",
    "by_key",
    is_flag=True,
    help="--identify naming by invariant keys only, never in full: designs no table type matches are filed "
    "'not in the tables'; for spaces too big to name (see docs/identify.md).",
)
@click.option(
    "--invariant",
    metavar="SUBGROUP",
    help="Only designs fixed by this subgroup of the symmetries (rotations, C3, C4:face=0, stabilizer:vertex=0, "
    "perm:...), up to its normalizer; see docs/structured.md.",
)
@json_option
def enumerate_cmd(
    mesh: str | None,
    labels_spec: str,
    symmetry: SymmetryMode,
    output: str | None,
    mode: WalkMode,
    components: int | None,
    no_zero: bool,
    max_designs: int | None,
    count_only: bool,
    sample: int | None,
    seed: int,
    jobs: int,
    shards: int | None,
    scheduler: str | None,
    resume: bool,
    yes: bool,
    identify: bool,
    by_key: bool,
    invariant: str | None,
    as_json: bool,
) -> None:
    """Walk the design space of MESH: one row per design up to symmetry.

    \b
    Examples:
      lkspace enumerate tetrahedron --labels -2,2            # 12 designs up to rotation
      lkspace enumerate cube --labels -2..2 -o cube.parquet --jobs 2
      lkspace enumerate cube --count-only --components 1 --no-zero
      lkspace enumerate cube --mode residues -o cube-topology.parquet
      lkspace enumerate cube --labels -2..2 -o cube.parquet --jobs 2 --resume   # after Ctrl-C
      lkspace enumerate cube --labels -2..2 -o s3://bucket/cube --scheduler tcp://head:8786
      lkspace enumerate cube --labels -1..1 --invariant C3:vertex=0 -o cube-c3.parquet

    The representative of each design is the orbit member smallest in (t mod K per
    edge, then t per edge), lexicographically in edge order.
    """
    from ..catalog.transaction import CatalogInterrupted
    from ..runtime.schedulers import check_scheduler, resolve_scheduler

    ctx = Context(as_json)
    engine = resolve_scheduler(scheduler)
    check_scheduler(engine)
    identify = identify or by_key
    selection = Selection(mode, components, max_designs, sample, seed, identify, by_key)
    execution = Execution(jobs, shards, engine, resume, allow_large=yes)
    writes = output is not None and not count_only
    target = _check_before_work(mesh, output if writes else None, selection, execution)
    with contextlib.ExitStack() as held:
        if target is not None:  # the lock before any work: a second run on the same -o stops at once
            from ..catalog.lock import catalog_lock

            held.enter_context(catalog_lock(target.lock, target.shown))
        if invariant is not None:
            from .invariant import InvariantOutput, refuse_with_invariant, run_invariant

            refuse_with_invariant(
                mode=mode != "designs", sample=sample, shards=shards, resume=resume, identify=identify
            )
            refuse_with_invariant(jobs=jobs > 1, scheduler=scheduler)
            return run_invariant(
                ctx,
                load_mesh(ctx, mesh),
                label_set(labels_spec),
                symmetry,
                invariant,
                no_zero,
                InvariantOutput(output, count_only, components, max_designs),
            )
        try:
            scaffold = load_mesh(ctx, mesh)
            labels = label_set(labels_spec)
            space = make_space(scaffold, labels, symmetry, no_zero, symmetry_tolerance())
            facts = symmetry_facts(scaffold) if symmetry != "none" else {}
        except KeyboardInterrupt as exc:  # Ctrl-C or SIGTERM while the symmetry group is computed
            if not writes:
                raise
            code = 128 + getattr(exc, "signum", 2)
            raise CatalogInterrupted(f"interrupted; nothing was written to {output}", code) from None
        started = time.perf_counter()
        if output is None or count_only:
            payload = _count_payload(space, selection, engine, jobs)
            payload.update(
                group_order=space.group_order, written=None, mode=mode, symmetry=symmetry, label_set=labels.tolist()
            )
            if output is None and not count_only:
                ctx.notes["note"] = "no -o given: counted, nothing written"
        else:
            payload = _written(space, output, selection, execution)
        payload["seconds"] = round(time.perf_counter() - started, 3)
        payload.update(facts)
        ran_in = _where_it_ran(engine, payload, not writes, identify, output)
        if ran_in is not None:
            payload["ran_in"] = ran_in
        found = f"group order {space.group_order}"
        if facts:
            found += f"; found {facts['group']} within {facts['symmetry_tolerance']:.3g}"
        headline = f"{scaffold.name}: label set {labels.tolist()}, symmetry {symmetry} ({found}), mode {mode}"
        emit(ctx, payload, lambda: _show(headline, payload))


def _check_before_work(
    mesh: str | None, output: str | None, selection: Selection, execution: Execution
) -> Destination | None:
    """Refuse options that do not go together, and a bad catalog ``output`` (``None``: none written), before any work.

    Returns where a local catalog goes (``None``: a URL, or nothing written).
    """
    from ..runtime.schedulers import is_dask

    url, target = None, None
    if output is not None:  # a bad -o fails before any work
        from ..catalog.remote import check_remote, remote_url  # pyarrow: only when a catalog is written
        from ..catalog.transaction import catalog_target

        url = remote_url(output)
        if url is None:
            target = catalog_target(output, (mesh,), "-o")
        else:
            check_remote(output, "-o")
    sel = selection
    if sel.sample is not None and sel.mode != "spanning-trees":
        raise UsageError("--sample applies to --mode spanning-trees only")
    if output is not None and (execution.shards or 1) > 1 and (sel.mode != "designs" or sel.max_designs is not None):
        raise CatalogError("--shards applies to full design walks (not with --max-designs or other modes)", usage=True)
    if url is not None and url.startswith("memory://") and (execution.jobs > 1 or is_dask(str(execution.scheduler))):
        raise UsageError(f"{url}: memory:// is private to this process; use --jobs 1 and --scheduler local")
    if sel.identify and output is None:
        raise UsageError("--identify names the rows of a written catalog: give -o CATALOG.parquet")
    return target


def _written(space: DesignSpace, output: str, selection: Selection, execution: Execution) -> dict[str, Any]:
    """Write the catalog; return the command's JSON of it (its errors in flags)."""
    from ..catalog.plan import CatalogTooLarge
    from ..catalog.shards import write_catalog
    from ..catalog.transaction import CatalogInterrupted

    try:
        written = write_catalog(space, output, selection=selection, execution=execution)
    except CatalogInterrupted as exc:
        if not exc.resumable:
            raise
        raise CatalogInterrupted(f"{exc.left}: run the same command with --resume to finish", exc.exit_code) from None
    except CatalogTooLarge as exc:  # the way ahead, in flags
        ahead = "use --count-only, filters or a smaller label set"
        if exc.allowable:
            ahead = f"pass --yes to go ahead (or {ahead})"
        raise TooLargeError(f"{exc.estimate}; {ahead}") from None
    payload = written.to_dict()
    payload["written"] = payload.pop("output")
    return payload


def _show(headline: str, payload: dict[str, Any]) -> None:
    """Print the ``headline`` and the totals of ``payload`` as a table (the command's human output)."""
    from rich.console import Console

    con = Console(highlight=False)
    con.print(headline)
    rows: list[tuple[str, str]] = []
    rows.append(("designs", f"{payload['designs']:,}"))
    rows.append(("assignments", f"{payload['assignments']:,}"))
    for k, v in (payload["by_components"] or {}).items():
        rows.append((f"  {plural(int(k), 'component')}", f"{v:,}"))
    rows.append(("written", str(payload.get("written") or "- (count only; give -o FILE to write)")))
    if "identified" in payload:
        identified = payload["identified"]
        top = ", ".join(f"{k} ({v})" for k, v in list(identified["names"].items())[:6])
        rows.append(("identified", f"{identified['named']:,} of {identified['rows']:,} named: {top}"))
    if "ran_in" in payload:
        rows.append(("ran in", payload["ran_in"]))
    rows.append(("seconds", str(payload["seconds"])))
    print_rows(rows)
