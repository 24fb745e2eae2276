"""The ``symbolic-friction`` command line.

Start-up must stay fast (Standard 6): this module and the command modules
import only the standard library at top level; each command imports sympy,
scipy or cvxpy inside its ``run`` function, and only what it needs.

Each subcommand lives in ``symbolic_friction/_commands/<name>.py`` and
provides ``HELP`` (one line), ``add_arguments(parser)`` and
``run(args) -> int``.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence

__all__ = ["main", "build_parser"]

COMMANDS = ("check", "certify", "verify", "simulate", "figures", "crosscheck", "tradeoff", "extremes")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser, with one subparser per command."""
    parser = argparse.ArgumentParser(
        prog="symbolic-friction",
        description=(
            "Machine-checked proof of global asymptotic stability for a PID-controlled mass with Coulomb "
            "friction (Bisoffi, Da Lio, Teel, Zaccarian). Re-derives the proof, certifies gains exactly, "
            "simulates the Filippov inclusion and cross-checks certificates on trajectories."
        ),
    )
    from . import __version__

    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for name in COMMANDS:
        module = importlib.import_module(f"symbolic_friction._commands.{name}")
        p = sub.add_parser(name, help=module.HELP, description=module.HELP)
        module.add_arguments(p)
        p.set_defaults(_module=module)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit code.

    User errors (any :class:`~symbolic_friction.SymbolicFrictionError`, and a
    missing or unreadable file) print one line ``error: …`` to stderr and
    return 2, without a traceback.
    """
    from ._errors import SymbolicFrictionError

    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args._module.run(args))
    except SymbolicFrictionError as exc:
        print(f"symbolic-friction {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except (FileNotFoundError, IsADirectoryError, PermissionError) as exc:
        print(f"symbolic-friction {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"symbolic-friction {args.command}: interrupted", file=sys.stderr)
        return 130


def entry_point() -> None:  # pragma: no cover - thin wrapper for the console script
    sys.exit(main())


if __name__ == "__main__":  # pragma: no cover
    entry_point()
