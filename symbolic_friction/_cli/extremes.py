"""``symbolic-friction extremes``: every simulation method and ``certify`` on a
fixed matrix of hard cases, each outcome classified against the 50-digit
reference (:mod:`symbolic_friction._extremes`).  Writes the report
(Markdown) and the heat map.  This module imports only the standard library
at top level.
"""

from __future__ import annotations

import argparse

HELP = "run every method and certify on a matrix of hard cases; classify each outcome against a 50-digit reference"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """``[--out DIR] [--only GROUP ...] [--format FMT ...] [--json]``."""
    parser.add_argument("--out", default="figures", metavar="DIR", help="directory for extremes.md and the heat map (default: ./figures)")
    parser.add_argument("--only", nargs="+", metavar="GROUP", help="run only these groups or cells (e.g. 'Routh boundary' f_c)")
    parser.add_argument("--format", nargs="+", default=["png"], metavar="FMT", help="heat-map formats: png (always), pdf, svg")
    parser.add_argument("--json", action="store_true", help="print the outcomes as JSON")
    parser.add_argument("--theta", default=None, metavar="THETA",
                        help="weight θ in [1/2, 1] of the moreau θ-method (default 1: implicit Euler; 1/2: second order)")


def run(args: argparse.Namespace) -> int:
    import json

    from .._extremes import extremes_figure, run_extremes
    from .._infra.io import atomic_write_text, ensure_directory
    from .._infra.output import emit
    from .._studies.tradeoff import check_formats

    from .tradeoff import theta_value

    formats = check_formats(args.format)
    theta = 1.0 if args.theta is None else theta_value(args.theta)
    out = ensure_directory(args.out)  # an unusable --out fails now, not after the run
    result = run_extremes(only=args.only, theta=theta)
    report = atomic_write_text(out / "extremes.md", result.report())
    files = [report, *extremes_figure(result, out / "extremes_heatmap.png", formats)]
    if args.json:
        emit(json.dumps({"seconds": result.seconds, "counts": result.counts(),
                         "outcomes": [o.__dict__ for o in result.outcomes], "files": [str(f) for f in files]},
                        indent=1, default=str), level=0)
    else:
        emit(result.report(), level=0)
        for f in files:
            emit(f"wrote {f}", level=0)
    # a silently wrong cell is a failure of the package's contract
    return 1 if result.silently_wrong else 0
