"""``symbolic-friction figures``: regenerate the paper's figures (and any other
registered figure) as PNG files.

The figures live in a registry (:mod:`symbolic_friction._figures`); matplotlib
is imported only when a figure is drawn.  This module imports only the
standard library at top level (Standard 6).
"""

from __future__ import annotations

import argparse

HELP = "regenerate the paper's figures (Fig. 2, 3a, 3b, 4, ...) and the extremes heat map as PNG (and PDF/SVG) files"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """``--out DIR [--only NAME ...] [--format FMT ...] [--list]``."""
    parser.add_argument("--out", default="figures", metavar="DIR", help="output directory (default: ./figures)")
    parser.add_argument("--only", nargs="+", metavar="NAME", help="draw only these figures (see --list)")
    parser.add_argument("--list", action="store_true", help="list the available figures and exit")
    parser.add_argument("--format", nargs="+", default=["png"], metavar="FMT",
                        help="also write these formats: pdf, svg (png is always written)")


def run(args: argparse.Namespace) -> int:
    from .._figures import available_figures, make_figures

    if args.list:
        for spec in available_figures().values():
            print(f"{spec.name:10s} {spec.description}")
        return 0
    for path in make_figures(args.out, args.only, formats=args.format):
        print(f"wrote {path}")
    return 0
