"""The ``symbolic-friction`` command line.

Start-up must stay fast: this module and the command modules
import only the standard library (and ``_infra``, which does too) at top level;
each command imports sympy, scipy or cvxpy inside its ``run`` function, and
only what it needs.

Each subcommand lives in ``symbolic_friction/_cli/<name>.py`` and
provides ``HELP`` (one line), ``add_arguments(parser)`` and
``run(args) -> int``.
"""

from __future__ import annotations

import argparse
import functools
import importlib
import re
import sys
from collections.abc import Sequence
from typing import Any, NoReturn

# every run needs these two: imported with this module, so that a process that imports it before running many
# command lines (a fork server) has them already
from .._infra.errors import SymbolicFrictionError
from .._infra.output import install_ascii_fallback, set_verbosity

__all__ = ["main", "build_parser", "shared_parser", "exit_without_teardown"]

COMMANDS = ("check", "certify", "verify", "simulate", "figures", "crosscheck", "hunting", "settling", "tradeoff", "extremes", "map")


class _Parser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line on stderr and exit status 2."""

    # A tuple of numbers such as ``--z0 -1,0,0`` (or ``-3/5,0,0``) is a value, not an option:
    # argparse by default only recognises plain negative numbers.  No option starts with a digit.
    _NUMBERS = re.compile(r"^-\.?\d[\d.,/eE+-]*$")

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = self._NUMBERS

    def error(self, message: str) -> "NoReturn":  # type: ignore[override]
        message = " ".join(message.split())
        if len(message) > 300:
            message = message[:300] + "…"
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def _common(parser: argparse.ArgumentParser) -> None:
    """``--quiet`` and ``--verbose``, on every command."""
    group = parser.add_mutually_exclusive_group()
    group.add_argument("-q", "--quiet", action="store_true", help="print only verdicts, the closing line and errors")
    group.add_argument("-v", "--verbose", action="store_true", help="print more detail (every inequality, every trajectory, timings)")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser, with one subparser per command."""
    parser = _Parser(
        prog="symbolic-friction",
        description=(
            "Machine-checked proof of global asymptotic stability for a PID-controlled mass with Coulomb "
            "friction (Bisoffi, Da Lio, Teel, Zaccarian). Re-derives the proof, certifies gains exactly, "
            "simulates the Filippov inclusion and cross-checks certificates on trajectories."
        ),
    )
    from .. import __version__

    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True, parser_class=_Parser)
    for name in COMMANDS:
        module = importlib.import_module(f"symbolic_friction._cli.{name}")
        p = sub.add_parser(name, help=module.HELP, description=module.HELP)
        _common(p)
        module.add_arguments(p)
        p.set_defaults(_module=module)
    return parser


@functools.cache
def shared_parser() -> argparse.ArgumentParser:
    """The parser :func:`main` parses with: :func:`build_parser`'s, built once per process.

    Building it (a dozen parsers, about 180 options, each checked by a help formatter) costs more than most
    refused command lines do; a process that runs :func:`main` many times (the tests, a fork server that
    builds it before forking) builds it once.  Parsing leaves a parser as it was: the help's width is read when
    help is printed, and :func:`main` gives each run its own copy of a list default.
    """
    return build_parser()


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit code.

    User errors (any :class:`~symbolic_friction.SymbolicFrictionError`, any
    OS error on a path, input nested too deeply to parse) print one line
    ``error: …`` to stderr and return 2, without a traceback.  Output that
    cannot be encoded (``PYTHONIOENCODING=ascii``) falls back to ASCII.
    """
    install_ascii_fallback()
    parser = shared_parser()
    if not (sys.argv[1:] if argv is None else list(argv)):
        # a bare command is a request for help, not a usage error
        parser.print_help()
        return 0
    args = parser.parse_args(argv)
    for name, value in vars(args).items():
        if isinstance(value, list):  # a list default (``--format``'s) is the shared parser's own object
            setattr(args, name, list(value))
    set_verbosity(0 if getattr(args, "quiet", False) else 2 if getattr(args, "verbose", False) else 1)
    prefix = f"symbolic-friction {args.command}: error:"
    try:
        return int(args._module.run(args))
    except SymbolicFrictionError as exc:
        _error_line(prefix, str(exc))
        return 2
    except BrokenPipeError:
        # the reader went away (`| head`): stop quietly, as other command-line tools do
        import os

        try:
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        except OSError:  # pragma: no cover
            pass
        return 141
    except OSError as exc:
        from .._infra.io import describe_os_error

        _error_line(prefix, describe_os_error(exc))
        return 2
    except RecursionError:
        _error_line(prefix, "input nested too deeply")
        return 2
    except OverflowError as exc:  # only user numbers reach float conversion at this size
        _error_line(prefix, f"a number is beyond the range of floating point (about 1e308): {exc}")
        return 2
    except KeyboardInterrupt:
        print(f"symbolic-friction {args.command}: interrupted", file=sys.stderr)
        return 130
    finally:
        set_verbosity(1)


def _error_line(prefix: str, message: str) -> None:
    """One line on stderr: newlines folded, a runaway message cut."""
    message = " ".join(message.split())
    if len(message) > 2000:
        message = message[:2000] + "…"
    print(f"{prefix} {message}", file=sys.stderr, flush=True)


def entry_point() -> None:  # pragma: no cover - thin wrapper for the console script
    exit_without_teardown(main())


def exit_without_teardown(code: int) -> "NoReturn":
    """End the process with ``code`` as :func:`sys.exit` would, without the interpreter freeing every object first.

    After ``check`` that teardown (sympy's caches, the derivations, one object
    at a time) takes about 0.25 s of a 3.5 s run, and nothing a user sees
    depends on it: what does is done here, in the order the interpreter does
    it: other threads are joined, the ``atexit`` handlers run (coverage,
    multiprocessing's), the standard streams are flushed.  If flushing fails
    (a reader that went away), the ordinary exit reports it as Python does.
    """
    import atexit
    import os
    import threading

    for thread in threading.enumerate():
        if thread is not threading.main_thread() and not thread.daemon:
            thread.join()
    atexit._run_exitfuncs()
    try:
        sys.stdout.flush()
        sys.stderr.flush()
    except Exception:  # noqa: BLE001 - the interpreter's own exit reports it
        sys.exit(code)
    os._exit(code)


if __name__ == "__main__":  # pragma: no cover
    entry_point()
