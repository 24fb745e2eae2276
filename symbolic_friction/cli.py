"""The ``symbolic-friction`` command line (public entry point).

The console script ``symbolic-friction`` and ``python -m symbolic_friction``
run :func:`entry_point`; the parser and the commands live in
:mod:`symbolic_friction._cli`.
"""

from __future__ import annotations

from ._cli.main import build_parser, entry_point, main

__all__ = ["main", "build_parser", "entry_point"]

if __name__ == "__main__":  # pragma: no cover
    entry_point()
