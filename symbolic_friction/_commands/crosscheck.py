"""``symbolic-friction crosscheck``: placeholder until its issue lands."""

from __future__ import annotations

import argparse

from .._errors import SymbolicFrictionError

HELP = "(not implemented yet)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """No arguments yet."""


def run(args: argparse.Namespace) -> int:
    raise SymbolicFrictionError("'crosscheck' is not implemented yet")
