"""``check --smt``: the obligations' algebra re-decided by an SMT solver (:mod:`symbolic_friction._obligations._smt`).

The section exports every obligation's recorded decisions as SMT-LIB 2 queries,
compares them with the committed ``<proofs>/smt/*.smt2`` (as ``obligations.md``
is compared: a missing, edited or extra file is ``STALE``; ``check --write``
regenerates them) and runs the solver on each.  It fails on a counterexample
(the solver's model of a claim's negation, which the row prints) and on a stale
file; a claim the solver does not decide in its time is reported (``timeout``,
``unknown``), never counted as confirmed.  Without ``--smt`` the section runs only
under ``--write`` where ``<proofs>/smt/`` exists (to write the files; no solver is needed for that).

Only the standard library is imported at module level (fast ``--help``).
"""

from __future__ import annotations

import argparse
import time

from ._sections import Section

__all__ = ["add_smt_arguments", "smt_section", "validate_smt", "wants_smt"]

_INSTALL = "pip install 'symbolic-friction[smt]'"


def add_smt_arguments(parser: argparse.ArgumentParser) -> None:
    """``--smt``, ``--smt-solver``, ``--smt-timeout`` and ``--smt-budget``."""
    parser.add_argument("--smt", action="store_true",
                        help="also re-decide every polynomial obligation with an SMT solver (z3 or cvc5; the extra [smt]) "
                        "and compare <proofs>/smt/*.smt2 with what check exports now")
    parser.add_argument("--smt-solver", choices=("z3", "cvc5"), default="z3", help="the solver of --smt (default z3)")
    parser.add_argument("--smt-timeout", metavar="SECONDS", default="10",
                        help="time limit of one solver call under --smt (default 10)")
    parser.add_argument("--smt-budget", metavar="SECONDS", default="60",
                        help="wall-clock budget of all solver calls under --smt (default 60); claims not started "
                        "by then count as timed out, never as confirmed")


def _seconds(text: str, option: str) -> float:
    """A number of seconds in (0, 86400], read exactly (ASCII decimals or fractions, as every option's number)."""
    from .._infra.errors import ParameterError
    from .._infra.rational import to_rational

    seconds = to_rational(text, name=option)
    if not 0 < seconds <= 86_400:
        raise ParameterError(f"{option} must be a number of seconds in (0, 86400]; got {text}")
    return float(seconds)


def wants_smt(args: argparse.Namespace) -> bool:
    """The section runs under ``--smt``, and under ``--write`` where ``<proofs>/smt/`` exists (not with ``--only``).

    A project opts in to the committed queries by creating the directory (``check --write --smt`` does), so
    ``check --write`` in a user's repository writes no 3 MB of SMT-LIB it did not ask for.
    """
    if getattr(args, "smt", False):
        return True
    if not getattr(args, "write", False) or getattr(args, "only", None):
        return False
    from ._sections import resolve_target

    return (resolve_target(args).proofs / "smt").is_dir()


def validate_smt(args: argparse.Namespace) -> None:
    """Refuse ``--smt`` without its solver, and non-positive time limits, before any work (exit 2)."""
    from .._infra.errors import UsageError

    timeout = _seconds(getattr(args, "smt_timeout", "10"), "--smt-timeout")
    budget = _seconds(getattr(args, "smt_budget", "60"), "--smt-budget")
    if not getattr(args, "smt", False):
        return
    from .._obligations._smt import solver_version

    try:
        solver_version(args.smt_solver)
    except ImportError:
        raise UsageError(f"check --smt needs the solver {args.smt_solver}, which is not installed: {_INSTALL}"
                         + (" (cvc5: pip install cvc5)" if args.smt_solver == "cvc5" else "")) from None
    args.smt_timeout_s, args.smt_budget_s = timeout, budget


def smt_section(args: argparse.Namespace) -> Section:
    """Export the obligations' claims; write (``--write``) or compare the files; under ``--smt`` solve them."""
    from .._infra.junit import Case
    from .._obligations import all_obligations
    from .._obligations._smt import export_smt, run_smt, smt_summary, solver_version, stale_smt, write_smt
    from ._sections import _selected, resolve_target

    only = getattr(args, "only", None)
    where = resolve_target(args)
    start = time.perf_counter()
    exported = export_smt([ob for ob in all_obligations() if _selected(ob.id, only)])
    exported_s = time.perf_counter() - start
    notes: list[str] = []
    ok = bool(exported)
    if only:
        file_state = "not compared (--only)"
    elif getattr(args, "write", False):
        written = write_smt(where.proofs, exported)
        file_state = f"{len(written)} written"
        notes.append(f"wrote {len(written)} SMT-LIB files under {where.proofs / 'smt'}")
    else:
        stale = stale_smt(where.proofs, exported)
        file_state = "up to date" if not stale else f"{len(stale)} STALE"
        for path, state in stale:
            ok = False
            notes.append(f"STALE: {path} is {state}; run `symbolic-friction check --write` and commit it")
    polynomial = sum(1 for ob in exported if ob.claims)
    if not getattr(args, "smt", False):
        summary = f"SMT files: {polynomial} obligations exported, {file_state} (solver not run; pass --smt)"
        return Section("SMT-LIB export", ("obligations", "files"), [(str(len(exported)), file_state)],
                       {"smt": {"exported": polynomial, "files": file_state}}, ok, [summary] + notes, summary=summary,
                       counts={"smt_exported": polynomial})
    solver = args.smt_solver
    start = time.perf_counter()
    outcomes = run_smt(exported, timeout_s=getattr(args, "smt_timeout_s", 10.0), budget_s=getattr(args, "smt_budget_s", 60.0),
                       solver=solver, workers=2)
    solved_s = time.perf_counter() - start
    bad = [o for o in outcomes if o.status == "counterexample"]
    ok = ok and not bad
    summary = f"{smt_summary(outcomes, solved_s, solver_version(solver))} (export {exported_s:.1f} s), files {file_state}"
    notes.insert(0, summary)
    notes += [f"FAILED smt {o.id}: counterexample: {o.reason}; model: " + ", ".join(f"{k} = {v}" for k, v in o.model)
              for o in bad]
    rows = [(o.id, o.status, f"{o.seconds:.2f}", f"{o.confirmed}/{o.claims}" if o.claims else "-", o.reason)
            for o in outcomes]
    confirmed = sum(1 for o in outcomes if o.status == "confirmed")
    cases = [Case(name=o.id, classname="check.smt", seconds=o.seconds,
                  failure=f"counterexample: {o.reason}" if o.status == "counterexample" else None,
                  output=f"{o.status}: {o.reason}" if o.reason else o.status)
             for o in outcomes]
    return Section(f"SMT ({solver}): every polynomial obligation re-decided",
                   ("id", "status", "seconds", "claims", "reason"), rows,
                   {"smt": {"solver": solver_version(solver), "outcomes": [o.as_json() for o in outcomes],
                            "files": file_state, "seconds": round(solved_s, 3)}},
                   ok, notes, summary=summary,
                   counts={"smt_obligations": len(outcomes), "smt_polynomial": sum(o.expressible for o in outcomes),
                           "smt_confirmed": confirmed, "smt_counterexamples": len(bad)},
                   cases=cases)
