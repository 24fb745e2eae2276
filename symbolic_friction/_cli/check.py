"""``symbolic-friction check``: re-derive every proof obligation of the paper.

The command is a list of *sections* (:data:`SECTIONS`).  Each section is a
function ``(args) -> Section`` that does its work and returns its printable
table, its JSON members and whether it is satisfied; ``run`` prints them in
order and exits 0 only if every section is satisfied.  Further checks (for
example the exact verification of every certificate under ``proofs/``) are
added by appending a function to :data:`SECTIONS`.

The sections: the obligations, the configured certificates, the
cross-check's self-test and the self-check (the verifiers refuse the
known-false certificates shipped with the package,
:mod:`._self_check`).  One gate (:func:`._sections.gate`) fails a section
that prints a ``FAILED`` or ``NOT PROVED`` line, whatever it reported.

The obligations section runs every obligation from
:func:`symbolic_friction._obligations.all_obligations`, lists the errata and
compares ``<DIR>/obligations.md`` with what it would write now (``--write``
regenerates it).

Nothing passes vacuously: a ``--proofs DIR`` that does not exist is a usage
error (exit 2) unless ``--write`` creates it; a directory with no
certificate fails unless ``--no-certificates`` says that only the
derivations are to be checked; a section that crashes fails.  Each section
has a one-line summary with counts, and the last line of the output,
``check: PASSED — …`` or ``check: FAILED — …``, agrees with the exit code.

Only the standard library is imported at module level (fast ``--help``).
"""

from __future__ import annotations

import argparse
import json
from collections.abc import Callable
from typing import Any
from ._independent import independent_section
from ._self_check import self_check_section
from ._smt import add_smt_arguments, smt_section, validate_smt, wants_smt
from ._sections import (
    Section,
    _crashed,
    _format_table,
    _is_verdict,
    _ObligationLayout,
    _selected,
    _wrap,
    closing_line,
    gate,
    dataclasses_asdict,
    resolve_target,
)

HELP = "re-derive the paper's proof obligations for symbolic gains; exit 0 only if all hold"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """``--json``, ``--write``, ``--proofs DIR``, ``--config FILE``, ``--no-certificates`` and the ``--smt`` options."""
    parser.add_argument("--json", action="store_true", help='print {"obligations": [...], "errata": [...]} as JSON instead of a table')
    parser.add_argument("--write", action="store_true", help="regenerate the configured certificates (and obligations.md "
                        "where kept, and proofs/smt/*.smt2) atomically instead of checking them")
    parser.add_argument(
        "--proofs",
        metavar="DIR",
        default=None,
        help="proofs directory (default: the one configured in [tool.symbolic-friction]); without a configuration, "
        "every *.json under DIR is verified; it must exist unless --write creates it",
    )
    parser.add_argument(
        "--config",
        metavar="FILE",
        default=None,
        help="read the configuration from FILE (a pyproject.toml or symbolic-friction.toml) instead of searching "
        "upwards from the working directory",
    )
    parser.add_argument(
        "--strict",
        action="store_true",
        help="fail on drift too: a certificate that proves its statement but is not what `certify` writes now "
        "(a newer solver or package rounded differently); by default drift is reported, not failed "
        "(`strict = true` in the configuration does the same)",
    )
    parser.add_argument("--no-certificates", action="store_true", help="check only the derivations (and obligations.md); "
                        "without it, check fails when no certificate was verified")
    parser.add_argument(
        "--only",
        metavar="PART",
        action="append",
        default=None,
        help="re-derive only the obligations whose id is PART or starts with PART. (e.g. lemma3, claim1.cases); "
        "repeatable; certificates, obligations.md and the cross-check self-test are not checked then",
    )
    parser.add_argument("--junit-xml", metavar="FILE", default=None,
                        help="also write a JUnit XML report: one test case per obligation, certificate and self-test row")
    add_smt_arguments(parser)


def obligations_section(args: argparse.Namespace) -> Section:
    """Run every obligation, list the errata and check or write the report."""
    from .._obligations import all_errata, all_obligations, run_checked
    from .._obligations._report import compare_report, render_report, report_path, write_atomic
    from .._infra.io import ensure_directory

    from .._infra.junit import Case
    from .._infra.output import emit

    only = getattr(args, "only", None)
    obligations = [ob for ob in all_obligations() if _selected(ob.id, only)]
    claims = getattr(args, "claims", None)
    if claims is not None:  # each decided here unless the other core has claimed it (see run())
        obligations = [_Claimed(ob, claims, args.inbox) if ob.id in claims.names else ob for ob in obligations]
    stream = not getattr(args, "json", False)
    layout = _ObligationLayout()
    if stream:
        emit(layout.title)
        emit(layout.head)
        emit(layout.rule)
    on_result = (lambda r: emit(layout.row(r), level=0 if not r.holds else 1)) if stream else None
    from .._obligations._derived_k import shared_derivations

    with shared_derivations():  # one derivation of Lemma 3's k-conditions for the obligations that use it
        results = run_checked(obligations, on_result=on_result)
    errata = all_errata()
    notes: list[str] = []
    ok = all(r.holds for r in results)
    for r in results:
        if not r.holds:
            notes.append(f"FAILS {r.id}: {r.reason}")
    if errata:
        notes.append("Errata (the paper's text is wrong here; the corrected statement was checked):")
        for n, e in enumerate(errata, 1):
            notes.append(f"  {n}. {e.where}: the paper says \"{e.paper_says}\"; correct: {e.correct} [checked by {e.checked_by}]")

    text = render_report(results, errata)
    where = resolve_target(args)
    proofs = where.proofs
    target = report_path(proofs)
    report_state = "up to date"
    if only:
        report_state = "not compared (--only)"
    elif not where.report:
        pass  # the project keeps no obligations.md (its configuration says report = false)
    elif args.write:
        ensure_directory(proofs, what="proofs directory")
        write_atomic(target, text)
        notes.append(f"wrote {target}")
        report_state = "written"
    elif not proofs.is_dir():
        # only reachable with --no-certificates (run() refuses a missing DIR otherwise)
        report_state = "not checked (no such directory)"
        notes.append(f"note: {proofs} does not exist; {target} was not compared")
    elif (state := compare_report(target, text)) == "missing":
        ok = False
        report_state = "missing"
        notes.append(f"STALE: {target} is missing; run `symbolic-friction check --write` and commit it")
    elif state == "stale":
        ok = False
        report_state = "STALE"
        notes.append(f"STALE: {target} differs from what `check` derives now; run `symbolic-friction check --write` and commit it")

    rows = [(r.id, r.paper, r.statement, r.method, r.status, f"{r.seconds:.2f}") for r in results]
    cases = [
        Case(name=r.id, classname="check.obligations", seconds=r.seconds,
             failure=None if r.holds else (r.reason or "fails"), output=f"{r.paper}: {r.statement}")
        for r in results
    ]
    if where.report and not only:
        cases.append(Case(name=str(target), classname="check.report",
                          failure=None if report_state in ("up to date", "written") else f"{target} {report_state}"))
    total = sum(r.seconds for r in results)
    held = sum(1 for r in results if r.holds)
    notes.insert(0, f"{held} of {len(results)} obligations hold ({total:.1f} s)")
    if not results:
        ok = False  # a run that checked nothing proves nothing
    return Section(
        title="Proof obligations",
        columns=("id", "paper", "statement", "method", "status", "seconds"),
        rows=rows,
        json={"obligations": [r.as_json() for r in results], "errata": [e.as_json() for e in errata]},
        ok=ok,
        notes=notes,
        summary=(f"{held} of {len(results)} obligations hold, {target} {report_state}" if where.report and not only
                 else f"{held} of {len(results)} obligations hold" + (f" (only {', '.join(only)})" if only else "")),
        counts={"obligations": len(results), "obligations_hold": held},
        cases=cases,
        streamed=stream,
    )


TOGETHER = (("lemma3.hatV_derivative", "certificate.verifier"),)
"""Obligations one process decides together: one derivation of Lemma 3's k-conditions serves both."""


class _Claimed:
    """An obligation both processes may claim: decided here if this process claims it first, else its result is the
    worker's (and decided here after all if the worker is gone)."""

    def __init__(self, ob: Any, claims: Any, inbox: Any) -> None:
        self.ob, self.claims, self.inbox = ob, claims, inbox
        self.id, self.paper, self.statement, self.method = ob.id, ob.paper, ob.statement, ob.method

    def run(self) -> Any:
        if self.claims.take_front(self.id):
            return self.ob.run()
        try:
            return self.inbox.get("claimed", self.id)
        except RuntimeError:  # the worker is gone: decide it here
            return self.ob.run()


def _decide_tail() -> list[tuple[str, Callable[[], Any]]]:
    """``[(id, run it)]`` for every obligation: the worker takes them from the back once its sections are done, this
    process from the front (:class:`._parallel.Claims`, each group of :data:`TOGETHER` as one), so the cores finish
    together however fast each one is (measured: the sections alone are about as long as the obligations, so a fixed
    split leaves one core idle whichever way it errs)."""
    import sympy.tensor.tensor  # noqa: F401 - sympy loads it on the first sum it builds: here, not mid-obligation

    from .._obligations import all_obligations, run_checked

    return [(ob.id, (lambda ob=ob: run_checked([ob])[0])) for ob in all_obligations()]


def _shared_derivations() -> Any:
    """:func:`~.._obligations._derived_k.shared_derivations`, entered after the fork: one block of shared derivations
    in each process."""
    from .._obligations._derived_k import shared_derivations

    return shared_derivations()


def _import_shared() -> None:
    """Import before the fork what both processes would each import after it: ``xml.etree`` for every section's
    JUnit cases, and sympy, numpy and the obligations' modules (about 0.5 s).  The child needs them all too:
    numpy and the certificate modules in its first section, sympy in the self-check, the obligations' modules
    for the items of the tail it takes (:func:`_decide_tail`); imported once here, the child starts that much
    later and no longer imports them itself, so neither process finishes later and the pair does the import once."""
    from .._infra import junit  # noqa: F401

    try:
        import sympy.tensor.tensor  # noqa: F401 - sympy loads it on the first sum it builds: here, not mid-obligation

        from .._obligations import registry

        registry()
    except Exception:  # noqa: BLE001 - the obligations' section meets the same error and reports it as failing
        pass


def certificates_section(args: argparse.Namespace) -> Section:
    """Verify the configured certificates exactly and detect stale or missing ones.

    A certificate is stale when it, or its Markdown report, differs from what
    ``symbolic-friction certify`` would write now (this re-runs the search,
    so it imports cvxpy).  Every configured certificate must exist; files in
    the directory that are not configured are listed, not checked.
    """
    where = resolve_target(args)
    proofs = where.proofs
    if getattr(args, "no_certificates", False):
        return Section("Certificates", ("file", "proved", "up to date"), [], {"certificates": []}, True,
                       ["certificates: not checked (--no-certificates)"],
                       summary="certificates not checked (--no-certificates)", counts={"certificates": 0})
    from .._certify import check_listed_certificates, write_listed_certificates

    written: list[str] = []
    names = where.certificates
    if names is None:
        names = tuple(sorted(str(p.relative_to(proofs)) for p in proofs.rglob("*.json"))) if proofs.is_dir() else ()
    if args.write:
        # --write regenerates every configured certificate (from its own provenance, or
        # Table I's gains for Table I's file names), so one command brings a project up to date.
        written = [f"wrote {p}" for p in write_listed_certificates(proofs, names)]
    from .._infra.output import emit, fit, terminal_width
    from .._infra.progress import Progress

    stream = not getattr(args, "json", False)
    columns = ("file", "proved", "up to date", "kappa")
    file_width = min(max([len(str(proofs / n)) for n in names] + [4]), max(20, terminal_width() - 36))
    widths = (file_width, 6, 10, 8)
    title = "Certificates (exact re-verification)"
    if stream and names:
        emit(title)
        emit("  ".join(c.ljust(w) for c, w in zip(columns, widths)).rstrip())
        emit("  ".join("-" * w for w in widths))
    entries = []
    with Progress(len(names), desc="certificates") as bar:
        for name in names:
            entry = check_listed_certificates(proofs, [name], strict=where.strict, expectations=where.expectations)[0]
            entries.append(entry)
            bar.update()
            if stream:
                cells = (str(entry.path), "yes" if entry.proved else "NO", "no" if entry.stale else "yes",
                         _claim(entry))
                line = "  ".join(fit(c, w).ljust(w) for c, w in zip(cells, widths)).rstrip()
                bar.write(line, level=1 if entry.ok else 0)  # above the bar, which stays at the bottom
    rows = [(str(e.path), "yes" if e.proved else "NO", "no" if e.stale else "yes", _claim(e)) for e in entries]
    ok = bool(entries) and all(e.ok for e in entries)
    proved = sum(e.proved for e in entries)
    current = sum(e.ok for e in entries)
    drifted = [e for e in entries if e.ok and e.drift]
    if entries:
        summary = f"{proved} of {len(entries)} certificates proved exactly, {current} of {len(entries)} up to date"
        if drifted:
            summary += f" ({len(drifted)} with drift, reported)"
    elif where.certificates is not None:
        summary = f"no certificates configured in {where.origin} (list them under [tool.symbolic-friction] certificates, or pass --no-certificates)"
    else:
        summary = f"no certificates checked in {proofs} (pass --no-certificates to check only the derivations)"
    notes = [summary]
    notes += [e.describe() + (f" (listed in {where.origin})" if e.report is None and not e.path.exists()
                              and where.certificates is not None else "")
              for e in entries if not e.ok]
    notes += [f"drift (reported, not failed; `check --strict` fails on it): {e.path}: {e.drift}" for e in drifted]
    notes += written
    if where.certificates is not None and proofs.is_dir():
        listed = {str(proofs / n) for n in where.certificates}
        extra = sorted(str(p) for p in proofs.rglob("*.json") if str(p) not in listed)
        if extra:
            notes.append(f"note: {len(extra)} file(s) in {proofs} not listed in {where.origin} were not checked: "
                         + ", ".join(extra[:5]) + (" …" if len(extra) > 5 else ""))
    payload = [
        {"file": str(e.path), "proved": e.proved, "stale": e.stale, "reason": e.reason, "drift": e.drift,
         **({"gains": e.report.certificate.gains_text()} if e.report is not None else {})}
        for e in entries
    ]
    from .._infra.junit import Case

    cases = [Case(name=str(e.path), classname="check.certificates", failure=None if e.ok else e.describe(),
                  output=e.report.certificate.gains_text() if e.report is not None else "")
             for e in entries]
    if not entries:
        cases.append(Case(name=str(proofs), classname="check.certificates", failure=summary))
    return Section(title, columns, rows,
                   {"certificates": payload}, ok, notes, summary=summary,
                   counts={"certificates": len(entries), "certificates_proved": proved, "certificates_current": current},
                   cases=cases, streamed=stream and bool(names))


def _claim(entry: Any) -> str:
    """The ``kappa`` column: κ of a stability certificate, ``cycle`` for a hunting certificate, a template's own
    ``claim_column`` (``ρ≤…`` for a reset-contraction certificate)."""
    if entry.report is None:
        return "-"
    bound = getattr(entry.report.certificate, "overshoot_bound", None)
    return str(bound) if bound is not None else getattr(entry.report.certificate, "claim_column", "cycle")


def crosscheck_section(args: argparse.Namespace) -> Section:
    """The cross-check passes Table I's proved certificates and catches each wrong variant (:mod:`._crosscheck._selftest`).

    Uses ``DIR/case_{a,b}_tightest.json`` when they verify, else certifies
    Table I in memory.
    """
    from .._crosscheck._selftest import EXPECTED, crosscheck_self_test, table_i_certificates

    from .._infra.output import emit

    if not getattr(args, "json", False):
        emit("cross-check self-test: simulating Table I's certificates and wrong variants of them …")
    result = crosscheck_self_test(table_i_certificates(resolve_target(args).proofs))
    rows = [(f"({r.case})", r.variant, r.expected, ", ".join(r.caught_by) or "-", "ok" if r.ok else "NOT CAUGHT" if r.variant != "proved" else "FAILED")
            for r in result.rows]
    proved = [r for r in result.rows if r.variant == "proved"]
    wrong = [r for r in result.rows if r.variant in EXPECTED]
    kernel = [r for r in result.rows if r.case == "kernel"]
    guards = [r for r in result.rows if r.variant not in EXPECTED and r.variant != "proved" and r.case != "kernel"]
    summary = (
        f"cross-check self-test: {sum(r.ok for r in kernel)} of {len(kernel)} kernel runs match the reference, "
        f"{sum(r.ok for r in proved)} of {len(proved)} proved certificates pass, "
        f"{sum(r.ok for r in wrong)} of {len(wrong)} wrong certificates caught, "
        f"{sum(r.ok for r in guards)} of {len(guards)} refusals hold ({result.trajectories} trajectories)"
    )
    notes = [summary + f" ({result.seconds:.1f} s)"]
    notes += [f"FAILED cross-check self-test ({r.case}) {r.variant}: expected {r.expected}, got {', '.join(r.caught_by) or 'nothing'}"
              for r in result.rows if not r.ok]
    from .._infra.junit import Case

    cases = [Case(name=f"({r.case}) {r.variant}", classname="check.crosscheck_self_test",
                  failure=None if r.ok else f"expected {r.expected}, got {', '.join(r.caught_by) or 'nothing'}")
             for r in result.rows]
    return Section(
        "Cross-check self-test (it passes proved certificates and catches wrong ones)",
        ("case", "certificate", "must be", "failing properties", "verdict"),
        rows,
        {"crosscheck_self_test": [dataclasses_asdict(r) for r in result.rows]},
        result.ok,
        notes,
        summary=summary,
        counts={"selftest_rows": len(result.rows), "selftest_ok": sum(r.ok for r in result.rows)},
        cases=cases,
    )


SECTIONS: list[Callable[[argparse.Namespace], Section]] = [obligations_section, certificates_section, crosscheck_section,
                                                          self_check_section, independent_section]
"""The parts of ``check``, in order; append to extend the command."""


def _validate(args: argparse.Namespace) -> None:
    """Refuse a configuration or ``--proofs`` that cannot be what the user meant (exit 2), before any work."""
    from .._infra.errors import UsageError

    where = resolve_target(args)
    proofs = where.proofs
    if getattr(args, "no_certificates", False) and where.origin == "none":
        return
    if proofs.exists() and not proofs.is_dir():
        raise UsageError(f"--proofs {proofs} is not a directory")
    if not proofs.exists() and not args.write and not getattr(args, "no_certificates", False):
        raise UsageError(
            f"proofs directory {str(proofs)!r} does not exist; pass --proofs DIR with your certificates, "
            "--write to create it, or --no-certificates to check only the derivations"
        )


def run(args: argparse.Namespace) -> int:
    """Run every section, printing each as it is decided; 0 if all are satisfied, 1 otherwise (2 for bad usage)."""
    from .._infra.output import emit

    if getattr(args, "junit_xml", None) is not None:
        from .._infra.junit import check_writable

        check_writable(args.junit_xml)
    only = getattr(args, "only", None)
    if only:
        _validate_only(only)
    _validate(args)
    validate_smt(args)
    where = resolve_target(args)
    as_json = getattr(args, "json", False)
    if where.origin == "none":
        emit("note: no configuration found; checking the derivations only (--no-certificates)", err=as_json)
    elif where.origin not in ("--proofs",):
        emit(f"configuration: {where.origin} (proofs: {where.proofs})", err=as_json, level=2)
    sections = []
    makers = ([obligations_section] if only else SECTIONS) + ([smt_section] if wants_smt(args) else [])
    from ._parallel import run_sections

    _import_shared()
    for section in run_sections(list(makers), args, tail=_decide_tail if not only else [], together=TOGETHER,
                                context=_shared_derivations):
        sections.append(gate(section))
        if not as_json:
            if not section.streamed:
                emit(_format_table(section))
            emit()
            for note in section.notes:
                emit(_wrap(note), level=0 if _is_verdict(note) else 1)
    passed = all(s.ok for s in sections)
    last = closing_line(sections)
    if getattr(args, "junit_xml", None) is not None:
        from .._infra.junit import write_junit

        write_junit(args.junit_xml, "symbolic-friction check", [c for s in sections for c in s.cases])
    if as_json:
        payload: dict[str, Any] = {}
        counts: dict[str, int] = {}
        for s in sections:
            payload.update(s.json)
            counts.update(s.counts)
        payload["passed"] = passed
        payload["counts"] = counts
        payload["configuration"] = {
            "source": where.origin, "proofs": str(where.proofs), "report": where.report,
            "certificates": None if where.certificates is None else list(where.certificates), "only": only,
        }
        print(json.dumps(payload, indent=2, ensure_ascii=False), flush=True)
        for s in sections:
            for note in s.notes:
                emit(note, err=True, level=0 if _is_verdict(note) else 1)
        emit(last, err=True, level=0)
    else:
        emit(last, level=0)
    return 0 if passed else 1


def _validate_only(only: list[str]) -> None:
    from .._infra.errors import UsageError
    from .._obligations import all_obligations

    ids = [ob.id for ob in all_obligations()]
    unknown = [p for p in only if not any(_selected(i, [p]) for i in ids)]
    if unknown:
        parts = sorted({i.split(".")[0] for i in ids})
        raise UsageError(f"--only {', '.join(unknown)} selects no obligation; parts are: {', '.join(parts)}")
