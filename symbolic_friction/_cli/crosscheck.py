"""``symbolic-friction crosscheck [CERT…]``: test certificates on exact trajectories.

Every inequality a certificate instantiates (Lemma 2, Lemma 3, Proposition 1
and the Remark after Lemma 2) is checked along solutions of eq. (xDot)
simulated by the exact event-driven method, from random, grid, special and
adversarial initial states.  Every certificate is verified exactly first: one that does not verify is
refused (exit 1, one line naming the failing inequality).  Exit status: 0 if
every property holds within the stated tolerance on complete trajectories, 1
if some property is violated (counterexamples are written to ``--out``), a
certificate is not proved, or a trajectory is incomplete (event limit); 2 on
bad input (missing or malformed file, bad option).
"""

from __future__ import annotations

import argparse
import json
import math

from .._infra import limits


HELP = "check certificates on exact simulated trajectories and measure how tight they are"


MAX_TRAJECTORIES = limits.CROSSCHECK_MAX_TRAJECTORIES
MAX_SAMPLES = limits.CROSSCHECK_MAX_SAMPLES
MAX_EVENTS = 10_000_000
MAX_TOTAL_SAMPLES = limits.CROSSCHECK_MAX_TOTAL_SAMPLES
MAX_HORIZON = limits.CROSSCHECK_MAX_HORIZON
"""Bounds on the work one run may ask for (time and memory), said in the help and in the error when exceeded."""


def _seed(text: str) -> int:
    if len(text) > 40 or not text.isascii() or not text.lstrip("+").isdigit():
        raise argparse.ArgumentTypeError(f"expected an integer ≥ 0 of at most 40 digits; got {text[:40]!r}")
    return int(text)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """``CERT…`` and the options."""
    from .._infra.options import count_option, real_option

    parser.description = (
        f"{HELP}. Exit status: 0 if every property holds within the tolerance, 1 if one is violated "
        "(counterexamples written to --out), 2 on bad input."
    )
    parser.add_argument("certificates", nargs="*", metavar="CERT",
                        help="certificate JSON files (default: those configured in [tool.symbolic-friction], "
                        "else every proofs/*.json)")
    parser.add_argument("--trajectories", type=count_option("--trajectories", high=MAX_TRAJECTORIES), default=100_000,
                        metavar="N", help=f"trajectories per gain set, shared by its certificates (default 100000; at "
                        f"most {MAX_TRAJECTORIES}, and --trajectories × --samples at most {MAX_TOTAL_SAMPLES})")
    parser.add_argument("--seed", type=_seed, default=0, help="seed of the random states and optimisers (default 0)")
    parser.add_argument("--horizon", type=real_option("--horizon", high=MAX_HORIZON), default=None, metavar="T",
                        help=f"simulation horizon (default 20/|Re λ| of the slowest root; at most {MAX_HORIZON:g})")
    parser.add_argument("--samples", type=count_option("--samples", high=MAX_SAMPLES), default=101, metavar="N",
                        help=f"samples per trajectory, plus every event (default 101; at most {MAX_SAMPLES})")
    parser.add_argument("--rtol", type=real_option("--rtol", high=1, high_open=True), default=1e-8,
                        help="relative tolerance of every check, in (0, 1) (default 1e-8)")
    parser.add_argument("--theta", type=real_option("--theta", high=1), default=0.5,
                        help="attractivity: |x(T)|_A <= theta |x(0)|_A required, theta in (0, 1] (default 0.5)")
    parser.add_argument("--out", default="crosscheck-counterexamples", metavar="DIR",
                        help="directory for counterexample files (written only if a property fails)")
    parser.add_argument("--no-adversarial", action="store_true", help="skip the optimisers")
    parser.add_argument("--decay", action="store_true",
                        help="also fit the decay of |x(t)|_A (power law or exponential)")
    parser.add_argument("--max-events", type=count_option("--max-events", high=MAX_EVENTS), default=10_000, metavar="N",
                        help=f"event limit per trajectory; a trajectory reaching it is incomplete (default 10000; at most "
                        f"{MAX_EVENTS})")
    parser.add_argument("--json", action="store_true",
                        help="print the results as one JSON object (every certificate and property) instead of tables")
    parser.add_argument("--junit-xml", metavar="FILE", default=None,
                        help="also write a JUnit XML report: one test case per certificate and property")
    parser.add_argument("--iss", action="store_true",
                        help="also estimate Corollary 1's ISS gain (a few seconds per gain set)")
    parser.add_argument("--iss-search", action="store_true",
                        help="with --iss: search the selections of SGN_rho for the worst found ultimate bound "
                             "at rho = 0.01, 0.1, 1 (about a minute per gain set)")


def run(args: argparse.Namespace) -> int:
    """Run the cross-check, print the tables, write counterexamples; 1 if any property fails."""
    from .._crosscheck import crosscheck, default_certificate_selection, format_report, write_counterexamples
    from .._infra.errors import ParameterError, UnprovedCertificateError
    from .._infra.io import check_output_directory
    from .._infra.output import emit, verbosity

    files, skipped = (list(args.certificates), []) if args.certificates else default_certificate_selection()
    if args.rtol >= 1:
        raise ParameterError(f"--rtol must be < 1; got {args.rtol:g}")
    if args.theta > 1:
        raise ParameterError(f"--theta must be ≤ 1; got {args.theta:g}")
    if args.trajectories * args.samples > MAX_TOTAL_SAMPLES:
        raise ParameterError(
            f"--trajectories × --samples = {args.trajectories * args.samples} samples per gain set; at most "
            f"{MAX_TOTAL_SAMPLES} are supported (a bound on memory)"
        )
    check_output_directory(args.out, what="--out")
    if args.junit_xml is not None:
        from .._infra.junit import check_writable

        check_writable(args.junit_xml)
    if not args.json:
        for name, why in skipped:  # said before the long run, so a missing file is never a surprise
            emit(f"skipped {name}: {why}")
    try:
        report = _run_crosscheck(crosscheck, files, args)
    except UnprovedCertificateError as exc:
        if args.junit_xml is not None:
            from .._infra.junit import Case, write_junit

            write_junit(args.junit_xml, "symbolic-friction crosscheck",
                        [Case(name=" ".join(files), classname="crosscheck.refused", failure=str(exc))])
        if args.json:
            emit(json.dumps({"passed": False, "refused": str(exc), "certificates": []}, ensure_ascii=False), level=0)
        else:
            emit(f"crosscheck: REFUSED — {exc}", level=0)
        return 1
    written = [str(p) for p in write_counterexamples(report, args.out)] if report.counterexamples() else []
    if args.junit_xml is not None:
        from .._infra.junit import write_junit

        write_junit(args.junit_xml, "symbolic-friction crosscheck", _junit_cases(report))
    if args.json:
        payload = {**_json_report(report, written), "skipped": [{"file": n, "reason": why} for n, why in skipped]}
        emit(json.dumps(payload, indent=2, ensure_ascii=False, default=_json_default), level=0)
        return 0 if report.passed else 1
    emit(format_report(report))
    for path in written:
        emit(f"counterexamples written to {path}", level=0)
    if written:
        emit(report.summary(), level=0)
    elif verbosity() == 0:
        emit(report.summary(), level=0)
    return 0 if report.passed else 1


def _finite(x: object) -> object:
    """A float for JSON: NaN and infinities (nothing checked, no bound) become null."""
    try:
        value = float(x)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return None
    return value if math.isfinite(value) else None


def _json_default(value: object) -> object:
    try:
        import numpy as np

        if isinstance(value, np.generic):
            return value.item()
        if isinstance(value, np.ndarray):
            return value.tolist()
    except ImportError:  # pragma: no cover
        pass
    return str(value)


def _json_report(report, written: list[str]) -> dict:
    """The report as plain JSON, from the fields the report object already carries."""
    certificates = []
    for check in report.checks:
        certificates.append({
            "label": check.label,
            "template": check.claims.template_name,
            "file": check.source or None,
            "exact": {k: str(v) for k, v in check.claims.exact.items()},
            "proved": check.proved,
            "verdict": check.verdict,
            "trajectories": check.trajectories,
            "incomplete": check.incomplete,
            "horizon": _finite(check.horizon),
            "seconds": _finite(check.seconds),
            "max_overshoot": {k: _finite(v) for k, v in check.max_overshoot.items()},
            "tightness": {k: _finite(v) for k, v in check.tightness.items()},
            "properties": [
                {
                    "id": r.id, "paper": r.paper, "inequality": r.inequality, "trajectories": r.trajectories,
                    "checked": r.samples, "worst_margin": _finite(r.worst_margin), "failures": r.failures,
                    "inconclusive": getattr(r, "inconclusive", 0), "passed": r.passed,
                }
                for r in check.results
            ],
        })
    return {
        "passed": report.passed,
        "summary": report.summary(),
        "rtol": report.rtol,
        "theta": report.theta,
        "seed": report.seed,
        "seconds": _finite(report.seconds),
        "counterexamples": written,
        "certificates": certificates,
    }


def _junit_cases(report) -> list:
    from .._infra.junit import Case

    cases = []
    for check in report.checks:
        name = check.source or check.label
        cases.append(Case(
            name=name, classname="crosscheck.certificates", seconds=float(check.seconds),
            failure=None if check.verdict == "passed" else f"{check.verdict}: {check.incomplete} incomplete trajectories"
            if check.verdict == "incomplete" else check.verdict,
        ))
        for r in check.results:
            cases.append(Case(
                name=f"{name}: {r.id}", classname="crosscheck.properties",
                failure=None if r.passed else f"{r.failures} of {r.samples} instances of {r.inequality} fail "
                f"(worst relative margin {r.worst_margin:.3g})",
                output=f"{r.paper}: {r.inequality}; {r.samples} instances on {r.trajectories} trajectories",
            ))
    return cases


def _run_crosscheck(crosscheck, files, args):
    return crosscheck(
        files,
        trajectories=args.trajectories,
        seed=args.seed,
        horizon=args.horizon,
        samples=args.samples,
        rtol=args.rtol,
        theta=args.theta,
        adversarial=not args.no_adversarial,
        decay=args.decay,
        iss=args.iss or args.iss_search,
        iss_search=("0.01", "0.1", "1") if args.iss_search else (),
        max_events=args.max_events,
    )


__all__ = ["HELP", "add_arguments", "run"]

