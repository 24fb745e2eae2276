"""``symbolic-friction check``: re-derive every proof obligation of the paper.

The command is a list of *sections* (:data:`SECTIONS`).  Each section is a
function ``(args) -> Section`` that does its work and returns its printable
table, its JSON members and whether it is satisfied; ``run`` prints them in
order and exits 0 only if every section is satisfied.  Further checks (for
example the exact verification of every certificate under ``proofs/``) are
added by appending a function to :data:`SECTIONS`.

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
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

HELP = "re-derive the paper's proof obligations for symbolic gains; exit 0 only if all hold"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """``--json``, ``--write`` and ``--proofs DIR``."""
    parser.add_argument("--json", action="store_true", help='print {"obligations": [...], "errata": [...]} as JSON instead of a table')
    parser.add_argument(
        "--write",
        action="store_true",
        help="regenerate DIR/obligations.md and Table I's certificates (atomically) instead of checking them",
    )
    parser.add_argument(
        "--proofs",
        metavar="DIR",
        default="proofs",
        help="directory of the committed proof files (default: proofs); it must exist unless --write creates it",
    )
    parser.add_argument(
        "--no-certificates",
        action="store_true",
        help="check only the derivations (and obligations.md); without it, check fails when no certificate was verified",
    )


@dataclass
class Section:
    """What one part of ``check`` found.

    Attributes
    ----------
    title : str
        Heading of the printed table.
    columns : tuple of str
        Column names of the printed table.
    rows : list of tuple of str
        Printed rows.
    json : dict
        Members merged into the ``--json`` object.
    ok : bool
        Whether this section is satisfied.
    notes : list of str
        Lines printed after the table (to stderr under ``--json``).
    summary : str
        One line saying what was checked, with counts (e.g. ``"27 of 27
        obligations hold"``); the closing line of ``check`` joins them.
    counts : dict
        The numbers behind ``summary`` (``--json``'s ``"counts"``).
    """

    title: str
    columns: tuple[str, ...]
    rows: list[tuple[str, ...]]
    json: dict[str, Any]
    ok: bool
    notes: list[str] = field(default_factory=list)
    summary: str = ""
    counts: dict[str, int] = field(default_factory=dict)


def _short(text: str, width: int) -> str:
    return text if len(text) <= width else text[: width - 1] + "…"


def obligations_section(args: argparse.Namespace) -> Section:
    """Run every obligation, list the errata and check or write the report."""
    from .._obligations import all_errata, all_obligations
    from .._obligations._base import FAILS, Result
    from .._report import render_report, report_path, write_atomic

    results: list[Result] = []
    for ob in all_obligations():
        start = time.perf_counter()
        try:
            results.append(ob.run())
        except Exception as exc:  # a crashing check is reported as failing, never as holding
            results.append(
                Result(
                    id=ob.id, paper=ob.paper, statement=ob.statement, method=ob.method, status=FAILS,
                    seconds=time.perf_counter() - start, reason=f"error while checking: {type(exc).__name__}: {exc}",
                )
            )
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
    proofs = Path(args.proofs)
    target = report_path(proofs)
    report_state = "up to date"
    if args.write:
        proofs.mkdir(parents=True, exist_ok=True)
        write_atomic(target, text)
        notes.append(f"wrote {target}")
        report_state = "written"
    elif not proofs.is_dir():
        # only reachable with --no-certificates (run() refuses a missing DIR otherwise)
        report_state = "not checked (no such directory)"
        notes.append(f"note: {proofs} does not exist; {target} was not compared")
    elif not target.is_file():
        ok = False
        report_state = "missing"
        notes.append(f"STALE: {target} is missing; run `symbolic-friction check --write` and commit it")
    elif target.read_bytes() != text.encode("utf-8"):
        ok = False
        report_state = "STALE"
        notes.append(f"STALE: {target} differs from what `check` derives now; run `symbolic-friction check --write` and commit it")

    rows = [
        (r.id, _short(r.paper, 36), _short(r.statement, 60), _short(r.method, 44), r.status, f"{r.seconds:.2f}")
        for r in results
    ]
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
        summary=f"{held} of {len(results)} obligations hold, {target} {report_state}",
        counts={"obligations": len(results), "obligations_hold": held},
    )


def certificates_section(args: argparse.Namespace) -> Section:
    """Verify every certificate under ``--proofs`` exactly and detect stale ones.

    A certificate is stale when it, or its Markdown report, differs from what
    ``symbolic-friction certify`` would write now (this re-runs the search,
    so it imports cvxpy).  Table I's four certificates must exist.
    """
    proofs = Path(args.proofs)
    if getattr(args, "no_certificates", False):
        return Section("Certificates", ("file", "proved", "up to date"), [], {"certificates": []}, True,
                       ["certificates: not checked (--no-certificates)"],
                       summary="certificates not checked (--no-certificates)", counts={"certificates": 0})
    from .._certify import TABLE_I_FILES, certify_table_i, check_committed_certificates

    written: list[str] = []
    if args.write:
        # --write regenerates everything under proofs/, certificates included, so one
        # command brings a checkout up to date; they are then verified like any other.
        written = [f"wrote {p}" for p in certify_table_i(proofs)]
    entries = check_committed_certificates(proofs, expected=TABLE_I_FILES)
    rows = [
        (str(e.path), "yes" if e.proved else "NO", "no" if e.stale else "yes",
         e.report.certificate.overshoot_bound if e.report is not None else "-")
        for e in entries
    ]
    ok = bool(entries) and all(e.ok for e in entries)
    proved = sum(e.proved for e in entries)
    current = sum(e.ok for e in entries)
    if entries:
        summary = f"{proved} of {len(entries)} certificates proved exactly, {current} of {len(entries)} up to date"
    else:
        summary = f"no certificates checked in {proofs} (pass --no-certificates to check only the derivations)"
    notes = [summary]
    notes += [e.describe() for e in entries if not e.ok]
    notes += written
    payload = [
        {"file": str(e.path), "proved": e.proved, "stale": e.stale, "reason": e.reason}
        for e in entries
    ]
    return Section("Certificates (exact re-verification)", ("file", "proved", "up to date", "kappa"), rows,
                   {"certificates": payload}, ok, notes, summary=summary,
                   counts={"certificates": len(entries), "certificates_proved": proved, "certificates_current": current})


def crosscheck_section(args: argparse.Namespace) -> Section:
    """The cross-check passes Table I's proved certificates and catches each wrong variant (:mod:`._crosscheck._selftest`).

    Uses ``DIR/case_{a,b}_tightest.json`` when they verify, else certifies
    Table I in memory.
    """
    from .._certify import certify, load, verify_certificate
    from .._crosscheck._selftest import EXPECTED, crosscheck_self_test
    from .._parameters import Parameters

    certificates = {}
    for case in ("a", "b"):
        path = Path(args.proofs) / f"case_{case}_tightest.json"
        cert = None
        if path.is_file():
            try:
                cert = load(path)
            except Exception:  # a malformed file is the certificates section's to report
                cert = None
        if cert is None or not verify_certificate(cert).proved:
            cert = certify(Parameters.table_i(case), mode="tightest")
        certificates[case] = cert
    result = crosscheck_self_test(certificates)
    rows = [(f"({r.case})", r.variant, r.expected, ", ".join(r.caught_by) or "-", "ok" if r.ok else "NOT CAUGHT" if r.variant != "proved" else "FAILED")
            for r in result.rows]
    proved = [r for r in result.rows if r.variant == "proved"]
    wrong = [r for r in result.rows if r.variant in EXPECTED]
    guards = [r for r in result.rows if r.variant not in EXPECTED and r.variant != "proved"]
    summary = (
        f"cross-check self-test: {sum(r.ok for r in proved)} of {len(proved)} proved certificates pass, "
        f"{sum(r.ok for r in wrong)} of {len(wrong)} wrong certificates caught, "
        f"{sum(r.ok for r in guards)} of {len(guards)} refusals hold ({result.trajectories} trajectories)"
    )
    notes = [summary + f" ({result.seconds:.1f} s)"]
    notes += [f"FAILED cross-check self-test ({r.case}) {r.variant}: expected {r.expected}, got {', '.join(r.caught_by) or 'nothing'}"
              for r in result.rows if not r.ok]
    return Section(
        "Cross-check self-test (it passes proved certificates and catches wrong ones)",
        ("case", "certificate", "must be", "failing properties", "verdict"),
        rows,
        {"crosscheck_self_test": [dataclasses_asdict(r) for r in result.rows]},
        result.ok,
        notes,
        summary=summary,
        counts={"selftest_rows": len(result.rows), "selftest_ok": sum(r.ok for r in result.rows)},
    )


def dataclasses_asdict(obj: Any) -> dict[str, Any]:
    import dataclasses

    return {k: (list(v) if isinstance(v, tuple) else v) for k, v in dataclasses.asdict(obj).items()}


SECTIONS: list[Callable[[argparse.Namespace], Section]] = [obligations_section, certificates_section, crosscheck_section]
"""The parts of ``check``, in order; append to extend the command."""


def _format_table(section: Section) -> str:
    widths = [len(c) for c in section.columns]
    for row in section.rows:
        widths = [max(w, len(cell)) for w, cell in zip(widths, row)]
    line = "  ".join("-" * w for w in widths)
    head = "  ".join(c.ljust(w) for c, w in zip(section.columns, widths))
    body = ["  ".join(cell.ljust(w) for cell, w in zip(row, widths)).rstrip() for row in section.rows]
    return "\n".join([section.title, head.rstrip(), line, *body])


def _crashed(make: Callable[[argparse.Namespace], Section], exc: Exception) -> Section:
    """A section that raised: reported as failing, never as passing."""
    name = getattr(make, "__name__", "section")
    reason = f"{name} crashed: {type(exc).__name__}: {exc}"
    return Section(name, ("error",), [(reason,)], {}, False, [f"FAILED {reason}"], summary=reason)


def _validate(args: argparse.Namespace) -> None:
    """Refuse a ``--proofs`` that cannot be what the user meant (exit 2), before any work."""
    from .._errors import UsageError

    proofs = Path(args.proofs)
    if proofs.exists() and not proofs.is_dir():
        raise UsageError(f"--proofs {proofs} is not a directory")
    if not proofs.exists() and not args.write and not getattr(args, "no_certificates", False):
        raise UsageError(
            f"proofs directory {str(proofs)!r} does not exist; pass --proofs DIR with your certificates, "
            "--write to create it, or --no-certificates to check only the derivations"
        )


def closing_line(sections: list[Section]) -> str:
    """``check: PASSED — …`` or ``check: FAILED — …`` (failed sections named first)."""
    failed = [s for s in sections if not s.ok]
    passed = [s for s in sections if s.ok]
    parts = [s.summary or s.title for s in failed + passed]
    return f"check: {'FAILED' if failed else 'PASSED'} — " + "; ".join(parts)


def run(args: argparse.Namespace) -> int:
    """Run every section; 0 if all are satisfied, 1 otherwise (2 for a bad ``--proofs``)."""
    _validate(args)
    sections = []
    for make in SECTIONS:
        try:
            sections.append(make(args))
        except Exception as exc:  # a crashing section fails loudly, it never passes
            sections.append(_crashed(make, exc))
    passed = all(s.ok for s in sections)
    last = closing_line(sections)
    if args.json:
        payload: dict[str, Any] = {}
        counts: dict[str, int] = {}
        for s in sections:
            payload.update(s.json)
            counts.update(s.counts)
        payload["passed"] = passed
        payload["counts"] = counts
        print(json.dumps(payload, indent=2, ensure_ascii=False))
        for s in sections:
            for note in s.notes:
                print(note, file=sys.stderr)
        print(last, file=sys.stderr)
    else:
        for s in sections:
            print(_format_table(s))
            print()
            for note in s.notes:
                print(note)
        print(last)
    return 0 if passed else 1
