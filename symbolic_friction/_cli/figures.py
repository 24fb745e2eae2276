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
    from .._infra.options import count_option

    parser.add_argument("--jobs", type=count_option("--jobs", high=MAX_JOBS), default=None, metavar="N",
                        help="processes drawing figures at once (default: the number of cores; 1: one after the other; "
                        f"at most {MAX_JOBS})")


def run(args: argparse.Namespace) -> int:
    """Draw the figures (in ``--jobs`` processes), printing every file as it is written, with a progress bar."""
    import os

    from .._infra.errors import UsageError
    from .._infra.io import ensure_directory
    from .._infra.output import emit
    from .._infra.progress import Progress
    from .._studies.figures import available_figures, chosen_figures, make_figures
    from .._studies.figures_run import units

    figures = available_figures()
    if args.list:
        for spec in figures.values():
            emit(f"{spec.name:22s} {spec.description}", level=0)
        return 0
    jobs = args.jobs if args.jobs is not None else min(os.cpu_count() or 1, MAX_JOBS)
    if not 1 <= jobs <= MAX_JOBS:
        raise UsageError(f"--jobs must be between 1 and {MAX_JOBS}; got {jobs}")
    specs, _ = chosen_figures(args.only, args.format)  # unknown names or formats fail before any drawing
    ensure_directory(args.out)  # an unusable --out fails now, not after drawing
    with Progress(len(units(specs)), desc="figures") as bar:
        make_figures(args.out, [s.name for s in specs], formats=args.format, jobs=jobs, progress=bar,
                     on_written=lambda path: bar.write(f"wrote {path}", level=0))
    return 0


# more processes than this only queue for the same cores
MAX_JOBS = 64
