"""``lkspace verify``: check a catalog whole before other tools read it (docs/catalog.md)."""

from __future__ import annotations

import click

from ..words import plural
from .common import Context, emit, json_option


@click.command("verify")
@click.argument("catalog", metavar="CATALOG.parquet")
@json_option
def verify_cmd(catalog: str, as_json: bool) -> None:
    """Check that CATALOG is whole and unaltered: manifest, every part's footer and checksum.

    pandas, pyarrow and Dask read whatever Parquet files a folder holds; lkspace's own
    readers check a catalog each time.  Run this before reading a catalog with other
    tools: a damaged, truncated, swapped, missing, extra or foreign part, or an unknown
    format version, is one error line and exit status 1.

    \b
    Examples:
      lkspace verify cube.parquet
      lkspace verify cube.parquet --json
    """
    from ..catalog.verify import verify_catalog

    ctx = Context(as_json)
    found = verify_catalog(catalog)
    emit(
        ctx,
        found.to_dict(),
        lambda: click.echo(
            f"{catalog}: intact: {found.rows:,} rows in {plural(found.parts, 'part')} of {found.scaffold}, "
            f"format version {found.format_version} (checked: {found.checks})"
        ),
    )
