"""The ``lkspace`` command line: a thin layer over the public API.

Every :class:`~lkspace.errors.LkspaceError` (and every usage error) becomes one line on
stderr and exit status 2; nothing else reaches the user as a traceback.
"""

from __future__ import annotations

import sys

import click

from .. import __version__
from ..errors import LkspaceError
from .core import info_cmd, scaffold_cmd, trace_cmd


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="lkspace")
def cli():
    """lkspace: design knots, links and chainmail with twist labels on polygon meshes.

    MESH is a .obj or .json scaffold file or a built-in name (see 'lkspace scaffold
    --help'); left out, commands use the built-in tetrahedron.
    """


for command in (scaffold_cmd, info_cmd, trace_cmd):
    cli.add_command(command)


def _register_optional():
    """Commands living in their own modules (added as the product grows)."""
    import importlib

    for module, name in (
        ("enumerate", "enumerate_cmd"),
        ("solve", "solve_cmd"),
        ("export", "export_cmd"),
        ("identify", "identify_cmd"),
    ):
        try:
            mod = importlib.import_module(f"{__name__}.{module}")
        except ModuleNotFoundError as exc:
            if exc.name != f"{__name__}.{module}":
                raise
            continue
        cli.add_command(getattr(mod, name))


_register_optional()


def main(argv: list[str] | None = None) -> int:
    """Run the command line; return the exit status."""
    try:
        cli.main(args=argv, prog_name="lkspace", standalone_mode=False)
    except LkspaceError as exc:
        click.echo(f"lkspace: error: {exc}", err=True)
        return 2
    except click.exceptions.Abort:
        click.echo("lkspace: aborted", err=True)
        return 130
    except click.ClickException as exc:
        click.echo(f"lkspace: error: {exc.format_message()}", err=True)
        return exc.exit_code if exc.exit_code else 2
    except click.exceptions.Exit as exc:
        return exc.exit_code
    except KeyboardInterrupt:
        click.echo("lkspace: interrupted", err=True)
        return 130
    except BrokenPipeError:
        return 1
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
