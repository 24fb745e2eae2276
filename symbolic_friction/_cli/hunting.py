"""``symbolic-friction hunting``: the stick–slip limit cycle with static friction above Coulomb.

Finds the symmetric hunting cycles of one gain set with ``f_s > f_c`` (fixed
points of ``σ ↦ -P(σ)``, the hunting map on the exact event-driven model),
proves each with a Krawczyk test in arb balls, writes the proved ones as
certificates (atomically) that ``symbolic-friction verify`` re-checks, and
prints period, amplitudes, stick and slip durations, the multiplier
(stability), a long exact simulation's agreement with the cycle and the
comparison with Corollary 1's empirical ISS gain.  With ``f_s = f_c`` (the
paper's model) it says so: Proposition 1 holds, no cycle exists, and the
stability certificates of ``symbolic-friction certify`` apply.

Exit status: 0 if every cycle found was proved (or ``f_s = f_c``); 1 if no
cycle was found or one could not be proved; 2 on bad input.
"""

from __future__ import annotations

import argparse
import hashlib
import textwrap
from pathlib import Path

HELP = "find, prove (interval arithmetic) and certify the hunting cycle when f_s > f_c"

_NAMES = ("k_p", "k_i", "k_v", "f_c", "f_s")
_HELP = {
    "k_p": "normalised proportional gain k_p",
    "k_i": "normalised integral gain k_i",
    "k_v": "normalised velocity gain k_v",
    "f_c": "normalised Coulomb (kinetic) friction level f_c",
    "f_s": "normalised static friction level f_s ≥ f_c",
}
_EPILOG = """examples:
  symbolic-friction hunting --k-p 3 --k-i 4 --k-v 6.4 --f-c 1 --f-s 1.2
  symbolic-friction hunting --k-p 0.66 --k-i 0.08 --k-v 1.5 --f-c 1 --f-s 1.2 --figure hunting_b.png --sweep 1.05,1.1,1.2,1.5,2
  symbolic-friction verify proofs/hunting/*.json
"""


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Gains, ``--out``, ``--name``, ``--figure``, ``--sweep``, ``--no-iss``, ``--no-simulation``."""
    parser.description = textwrap.fill(
        f"{HELP}. Prints each cycle (period, amplitudes, stick and slip durations, multiplier), checks it "
        "against a long exact simulation and Corollary 1, and writes a certificate that `verify` re-checks."
    )
    parser.epilog = _EPILOG
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    gains = parser.add_argument_group("normalised gains (exact: '1.2' is 6/5; f_s = f_c or f_s/f_c in [1 + 1e-06, 100])")
    for name in _NAMES:
        gains.add_argument("--" + name.replace("_", "-"), dest=name, required=True, metavar="Q", help=_HELP[name])
    parser.add_argument("--out", default="proofs/hunting", metavar="DIR", help="directory for the certificates (default: proofs/hunting)")
    parser.add_argument("--name", default=None, metavar="STEM", help="file stem (default: hunting_<hash of the gains>)")
    parser.add_argument("--figure", default=None, metavar="PNG", help="write the phase plane, the map and (with --sweep) the sweep")
    parser.add_argument("--sweep", default=None, metavar="R,R,…",
                        help="ratios f_s/f_c for an amplitude sweep (e.g. 1.05,1.1,1.2,1.5; at most 50 ratios, "
                        "each in [1 + 1e-06, 100])")
    parser.add_argument("--no-iss", action="store_true", help="skip the comparison with Corollary 1's empirical ISS gain")
    parser.add_argument("--no-simulation", action="store_true", help="skip the long exact simulation check")


def run(args: argparse.Namespace) -> int:
    from .._infra.io import check_output_directory, check_output_file, check_stem
    from .._infra.output import emit
    from .._model.parameters import Parameters

    params = Parameters(**{name: getattr(args, name) for name in _NAMES})
    if args.name is not None:  # refused before any work, as certify's
        check_stem(args.name)
    check_output_directory(args.out, what="--out")  # an unusable --out or --figure fails now, not after the proofs
    if args.figure is not None:
        check_output_file(args.figure, what="--figure")
    if params.stiction:  # the search works in float64: refused before it, not after a traceback or an endless search
        from .._hunting._study import MAX_RATIO, MIN_EXCESS
        from .._infra.errors import ParameterError
        from .._simulation import _check_float_model

        if not 1 + MIN_EXCESS <= params.f_s / params.f_c <= MAX_RATIO:
            raise ParameterError(
                f"f_s/f_c must be 1 (the paper's model) or lie in [1 + {float(MIN_EXCESS):g}, {MAX_RATIO}]; "
                f"got f_s/f_c - 1 = {float(params.f_s / params.f_c - 1):.3g}"
            )
        _check_float_model(params)
    if not params.stiction:
        emit(
            f"{params}: f_s = f_c, the paper's model. Proposition 1: 𝒜 is globally asymptotically stable, so no "
            "hunting cycle exists; `symbolic-friction certify` with these gains writes the stability certificate "
            "that proves it, and the package's existing certificates (proofs/) apply.",
            level=0,
        )
        return 0
    from .._hunting._study import parse_sweep, study_cycle

    ratios = parse_sweep(args.sweep) if args.sweep is not None else None

    from .._certify.hunting import write_hunting
    from .._infra.bounds import bound_text
    from .._hunting._map import find_cycles, real_root_escape

    emit(f"{params}: ρ = (f_s - f_c)/f_c = {params.rho}")
    escape = real_root_escape(params)
    if escape is not None:
        lo, hi = escape.root_bracket
        root = f"λ₁ = {lo}" if lo == hi else f"λ₁ ∈ [{bound_text(lo, 15, direction='down')}, {bound_text(hi, 15, direction='up')}]"
        emit(
            f"three distinct real roots (discriminant > 0, exact), slowest {root}: a slip from a stick exit with "
            f"|σ| ≥ |λ₁|(f_s - f_c) = {bound_text(escape.bound, 10, direction='up')} never ends (proof: RealRootEscape), so only solutions "
            "whose stick exits stay below that bound can hunt; above it the mass slips into 𝒜"
        )
    cycles = find_cycles(params, general=False)  # only symmetric cycles are certified
    if not cycles:
        emit("no symmetric hunting cycle found (stick exits with σ in [Δ·1e-4, Δ·1e4], Δ = f_s - f_c): nothing certified", level=0)
        return 1
    stem = check_stem(args.name) if args.name is not None else "hunting_" + hashlib.sha256(str(params).encode()).hexdigest()[:10]
    failed = False
    for n, cycle in enumerate(cycles, start=1):
        k_i = float(params.k_i)
        emit(f"\ncycle {n}: symmetric, stick exit at φ = ±f_s with σ* = {cycle.sigma:.15g} (s = ∓{cycle.sigma / k_i:.15g})")
        emit(f"  period T = {cycle.period:.12g}; each half: slip {cycle.slip_time:.12g}, stick {cycle.stick_time:.12g}")
        emit(f"  the slip ends at φ = {cycle.phi_end:.12g} (|φ| ≤ f_s: sticks)")
        emit(
            f"  amplitude: max |s| = {cycle.amplitude_s:.10g}, max |e_i| = {cycle.amplitude_e_i:.10g}, "
            f"max |z|_𝒜 = {cycle.amplitude_distance:.10g}, max |x|_𝒜 = {cycle.amplitude_distance_x:.10g}"
        )
        stab = "stable (attracts nearby stick exits)" if cycle.stable else "unstable"
        emit(f"  multiplier d(-P)/dσ = {cycle.multiplier:.10g} (P∘P: {cycle.multiplier ** 2:.10g}): {stab}")
        if escape is not None:
            emit(f"  σ* = {cycle.sigma:.6g} < {bound_text(escape.bound, 6, direction='up')}: below the escape bound")
        study = study_cycle(params, cycle, simulate=not args.no_simulation, iss=not args.no_iss)
        proof = study.proof
        for check in proof.checks:
            emit(f"    {check}")
        if not proof.proved:
            emit("  NOT PROVED: no certificate written", level=0)
            failed = True
            continue
        m_lo, m_hi = proof.multiplier
        stab_proved = {True: "stable (proved |multiplier| < 1)", False: "unstable (proved |multiplier| > 1)", None: "stability undecided"}[proof.stable]
        emit(f"  PROVED: exactly one symmetric cycle with σ* in the box; multiplier ∈ [{m_lo:.10g}, {m_hi:.10g}]: {stab_proved}", level=0)
        if study.agreement is not None:
            agreement = study.agreement
            emit(f"  {agreement.describe()}: {'agrees to 1e-9' if agreement.holds(1e-9) else 'does NOT agree to 1e-9'}")
            emit(f"  the simulated |σ| at those exits {'lies' if study.inside_box else 'does NOT lie'} in the proved box [σ_lo, σ_hi]")
        if study.iss is not None:
            emit(f"  {study.iss.describe()}")
        cert = study.certificate
        name = stem if len(cycles) == 1 else f"{stem}_{n}"
        path = write_hunting(cert, Path(args.out) / f"{name}.json")
        emit(f"  certificate: {path} (re-check: symbolic-friction verify {path})", level=0)
    if args.figure is not None:
        from .._hunting._report import amplitude_sweep, hunting_figure

        sweep = amplitude_sweep(params, ratios) if ratios else None
        if sweep:
            emit("\nsweep over f_s/f_c (the cycle with the largest σ*):")
            for r, c in sweep:
                if c is None:
                    emit(f"  f_s/f_c = {r:g}: no symmetric cycle found")
                else:
                    emit(f"  f_s/f_c = {r:g}: σ* = {c.sigma:.6g}, max |s| = {c.amplitude_s:.6g}, max |z|_𝒜 = {c.amplitude_distance:.6g}, period {c.period:.6g}")
        hunting_figure(cycles[-1], args.figure, sweep=sweep)
        emit(f"figure: {args.figure}")
    elif ratios:
        emit("--sweep is drawn with --figure; pass --figure PNG", err=True, level=0)
    return 1 if failed else 0
