"""The ``lkspace`` command line: a thin layer over the public API (``docs/cli.md``).

Commands live in their own modules, imported only when run (or when ``--help`` lists
them), and import the heavy libraries they need inside the command.  Every
:class:`~lkspace.errors.LkspaceError` (and every usage error) becomes one line on stderr
and its exit status (1 bad data, 2 bad usage); nothing reaches the user as a traceback.
"""

from __future__ import annotations

import difflib
import importlib
import json
import os
import sys
import warnings

import click

from ..errors import LkspaceError, LkspaceWarning
from ..runtime.progress import install, stderr_reporter
from ..runtime.workers import INTERRUPTED, Terminated, exit_now, interrupt_signals
from .flags import flags_in, in_flags

COMMANDS = {
    "scaffold": "core:scaffold_cmd",
    "info": "core:info_cmd",
    "trace": "core:trace_cmd",
    "enumerate": "dna_enumerate:enumerate_cmd",
    "solve": "dna_solve:solve_cmd",
    "export": "dna_export:export_cmd",
    "identify": "identify:identify_cmd",
    "atlas": "atlas:atlas_cmd",
    "lookup": "lookup:lookup_cmd",
    "construct": "construct:construct_cmd",
    "surfaces": "surfaces:surfaces_cmd",
    "motifs": "motifs:motifs_cmd",
    "verify": "verify:verify_cmd",
    "studio": "studio:studio_cmd",
}
"""Command name -> ``module:attribute`` under :mod:`lkspace.cli`."""

SUMMARIES = {
    "scaffold": "Write the built-in scaffold NAME (or convert FILE, .obj or .json) to a file.",
    "info": "Show counts, edge-degree histogram, boundary and non-manifold edges, symmetry of MESH.",
    "trace": "Trace the strands of MESH labelled by --twist.",
    "enumerate": "Walk the design space of MESH: one row per design up to symmetry.",
    "solve": "Find twist labels on MESH giving exactly --components strands (or a --type), or prove none exist.",
    "export": "Realize the strands of MESH labelled by --twist and write them to -o FILE.",
    "identify": "Name the knot or link that MESH labelled by --twist realizes.",
    "atlas": "List every knot and link type the designs of MESH with labels SET realize.",
    "lookup": "Find the simplest designs of the knot or link type NAME in the shipped atlas.",
    "construct": "Write a scaffold file with twist labels whose strands are the knot or link TYPE.",
    "surfaces": "Choose cycles of GRAPH as faces, each edge on --per-edge faces; list the results up to automorphism.",
    "motifs": "Repeat a motif (labels on a block of cells) over a supercell of the periodic MESH.",
    "verify": "Check that CATALOG is whole and unaltered: manifest, every part's footer and checksum.",
    "studio": "Open the studio: edit twist labels of MESH in the browser and see the strands at once.",
}
"""Command name -> the first paragraph of its help, which ``lkspace --help`` lists without
importing the command (its module imports numpy); ``tests/test_cli.py`` keeps them equal."""


class LazyGroup(click.Group):
    """A click group whose commands are imported on first use."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        """Return the command names, in the order of ``COMMANDS`` (without importing them)."""
        return list(COMMANDS)

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        """List the commands as click does, their summaries from ``SUMMARIES`` (a command without one is imported)."""
        commands = [
            click.Command(n, help=SUMMARIES[n]) if n in SUMMARIES else self.get_command(ctx, n) for n in COMMANDS
        ]
        limit = formatter.width - 6 - max(map(len, COMMANDS))
        with formatter.section("Commands"):
            formatter.write_dl([(c.name or "", c.get_short_help_str(limit)) for c in commands if c is not None])

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        """Import and return the command ``cmd_name``; ``None`` if there is no such command."""
        if cmd_name not in COMMANDS:
            return None
        module, attribute = COMMANDS[cmd_name].split(":")
        return getattr(importlib.import_module(f"{__name__}.{module}"), attribute)

    def resolve_command(
        self, ctx: click.Context, args: list[str]
    ) -> tuple[str | None, click.Command | None, list[str]]:
        """Resolve ``args[0]`` as click does; an unknown name names the closest commands (``enumrate``)."""
        name = args[0]
        if name not in COMMANDS and not name.startswith("-"):
            close = difflib.get_close_matches(name, list(COMMANDS), n=3, cutoff=0.6)
            hint = f"; did you mean {' or '.join(repr(c) for c in close)}?" if close else ""
            raise click.UsageError(f"no such command {name[:40]!r}{hint} ('lkspace --help' lists them)", ctx)
        return super().resolve_command(ctx, args)


def _show_version(ctx: click.Context, param: click.Parameter, value: bool) -> None:
    """Print ``lkspace, version X`` and stop (as ``click.version_option``; the version is read only when asked)."""
    if not value or ctx.resilient_parsing:
        return
    from .. import __version__  # importlib.metadata: tens of milliseconds every other command need not pay

    click.echo(f"lkspace, version {__version__}")
    ctx.exit()


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.option(
    "--version",
    is_flag=True,
    expose_value=False,
    is_eager=True,
    callback=_show_version,
    help="Show the version and exit.",
)
def cli() -> None:
    """lkspace: design knots, links and chainmail with twist labels on polygon meshes.

    MESH is a .obj or .json scaffold file or a built-in name (see 'lkspace scaffold
    --help'); left out, commands use the built-in tetrahedron.
    """


def main(argv: list[str] | None = None) -> int:
    """Run the command line; return the exit status.

    Errors never reach Python's default handler: each becomes one line on stderr (and,
    under ``--json``, an ``{"error": {...}}`` object on stdout) and an exit status of 1
    (bad data), 2 (bad usage), 130 (Ctrl-C), 143 (SIGTERM) or 70 (a bug in lkspace; set
    ``LKSPACE_DEBUG=1`` for the traceback).  Run as the program (``argv`` left out), an
    interrupted command ends the process at once (:func:`~lkspace.runtime.workers.exit_now`).
    """
    code = _run(sys.argv[1:] if argv is None else list(argv))
    if argv is None and code in INTERRUPTED:  # the program, not a call from Python: stop now
        exit_now(code)
    return code


def _run(args: list[str]) -> int:
    """Run the command line on ``args``; return the exit status (see :func:`main`)."""
    as_json = "--json" in args[: args.index("--")] if "--" in args else "--json" in args
    install(stderr_reporter())
    with warnings.catch_warnings(), interrupt_signals():  # SIGTERM stops a command as Ctrl-C does
        warnings.simplefilter("always", LkspaceWarning)  # shown as a line even where warnings are errors
        warnings.showwarning = _show_warning
        try:
            cli.main(args=args, prog_name="lkspace", standalone_mode=False)
            sys.stdout.flush()  # a full disk at stdout fails here, inside the error handling
        except LkspaceError as exc:
            interrupt = _interrupt_behind(exc)  # e.g. Ctrl-C while an optional package imports
            if interrupt is not None:
                return _interrupted(as_json, interrupt)
            return _fail(as_json, type(exc).__name__, in_flags(exc), exc.exit_code)
        except (click.exceptions.Abort, KeyboardInterrupt) as exc:  # click turns KeyboardInterrupt into Abort
            return _interrupted(as_json, _interrupt_behind(exc))
        except click.exceptions.NoArgsIsHelpError as exc:  # bare ``lkspace``: the help as it is, exit 2
            click.echo(exc.ctx.get_help())
            return 2
        except click.ClickException as exc:
            return _fail(as_json, "UsageError", exc.format_message(), exc.exit_code or 2)
        except click.exceptions.Exit as exc:
            return exc.exit_code
        except BrokenPipeError:  # the reader left (``| head``): stop quietly, as other tools do
            _drop_stdout()
            return 1
        except OSError as exc:  # a full disk, a lost mount: the system's words, the file named
            where = f"{exc.filename}: " if exc.filename else ""
            return _fail(as_json, "OSError", f"{where}{exc.strerror or exc}", 1)
        except MemoryError:
            return _fail(as_json, "MemoryError", "out of memory; try a smaller input or label set", 1)
        except Exception as exc:
            interrupt = _interrupt_behind(exc)  # e.g. a compiled kernel reports Ctrl-C as a SystemError
            if interrupt is not None:
                return _interrupted(as_json, interrupt)
            if os.environ.get("LKSPACE_DEBUG"):
                raise
            message = f"internal error ({type(exc).__name__}: {exc}); please report it (LKSPACE_DEBUG=1 shows where)"
            return _fail(as_json, "InternalError", message, 70)
        finally:
            install(None)
    return 0


def _interrupt_behind(exc: BaseException) -> KeyboardInterrupt | None:
    """Return the KeyboardInterrupt (or SIGTERM's :class:`Terminated`) that caused ``exc``, if any."""
    seen: set[int] = set()
    cause: BaseException | None = exc
    while cause is not None and id(cause) not in seen:
        if isinstance(cause, KeyboardInterrupt):
            return cause
        seen.add(id(cause))
        cause = cause.__cause__ or cause.__context__
    return None


def _interrupted(as_json: bool, interrupt: KeyboardInterrupt | None) -> int:
    """Report an interrupt and return its exit status.

    A catalog run's interrupt carries its own line (how to resume) and ``exit_code``;
    otherwise ``interrupted`` with 130 (Ctrl-C) or ``terminated`` with 143 (SIGTERM).
    """
    terminated = isinstance(interrupt, Terminated)
    code = getattr(interrupt, "exit_code", 143 if terminated else 130)
    message = str(interrupt) or ("terminated" if terminated else "interrupted")
    return _fail(as_json, "Interrupted", message, code)


def _fail(as_json: bool, kind: str, message: str, code: int) -> int:
    """Report an error as one stderr line (and a JSON object under ``--json``); return ``code``."""
    line = " ".join(message.split())
    click.echo(f"lkspace: error: {line}", err=True)
    if as_json:
        try:
            sys.stdout.write(json.dumps({"error": {"type": kind, "message": line, "exit_code": code}}) + "\n")
            sys.stdout.flush()
        except OSError:  # stdout itself is what failed: the stderr line has said so
            _drop_stdout()
    return code


def _drop_stdout() -> None:
    """Point stdout's file descriptor at the null device, so the exit flush of what is left says nothing."""
    try:
        fd = sys.stdout.fileno()
    except (
        OSError,
        ValueError,
        AttributeError,
    ):  # no file behind stdout (tests capture it): nothing is flushed at exit
        return
    null = os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, fd)
    os.close(null)


def _show_warning(message: Warning | str, category: type[Warning], *_args: object, **_kwargs: object) -> None:
    """Show a warning as one ``lkspace: warning:`` line on stderr."""
    click.echo(f"lkspace: warning: {' '.join(flags_in(str(message)).split())}", err=True)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
