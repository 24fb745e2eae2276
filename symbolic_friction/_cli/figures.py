"""``symbolic-friction figures``: regenerate the paper's figures (and any other
registered figure) as PNG files.

The figures live in a registry (:mod:`symbolic_friction._studies.figures`); matplotlib
is imported only when a figure is drawn.  This module imports only the
standard library at top level.
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
    """Draw each figure, printing every file as it is written (a progress bar on a terminal)."""
    from .._studies.figures import available_figures, make_figures
    from .._infra.io import ensure_directory
    from .._infra.output import emit
    from .._infra.progress import Progress

    figures = available_figures()
    if args.list:
        for spec in figures.values():
            emit(f"{spec.name:10s} {spec.description}", level=0)
        return 0
    names = list(args.only) if args.only else list(figures)
    unknown = [n for n in names if n not in figures]
    if unknown:
        make_figures(args.out, unknown)  # raises, naming them and the available figures, before any drawing
    ensure_directory(args.out)  # an unusable --out fails now, not after drawing
    with Progress(len(names), desc="figures") as bar:
        for name in names:
            make_figures(args.out, [name], formats=args.format, on_written=lambda path: bar.write(f"wrote {path}", level=0))
            bar.update()
    return 0
