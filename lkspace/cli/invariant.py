"""``lkspace enumerate --invariant SUBGROUP``: the designs fixed by a subgroup of the symmetries."""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import TooLargeError, UsageError
from ..model.scaffold import Scaffold
from ..symmetry.group import SymmetryMode
from ..words import plural
from .common import Context, emit, print_rows, symmetry_tolerance, usage_errors


def refuse_with_invariant(**given: object) -> None:
    """One usage line naming the first option ``--invariant`` does not combine with."""
    for name, value in given.items():
        if value:
            raise UsageError(f"--invariant writes one catalog file of designs; it does not combine with --{name}")


@dataclass(frozen=True)
class InvariantOutput:
    """What ``enumerate --invariant`` makes of the designs it finds.

    A catalog at ``output`` (``None``: a count), or a count anyway with ``count_only``; the
    designs with ``components`` strands only (``None``: all), at most ``max_designs``.
    """

    output: str | None
    count_only: bool
    components: int | None
    max_designs: int | None


def run_invariant(
    ctx: Context,
    scaffold: Scaffold,
    labels: np.ndarray,
    symmetry: SymmetryMode,
    subgroup: str,
    no_zero: bool,
    made: InvariantOutput,
) -> None:
    """Count or write the symmetric designs and report them (JSON or a table)."""
    output, count_only, components, max_designs = made.output, made.count_only, made.components, made.max_designs
    from ..catalog.symmetric import count_invariant, write_invariant_catalog
    from ..design.invariant import make_invariant_space

    with usage_errors():
        space = make_invariant_space(scaffold, labels, symmetry, subgroup, no_zero, symmetry_tolerance())
    started = time.perf_counter()
    payload: dict[str, Any]
    if count_only or output is None:
        payload = count_invariant(space, components)
        if max_designs is not None and payload["designs"] is not None:
            payload["designs"] = min(payload["designs"], max_designs)
        payload.update(
            group_order=space.group.mode_order(space.mode), written=None, symmetry=symmetry, label_set=labels.tolist()
        )
        if output is None and not count_only:
            ctx.notes["note"] = "no -o given: counted, nothing written"
    else:
        try:
            payload = write_invariant_catalog(space, output, components, max_designs)
        except TooLargeError as exc:  # the other way ahead, in flags
            raise TooLargeError(f"{exc}, or count them with --count-only") from None
        payload["written"] = payload.pop("output")
    payload["mode"] = "designs"
    payload["seconds"] = round(time.perf_counter() - started, 3)

    def human() -> None:
        from rich.console import Console

        inv = payload["invariant"]
        con = Console(highlight=False)
        con.print(
            f"{scaffold.name}: label set {labels.tolist()}, designs fixed by {subgroup} (order {inv['order']}), "
            f"up to its normalizer in {symmetry} (order {inv['normalizer_order']})"
        )
        designs = payload["designs"]
        rows = [
            ("edge orbits", f"{inv['edge_orbits']} ({inv['zero_orbits']} forced to 0)"),
            ("fixed assignments", f"{payload['fixed_assignments']:,}"),
            ("designs", "-" if designs is None else f"{designs:,}"),
        ]
        rows += [(f"  {plural(int(k), 'component')}", f"{v:,}") for k, v in (payload["by_components"] or {}).items()]
        rows.append(("written", str(payload.get("written") or "- (count only; give -o FILE to write)")))
        if payload.get("note"):
            rows.append(("note", str(payload["note"])))
        rows.append(("seconds", str(payload["seconds"])))
        print_rows(rows)

    emit(ctx, payload, human)
