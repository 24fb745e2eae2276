"""``symbolic-friction verify FILE…``: exact re-check of certificate files.

Each file is dispatched on its ``schema`` field: a stability certificate of
the paper's model (:mod:`.._certify.verify`, exact rationals), a box
certificate (:mod:`.._certify.box`: the same verifier at every piece's four
corners) or a hunting certificate (a Krawczyk proof in arb balls).

Exit status: 0 if every file proves its claim; 1 if some inequality fails
(each failing one is named with its exact numbers); 2 if a file is missing
or malformed (not JSON, unknown schema, missing keys, a float where an exact
rational string is required, …).
"""

from __future__ import annotations

import argparse
import os

_LONG = 4000
HELP = "exactly re-check certificate files (exit 0 only if every file proves its claim)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """``FILE…``, ``--json`` and ``--junit-xml FILE``."""
    parser.description = (
        f"{HELP}. Exit status: 0 if every file proves its claim, 1 if an inequality fails "
        "(named with its exact numbers), 2 if a file is missing or malformed."
    )
    parser.add_argument("files", nargs="+", metavar="FILE", help="certificate JSON files")
    parser.add_argument("--json", action="store_true",
                        help="print one JSON object (every file, its gains, verdict and inequalities) instead of text")
    parser.add_argument("--junit-xml", metavar="FILE", default=None,
                        help="also write a JUnit XML report, one test case per certificate")
    parser.add_argument("--independent-only", action="store_true",
                        help="run only the small independent checker (symbolic_friction/independent/), for a reviewer")


def run(args: argparse.Namespace) -> int:
    """Verify each file; print one summary line per file, with its gains (and every check with ``--verbose``)."""
    import json

    from .._infra.rational import format_rational
    from .._infra.errors import CertificateFormatError, InputFileError
    from .._infra.junit import Case, write_junit
    from .._infra.output import emit

    if args.junit_xml is not None:
        from .._infra.junit import check_writable

        check_writable(args.junit_xml)
    if args.independent_only:
        return _independent_only(args)
    failed = False
    malformed: list[Exception] = []
    bad_names: list[str] = []
    cases: list = []
    payload: list[dict] = []
    from .._certify.templates import verify_any_file

    for name in args.files:
        try:
            if str(name).endswith(("/", os.sep)):  # pathlib would drop the slash and read the file
                raise InputFileError(f"cannot read certificate {name}: a trailing / names a directory, not a file")
            # dispatch on the file's schema: a hunting certificate has its own proof
            hunting, report = verify_any_file(name)
        except (CertificateFormatError, InputFileError) as exc:
            malformed.append(exc)
            bad_names.append(name)
            cases.append(Case(name=str(name), classname="verify", seconds=0.0, error=str(exc)))
            payload.append({"file": str(name), "status": "malformed", "error": str(exc)})
            if not args.json and len(args.files) > 1:
                # one line per file in the listing; the closing error then names the files, not the reasons again
                emit(f"MALFORMED {exc}", level=0)
            if isinstance(exc, CertificateFormatError):
                # the independent checker does not apply the main reader's format rules (key sets, exact rational
                # strings, a decimal κ, schema ids): where it proves the file, say that a format rule refuses it
                _format_disagreement(name, exc, args, payload[-1])
            continue
        cert = report.certificate
        second = _second_opinion(name, report, args)  # both verifiers, every time
        failed = failed or not second
        from .._certify.box import BoxReport

        if isinstance(report, BoxReport):
            _box_result(report, name, args, cases, payload)
            failed = failed or not report.proved
            continue
        if hunting:
            _hunting_result(report, name, args, cases, payload)
            failed = failed or not report.proved
            continue
        gains = cert.gains_text()
        cases.append(Case(
            name=str(name), classname="verify", seconds=0.0,
            failure=None if report.proved else "; ".join(c.message for c in report.failures),
            output=gains,
        ))
        payload.append({
            "file": str(name),
            "status": "proved" if report.proved else "failed",
            "gains": {k: format_rational(v) for k, v in cert.parameters.items()},
            "gains_text": gains,
            "label": cert.provenance.label if cert.provenance is not None else "",
            "overshoot_bound": getattr(cert, "overshoot_bound", None),  # None: a template without κ (reset contraction)
            "failures": [{"obligation": c.obligation, "inequality": c.name, "instance": c.instance} for c in report.failures],
            **({"checks": [{"obligation": c.obligation, "inequality": c.name, "instance": c.instance, "holds": c.holds}
                           for c in report.checks]} if args.verbose else {}),
        })
        if not args.json:
            line = f"{report.summary()} [{gains}]"
            if len(line) > _LONG and not args.verbose:
                # numbers of thousands of digits: the verdict stays readable; --verbose or --json give them exactly
                line = line[: _LONG - 200] + f" … ({len(line)} characters; --verbose or --json print the exact numbers)"
            emit(line, level=0)
            for check in report.checks:
                emit(f"  {check}  [{check.obligation}]", level=2)
        failed = failed or not report.proved
    if args.junit_xml is not None:
        write_junit(args.junit_xml, "symbolic-friction verify", cases)
    if args.json:
        emit(json.dumps({"files": payload, "passed": not failed and not malformed}, indent=2, ensure_ascii=False), level=0)
    if malformed:
        # the CLI turns this into "error: …" and exit status 2
        # each reason is printed once: a lone file's as the error, a listing's on its MALFORMED line (or in --json)
        if len(args.files) == 1:
            raise malformed[0]
        names = ", ".join(str(n) for n in bad_names)
        where = "see the JSON above" if args.json else "reasons above"
        raise CertificateFormatError(
            f"{len(malformed)} of {len(args.files)} files are missing or malformed ({where}): {names}"
        )
    return 1 if failed else 0


def _hunting_result(report, name, args, cases: list, payload: list) -> None:
    """One hunting certificate's line, JUnit case and JSON record (its checks are the Krawczyk proof's)."""
    from .._infra.junit import Case
    from .._infra.output import emit

    gains = str(report.certificate.params)
    failures = [c for c in report.checks if not c.holds]
    cases.append(Case(
        name=str(name), classname="verify", seconds=0.0,
        failure=None if report.proved else "; ".join(f"{c.name}: {c.detail}" for c in failures) or report.summary(),
        output=gains,
    ))
    payload.append({
        "file": str(name),
        "kind": "hunting",
        "status": "proved" if report.proved else "failed",
        "gains": report.certificate.params.as_strings(),
        "gains_text": gains,
        "verdict": report.certificate.verdict,
        "failures": [{"check": c.name, "detail": c.detail} for c in failures],
        **({"checks": [{"check": c.name, "holds": c.holds, "detail": c.detail} for c in report.checks]}
           if args.verbose else {}),
    })
    if not args.json:
        emit(report.summary(), level=0)
        for check in report.checks:
            emit(f"  {check}", level=2)


def _box_result(report, name, args, cases: list, payload: list) -> None:
    """One box certificate's line, JUnit case and JSON record (its checks: the cover and every piece's 4 corners)."""
    from .._infra.junit import Case
    from .._infra.output import emit

    cert = report.certificate
    gains = cert.gains_text()
    cases.append(Case(name=str(name), classname="verify", seconds=0.0,
                      failure=None if report.proved else "; ".join(c.message for c in report.failures[:5]), output=gains))
    payload.append({
        "file": str(name), "kind": "box", "status": "proved" if report.proved else "failed",
        "box": cert.to_dict()["box"], "gains_text": gains, "pieces": len(cert.pieces),
        "label": cert.provenance.get("label", ""), "overshoot_bound": cert.overshoot_bound,
        "failures": [{"obligation": c.obligation, "inequality": c.name, "instance": c.instance} for c in report.failures],
        **({"checks": [{"obligation": c.obligation, "inequality": c.name, "instance": c.instance, "holds": c.holds}
                       for c in report.checks]} if args.verbose else {}),
    })
    if not args.json:
        emit(f"{report.summary()} [{gains}]", level=0)
        for check in report.checks:
            emit(f"  {check}  [{check.obligation}]", level=2)


def _independent_verdict(name: object) -> tuple[bool, str]:
    """The independent checker's verdict on one file: ``(proved, why not)``."""
    from ..independent import Malformed, check_file

    try:
        verdict = check_file(str(name))
    except Malformed as exc:
        return False, f"not readable by the independent checker: {exc}"
    except Exception as exc:  # noqa: BLE001 - a crash of the second checker proves nothing, and says why
        return False, f"the independent checker failed: {type(exc).__name__}: {exc}"
    return verdict.proved, "" if verdict.proved else "; ".join(verdict.failing[:6])


def _second_opinion(name: object, report: object, args: argparse.Namespace) -> bool:
    """Run the independent checker beside the main verifier; a file is proved only if both prove it.

    Where they disagree, print both verdicts: the premises the independent checker names, or, where only the
    main verifier refuses, whether a format rule of its own refuses it (:func:`.._certify.verify.format_rules`:
    ``c``'s defining equation, a Table I label, the provenance's obligations), which the independent checker
    does not apply, or a premise, which it should have refused too.
    """
    from .._certify.verify import format_rules
    from .._infra.output import emit

    main_proved = bool(report.proved)  # type: ignore[attr-defined]
    proved, why = _independent_verdict(name)
    if proved != main_proved and not args.json:
        if main_proved:
            emit(f"DISAGREE {name}: the main verifier proves it; the independent checker refuses it ({why})", level=0)
        else:
            rules = format_rules(report)
            main_text = (f"only by its format rule{'s' * (len(rules) > 1)} {'; '.join(rules)} (which the independent "
                         "checker does not apply)" if rules else "by a premise, not a format rule: "
                         + "; ".join(c.name for c in report.checks if not c.holds)[:400])  # type: ignore[attr-defined]
            emit(f"DISAGREE {name}: the independent checker proves it; the main verifier refuses it {main_text}", level=0)
    return proved


def _format_disagreement(name: object, exc: Exception, args: argparse.Namespace, record: dict) -> None:
    """A file the main reader refuses as malformed: if the independent checker proves it, say which format rule refused it."""
    from .._infra.output import emit

    proved, _ = _independent_verdict(name)
    if not proved:
        return
    rule = str(exc).removeprefix(f"{name}: ")
    record["independent"] = "proved"
    record["disagreement"] = f"format rule: {rule}"
    if not args.json:
        emit(f"DISAGREE {name}: the independent checker proves it; the main verifier refuses it only by a format rule "
             f"of its reader (which the independent checker does not apply): {rule}", level=0)


def _independent_only(args: argparse.Namespace) -> int:
    """``verify --independent-only``: the small checker alone, one line per file."""
    import json

    from .._infra.output import emit

    rows, failed = [], False
    for name in args.files:
        proved, why = _independent_verdict(name)
        failed = failed or not proved
        rows.append({"file": str(name), "status": "proved" if proved else "not proved", "failing": why})
        if not args.json:
            emit(f"{'PROVED' if proved else 'NOT PROVED'} {name} (independent checker){'' if proved else ': ' + why}", level=0)
    if args.json:
        emit(json.dumps({"files": rows, "passed": not failed, "checker": "independent"}, indent=2, ensure_ascii=False), level=0)
    return 1 if failed else 0
