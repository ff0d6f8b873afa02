"""``python -m lkspace.blender``: build the add-on zip, or render a design headless with Blender.

``build -o FILE.zip`` needs no Blender.  ``render MESH --twist SPEC -o FILE.png`` needs
the ``bpy`` module (extra ``[blender]``, Python 3.11); ``experiments/gallery.py
--renderer blender`` uses it.
"""

from __future__ import annotations

import argparse
import sys

from ..errors import LkspaceError


def parser() -> argparse.ArgumentParser:
    """Return the command line of ``python -m lkspace.blender``."""
    top = argparse.ArgumentParser(prog="python -m lkspace.blender", description=__doc__.splitlines()[0])
    commands = top.add_subparsers(dest="command", required=True)
    build = commands.add_parser("build", help="write the installable add-on zip")
    build.add_argument("-o", "--output", default="dist/lkspace_blender.zip")
    render = commands.add_parser("render", help="render a design with Blender (needs bpy)")
    render.add_argument("mesh", help="built-in scaffold name or scaffold file")
    render.add_argument("--twist", default="", help="as lkspace export --twist (default: the scaffold's own or 0)")
    render.add_argument("-o", "--output", required=True, help="PNG file")
    render.add_argument("--size", default="800x800", help="WxH pixels")
    render.add_argument("--engine", choices=["cycles", "eevee", "workbench"], default="cycles")
    render.add_argument("--samples", type=int, default=32)
    render.add_argument("--block", help="periodic scaffolds: an AxB(xC) block of cells")
    return top


def main(argv: list[str] | None = None) -> int:
    """Run a command; an lkspace error is one line on stderr and exit status 1 or 2."""
    args = parser().parse_args(argv)
    try:
        if args.command == "build":
            from .bundle import build

            names = build(args.output)
            print(
                f"{args.output}: {len(names)} files; install it in Blender from Preferences > Add-ons > Install from Disk"
            )
            return 0
        from .headless import render_design

        render_design(args.mesh, args.twist, args.output, args.size, args.engine, args.samples, args.block)
        return 0
    except LkspaceError as exc:
        from ..cli.flags import in_flags  # this command line's flags are lkspace's

        print(f"error: {in_flags(exc)}", file=sys.stderr)
        return exc.exit_code
    except KeyboardInterrupt:
        return 130


if __name__ == "__main__":
    sys.exit(main())
