"""The ``lkspace`` command line: a thin layer over the public API (``docs/cli.md``).

Commands live in their own modules, imported only when run (or when ``--help`` lists
them), and import the heavy libraries they need inside the command.  Every
:class:`~lkspace.errors.LkspaceError` (and every usage error) becomes one line on stderr
and exit status 2; nothing else reaches the user as a traceback.
"""

from __future__ import annotations

import importlib
import sys

import click

from .. import __version__
from ..errors import LkspaceError

COMMANDS = {
    "scaffold": "core:scaffold_cmd",
    "info": "core:info_cmd",
    "trace": "core:trace_cmd",
    "enumerate": "enumerate:enumerate_cmd",
    "solve": "solve:solve_cmd",
    "export": "export:export_cmd",
    "identify": "identify:identify_cmd",
}
"""Command name -> ``module:attribute`` under :mod:`lkspace.cli`."""


class LazyGroup(click.Group):
    """A click group whose commands are imported on first use."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        """Return the command names, in the order of ``COMMANDS`` (without importing them)."""
        return list(COMMANDS)

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        """Import and return the command ``cmd_name``; ``None`` if there is no such command."""
        if cmd_name not in COMMANDS:
            return None
        module, attribute = COMMANDS[cmd_name].split(":")
        return getattr(importlib.import_module(f"{__name__}.{module}"), attribute)


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="lkspace")
def cli() -> None:
    """lkspace: design knots, links and chainmail with twist labels on polygon meshes.

    MESH is a .obj or .json scaffold file or a built-in name (see 'lkspace scaffold
    --help'); left out, commands use the built-in tetrahedron.
    """


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
