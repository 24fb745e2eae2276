"""``symbolic-friction tradeoff``: the speed/accuracy trade of every simulation
method, measured against the independent 50-digit reference.

Gains are Table I's case (a) or (b) (``--case``), or the user's own, read
exactly as ``certify`` reads them (``--k-p --k-i --k-v --f-c`` or the
physical ``--m --k-p-bar …``).  This module imports only the standard
library at top level.
"""

from __future__ import annotations

import argparse
import math
import json
import textwrap

from .._infra import limits

HELP = "measure each simulation method's error (vs a 50-digit reference) against its time, across its accuracy knob"

_EPILOG = """examples:
  symbolic-friction tradeoff                                  # Table I case (a), z0 = (0, 1, 0), T = 30
  symbolic-friction tradeoff --case b --z0 0,3,0 --t-end 60
  symbolic-friction tradeoff --k-p 3 --k-i 4 --k-v 6.4 --f-c 1 --z0 0,1,0 --z0 1,1,1 --format pdf svg
  symbolic-friction tradeoff --json --no-cost > tradeoff.json
  symbolic-friction tradeoff --theta 1/2 --no-cost --no-figures   # the second-order Moreau θ-method alone
"""

DEFAULT_Z0 = {"a": "0,1,0", "b": "0,3,0"}
DEFAULT_T = {"a": 30.0, "b": 60.0}


# Bounds checked before any work: the horizon, the sample count and the timed repeats of one run, the size of a state.
MAX_T_END, MAX_SAMPLES, MAX_REPEATS, MAX_STATE = (limits.TRADEOFF_MAX_T_END, limits.TRADEOFF_MAX_SAMPLES,
                                                limits.TRADEOFF_MAX_REPEATS, limits.TRADEOFF_MAX_STATE)
# ... and the stiffness of the comparison, spectral radius × t_end: explicit methods (ivp-events DOP853) take about
# that many steps, and 10⁶ of them ran for minutes.
MAX_STIFFNESS = 1e5


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Gains (as ``certify``), ``--case``, ``--z0``, ``--t-end``, ``--samples``, ``--repeats``, output options."""
    from .._infra.options import count_option, real_option
    from .certify import add_gain_arguments

    parser.description = textwrap.fill(
        f"{HELP}. For every method (event, moreau across h for each θ of --theta, regularized across epsilon for tanh and sat, "
        "ivp-events across rtol): the error in the state, the final state and the stick start times, the "
        "time per trajectory (median of repeats, with spread), the fitted order of accuracy; a table, a "
        "Pareto figure and a figure of the cost against the horizon T and the batch size N."
    )
    parser.epilog = _EPILOG
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.add_argument("--case", choices=("a", "b"), default=None, help="Table I case (default a unless gains are given)")
    parser.add_argument(
        "--z0", action="append", default=None, metavar="E_I,S,V",
        help="initial state (e_i, s, v), repeatable (default: 0,1,0 for case a, 0,3,0 for case b, 0,1,0 for gains; "
        f"each |component| at most {MAX_STATE:g})",
    )
    parser.add_argument("--t-end", type=real_option("--t-end", high=MAX_T_END), default=None, metavar="T",
                        help=f"horizon (default 30; 60 for case b; at most {MAX_T_END:g})")
    parser.add_argument("--samples", type=count_option("--samples", low=2, high=MAX_SAMPLES), default=301, metavar="M",
                        help=f"sample times where errors are measured (default 301; at most {MAX_SAMPLES})")
    parser.add_argument("--repeats", type=count_option("--repeats", high=MAX_REPEATS), default=7, metavar="R",
                        help=f"timed runs per configuration (default 7; at most {MAX_REPEATS})")
    parser.add_argument("--theta", nargs="+", default=None, metavar="THETA",
                        help="weights θ in [1/2, 1] of the Moreau θ-method, one curve each (default: 1 and 1/2; "
                             "1 is implicit Euler, 1/2 the second-order trapezoidal smooth part)")
    parser.add_argument("--quick", action="store_true", help="three knob values per method (a fast look)")
    parser.add_argument("--no-cost", action="store_true", help="skip the cost against T and N (and its figure)")
    parser.add_argument("--json", action="store_true", help="print the measurements as JSON instead of the table")
    parser.add_argument("--out", default="figures", metavar="DIR", help="directory for the figures (default: ./figures)")
    parser.add_argument("--no-figures", action="store_true", help="write no figure")
    parser.add_argument("--format", nargs="+", default=["png"], metavar="FMT", help="figure formats: png (always), pdf, svg")
    add_gain_arguments(parser)


def _spectral_radius(params) -> float:
    """Largest |root| of s³ + k_v s² + k_p s + k_i (eq. xPhDot's A): the rate an explicit method must resolve."""
    import numpy as np

    try:
        coefficients = [1.0, *(float(q) for q in (params.k_v, params.k_p, params.k_i))]
    except OverflowError:
        return math.inf
    return float(np.max(np.abs(np.roots(coefficients))))


def _state(text: str) -> tuple[float, float, float]:
    from .._infra.errors import UsageError
    from .._infra.options import read_reals

    try:
        return read_reals(text, name="--z0 (e_i,s,v)", size=3, bound=MAX_STATE)  # type: ignore[return-value]
    except argparse.ArgumentTypeError as exc:
        raise UsageError(str(exc)) from None


def theta_value(text: str, *, option: str = "--theta") -> float:
    """The weight ``θ`` of the Moreau θ-method read exactly (``1/2``, ``0.5``), refused outside ``[1/2, 1]``."""
    from fractions import Fraction

    from .._infra.errors import UsageError
    from .._infra.rational import to_rational

    theta = to_rational(text.strip(), name=option)
    if not Fraction(1, 2) <= theta <= 1:
        raise UsageError(f"{option} must be in [1/2, 1] (1: implicit Euler, 1/2: trapezoidal); got {option} {text}")
    return float(theta)


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from .._infra.errors import UsageError
    from .._infra.io import ensure_directory
    from .._infra.output import emit
    from .._model.parameters import Parameters
    from .._studies.tradeoff import DEFAULT_THETAS, check_formats, measure_cost, measure_tradeoff, tradeoff_figures
    from .certify import _gains

    formats = check_formats(args.format)
    thetas = tuple(theta_value(t) for t in args.theta) if args.theta else DEFAULT_THETAS
    params = _gains(args)
    if params is not None and args.case is not None:
        raise UsageError("give either --case or gains, not both")
    if params is None:
        case = args.case or "a"
        params, label, stem = Parameters.table_i(case), f"Table I case ({case})", f"tradeoff_{case}"
    else:
        case, label, stem = None, "user gains", "tradeoff_user"
    z0s = [_state(z) for z in (args.z0 or [DEFAULT_Z0.get(case, "0,1,0")])]
    t_end = args.t_end if args.t_end is not None else DEFAULT_T.get(case, 30.0)
    if not (math.isfinite(t_end) and 0 < t_end <= MAX_T_END):
        raise UsageError(f"--t-end must be > 0 and at most {MAX_T_END:g} (the reference's cost grows with it); got {t_end:g}")
    if not 2 <= args.samples <= MAX_SAMPLES:
        raise UsageError(f"--samples must be between 2 and {MAX_SAMPLES}; got {args.samples}")
    stiffness = _spectral_radius(params) * t_end
    if not stiffness <= MAX_STIFFNESS:
        raise UsageError(
            f"these gains are too stiff to compare every method over t_end = {t_end:g}: spectral radius × t_end = "
            f"{stiffness:.3g}, at most {MAX_STIFFNESS:g} (explicit methods take about that many steps); "
            "shorten --t-end or simulate the event method alone"
        )
    if not args.no_figures:
        ensure_directory(args.out)  # an unusable --out fails now, not after the measurements
    result = measure_tradeoff(params, z0s, t_end, label=label, samples=args.samples, repeats=args.repeats, quick=args.quick,
                              thetas=thetas)
    if not args.no_cost:
        from dataclasses import replace

        cost = measure_cost(params, z0s[0], repeats=3, t_batch=min(t_end, 30.0),
                            sizes=(1, 10, 100) if args.quick else (1, 10, 100, 1000, 10000),
                            horizons=(3.0, 10.0, 30.0) if args.quick else (3.0, 10.0, 30.0, 100.0, 300.0))
        result = replace(result, cost=cost)
    files = [] if args.no_figures else tradeoff_figures(result, Path(args.out), stem, formats)
    if args.json:
        data = result.as_dict()
        data["files"] = [str(f) for f in files]
        emit(json.dumps(data, indent=1, default=str), level=0)
    else:
        emit(result.table())  # the table and the costs: not under --quiet; the note and the files: always
        if result.cost:
            emit()
            emit("cost against the horizon T (one trajectory) and the batch size N (median of repeats):")
            for c in result.cost:
                what = f"T = {c.t_end:g}" if c.axis == "T" else f"N = {c.n} (T = {c.t_end:g})"
                kernel = f" ({c.kernel} kernel)" if c.kernel else ""
                emit(f"  {c.config:34s} {what:22s} {c.seconds:10.4f} s{kernel}")
        emit(level=0)
        emit(result.note(), level=0)
        for f in files:
            emit(f"wrote {f}", level=0)
    return 0
