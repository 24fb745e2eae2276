"""``symbolic-friction settling``: the paper's PID against reset PID from one initial state, on exact trajectories.

Parses, calls :func:`symbolic_friction._studies.settling.compare_settling` and renders.
"""

from __future__ import annotations

import argparse
import textwrap

from .._infra.options import count_option, read_reals, real_option
from .hunting import _HELP as _GAIN_HELP
from .._studies.settling import MAX_SAMPLES

HELP = "compare the settling of PID and reset PID (exact trajectories) from one initial state, and write a figure"

_NAMES = ("k_p", "k_i", "k_v", "f_c", "f_s")
_HELP = {**_GAIN_HELP, "f_s": "normalised static friction level f_s ≥ f_c (default f_c)"}
_EPILOG = """examples:
  symbolic-friction settling --k-p 3 --k-i 4 --k-v 6.4 --f-c 1 --z0 0,3,0
  symbolic-friction settling --k-p 0.66 --k-i 0.08 --k-v 1.5 --f-c 1 --z0 -5,0.3,1.2 --json
"""


MAX_T_END, MAX_STATE = 1e5, 1e12
# the kernel runs in float64; a state beyond 1e12 leaves nothing of the friction band to resolve


def _exact(check):
    """``type=``: validate with ``check`` (a bounded reader), keep the exact rational."""
    from .._infra.rational import to_rational

    def parse(text: str):
        check(text)
        return to_rational(text, name="value")

    parse.__name__ = check.__name__
    return parse


def _state(text: str):
    from .._infra.rational import to_rational

    read_reals(text, name="--z0 (e_i,s,v)", size=3, bound=MAX_STATE)
    return tuple(to_rational(c.strip(), name="--z0") for c in text.split(","))


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Gains, ``--reset-dwell``, ``--z0``, ``--tol``, ``--t-end``, ``--samples``, ``--out``, ``--json``."""
    parser.description = textwrap.fill(
        f"{HELP}. Reset PID (the package's law, beyond the paper): at a stick, e_i jumps so that the integrator "
        "force reaches the Coulomb level toward the setpoint, φ⁺ = f_c·sign(σ); V is unchanged (reset.* obligations)."
    )
    parser.epilog = _EPILOG
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    gains = parser.add_argument_group("normalised gains (exact: '6.4' is 32/5)")
    for name in _NAMES:
        gains.add_argument("--" + name.replace("_", "-"), dest=name, required=name != "f_s", default=None,
                           metavar="Q", help=_HELP[name])
    gains.add_argument("--reset-dwell", dest="reset_dwell", default="1/100", type=_exact(real_option("--reset-dwell", high=MAX_T_END)),
                       metavar="Q", help="the reset's dwell time τ_d > 0: at most one reset per τ_d (default 1/100)")
    parser.add_argument("--z0", default="0,3,0", type=_state, metavar="E_I,S,V",
                        help=f"initial state (e_i, s, v), exact, each within ±{MAX_STATE:g} (default 0,3,0)")
    parser.add_argument("--tol", default="1/1000000", type=_exact(real_option("--tol", high=1, high_open=True)), metavar="Q",
                        help="settled when |s| ≤ tol·|s(0)| from then on, in (0, 1) (default 1e-6)")
    parser.add_argument("--t-end", dest="t_end", default=200.0, type=real_option("--t-end", high=MAX_T_END), metavar="T",
                        help=f"horizon, up to {MAX_T_END:g} (default 200)")
    parser.add_argument("--samples", default=20001, type=count_option("--samples", low=2, high=MAX_SAMPLES), metavar="N",
                        help=f"sample times besides the events, 2 to {MAX_SAMPLES} (default 20001)")
    parser.add_argument("--out", default=".", metavar="DIR", help="directory of the figure settling_<hash>.png (default: .)")
    parser.add_argument("--no-figure", action="store_true", help="do not write the figure")
    parser.add_argument("--contraction", action="store_true",
                        help="also prove exponential settling of reset PID (f_s = f_c): write the reset-contraction "
                        "certificate reset_contraction_<hash>.json into --out (|σ| shrinks by ρ < 1 per slip), which "
                        "`verify` re-checks; where none exists (e.g. real roots: a slip from a stick never ends) say why")
    parser.add_argument("--json", action="store_true",
                        help="print one JSON object with keys pid and reset (settling_time, events, resets, overshoot, hunting)")


def run(args: argparse.Namespace) -> int:
    import hashlib
    import json
    from pathlib import Path

    from .._infra.io import check_output_directory
    from .._infra.output import emit
    from .._model.parameters import Parameters
    from .._studies.settling import compare_settling, write_settling_figure

    params = Parameters(**{n: getattr(args, n) for n in _NAMES})
    if not args.no_figure:
        check_output_directory(args.out, what="--out")
    comparison = compare_settling(params, args.z0, tol=args.tol, t_end=args.t_end, dwell=args.reset_dwell,
                                  samples=args.samples)
    z0 = args.z0
    t_end = args.t_end
    contraction = None
    if args.contraction:
        contraction = _contraction(params, args)
    figure = None
    if not args.no_figure:
        key = json.dumps(comparison.as_json(), sort_keys=True).encode()
        figure = Path(args.out) / f"settling_{hashlib.sha256(key).hexdigest()[:12]}.png"
        write_settling_figure(comparison, figure)
    if args.json:
        out = comparison.as_json()
        out["figure"] = None if figure is None else str(figure)
        if contraction is not None:
            out["contraction"] = contraction
        emit(json.dumps(out, indent=2, ensure_ascii=False), level=0)
        return 0
    emit(f"{comparison.params} from z0 = ({', '.join(map(str, z0))}), tol {comparison.tol}, t_end {t_end:g}, "
         f"reset dwell {comparison.dwell}")
    for run_ in (comparison.pid, comparison.reset):
        settles = "not within t_end" if run_.settling_time is None else f"at t = {run_.settling_time:.6g}"
        emit(f"  {run_.name:5s}  settles {settles}; {run_.events} events, {run_.resets} resets, overshoot "
             f"{run_.overshoot:.6g}, hunting: {run_.hunting}", level=0)
    speed = comparison.speedup
    if speed is not None:
        said = ("where PID does not" if speed == float("inf") else "as soon as PID (no stick was shortened)" if speed == 1.0
                else f"{speed:.3g}× sooner")
        emit(f"  reset settles {said}", level=0)
    if figure is not None:
        emit(f"wrote {figure}")
    if contraction is not None:
        emit(f"contraction: {contraction.get('claim') or contraction['reason']}"
             + (f" (wrote {contraction['path']})" if contraction.get("path") else ""), level=0)
    return 0


def _contraction(params, args) -> dict:
    """The reset-contraction certificate for these gains, written into ``--out``; or the reason there is none."""
    import hashlib
    from pathlib import Path

    from .._certify.reset_contraction import certify_contraction, dumps_contraction, verify_contraction
    from .._infra.errors import ParameterError
    from .._infra.io import atomic_write_text, check_output_directory

    check_output_directory(args.out, what="--out")
    try:
        cert = certify_contraction(params, dwell=args.reset_dwell)
    except ParameterError as exc:
        return {"path": None, "rho": None, "reason": str(exc)}
    text = dumps_contraction(cert)
    path = Path(args.out) / f"reset_contraction_{hashlib.sha256(text.encode()).hexdigest()[:12]}.json"
    atomic_write_text(path, text)
    report = verify_contraction(cert, source=str(path))
    return {"path": str(path), "rho": str(cert.rho), "radius": str(cert.radius), "cycle_time": str(cert.cycle_time),
            "proved": report.proved, "claim": report.summary()}
