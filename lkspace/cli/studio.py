"""``lkspace studio``: design knots and links live in the browser (docs/studio.md)."""

from __future__ import annotations

import os

import click

from ..errors import MissingDependencyError
from ..io.sources import reads_builtin
from .common import Context, load_mesh
from .numbers import Count


@click.command("studio")
@click.argument("mesh", required=False, metavar="[MESH|CATALOG.parquet]")
@click.option("--port", type=Count(0, 65535), default=8765, show_default=True, help="Port (0: any free port).")
@click.option(
    "--host", default="127.0.0.1", show_default=True, help="Address to listen on (others than 127.0.0.1 warn)."
)
@click.option("--no-browser", is_flag=True, help="Do not open a browser; just print the URL.")
def studio_cmd(mesh: str | None, port: int, host: str, no_browser: bool) -> None:
    """Open the studio: edit twist labels of MESH in the browser and see the strands at once.

    MESH is a built-in name or a .obj / .json file (read once, here); a design file saved
    by the studio (.json) opens its scaffold, labels and view; a catalog opens its
    scaffold with the catalog browser beside it.  Every edit is traced and realized by
    lkspace; identify and solve run in worker processes.  The studio listens on
    127.0.0.1 unless --host says otherwise, prints its URL and stops on Ctrl-C.

    \b
    Examples:
      lkspace studio cube
      lkspace studio honeycomb:cP@3x3x3 --no-browser --port 0
      lkspace studio cube.parquet
      lkspace studio cube_t1.1.1.1.1.1.1.1.1.1.1.1.design.json
    """
    try:
        import starlette  # noqa: F401
        import uvicorn  # noqa: F401
    except ImportError as exc:
        raise MissingDependencyError(exc.name or "starlette", "studio", "the studio's web server") from None
    from ..catalog.settings import catalog_scaffold
    from ..studio.app import Studio
    from ..studio.browse import Browser
    from ..studio.design_files import is_design_file, open_path
    from ..studio.server import LOCAL, serve
    from .export import is_catalog

    studio = Studio()
    if is_catalog(mesh):
        studio.browser = Browser(mesh)  # the catalog's structure checked here, its parts' bytes as they are read
        scaffold = catalog_scaffold(studio.browser.footer, mesh)
        studio.initial = studio.registry.hold(scaffold, f"catalog {mesh}").key
    elif mesh is not None and not reads_builtin(mesh) and is_design_file(mesh):
        studio.design = open_path(studio.registry, mesh)  # a design file: its scaffold, labels and view
        studio.initial = studio.design.key
    elif mesh is not None and not reads_builtin(mesh) and os.path.lexists(mesh):
        studio.initial = studio.registry.open_file(mesh).key  # the one file the studio reads
    else:
        scaffold = load_mesh(Context(False), mesh)
        studio.initial = studio.registry.hold(scaffold, "built-in", scaffold.name).key
    if host != LOCAL:
        studio.local_only = False
        click.echo(f"lkspace: warning: listening on {host}: anyone who can reach it can use this studio", err=True)

    def ready(url: str) -> None:
        click.echo(f"lkspace studio: {url} (Ctrl-C stops it)")
        if not no_browser:
            import webbrowser

            webbrowser.open(url)

    serve(studio, host, port, ready)
