"""The obligations' algebra re-decided by an SMT solver (``check --smt``; the optional extra ``[smt]``).

The obligations decide signs and identities for symbolic gains with the
package's own procedures.  This package records every decision an
obligation's verdict rests on while it runs (:mod:`._record`), writes each as
a query of nonlinear real arithmetic in SMT-LIB 2 whose ``unsat`` answer
confirms it (:mod:`._encode`), exports them per obligation to
``proofs/smt/<id>.smt2`` (:mod:`._export`) and runs z3 (or cvc5) on them
(:mod:`._run`).  A second prover that shares no code with the first, on the
very expressions the first decided.

What it re-checks, and what not: the decisions (``sign_of``, ``is_zero``,
``is_nonneg``, ``frac_sign``), each as a first-order statement about the
expression it was asked about; not the sympy computations that produced
those expressions (determinants, substitutions, solutions of equations), nor
checks an obligation makes without those procedures (structure, numeric
bindings), which is why some obligations have nothing to export.

Usage (what ``check --smt`` does)::

    exported = export_smt()                      # derive + verify every obligation, recording its claims
    outcomes = run_smt(exported, timeout_s=10)   # one SmtOutcome per obligation
    print(render_smt(outcomes, seconds))         # one line each, then the summary
    write_smt(proofs_dir, exported)              # check --write: proofs/smt/*.smt2
    stale_smt(proofs_dir, exported)              # check: [(path, "missing" | "stale" | "unexpected")]

A caller that already runs the obligations can record around its own run
instead of :func:`export_smt` (same files): ``with recording() as claims:``
around each obligation's run, then ``translate(ob, claims, verdict)``.

Examples
--------
>>> import sympy as sp
>>> from symbolic_friction._obligations._smt import Claim, encode
>>> k_p, k_i = sp.symbols("k_p k_i", positive=True)
>>> print(encode(Claim("nonneg", k_p - k_i, None, "declared")).text)
(declare-fun k_i () Real)
(declare-fun k_p () Real)
(assert (> k_i 0))
(assert (> k_p 0))
(assert (not (>= (+ k_p (* (- 1) k_i)) 0)))
"""

from __future__ import annotations

from ._encode import ClaimScript, NotExpressible, encode
from ._export import (
    SMT_DIR,
    SmtObligation,
    export_one,
    export_smt,
    smt_files,
    stale_smt,
    translate,
    write_smt,
)
from ._record import Claim, RawPolynomial, declare_claim, recording
from ._run import (
    STATUSES,
    ClaimAnswer,
    SmtOutcome,
    render_smt,
    run_smt,
    smt_summary,
    solve_claim,
    solver_version,
)

__all__ = [
    "SMT_DIR",
    "STATUSES",
    "Claim",
    "ClaimAnswer",
    "ClaimScript",
    "NotExpressible",
    "RawPolynomial",
    "SmtObligation",
    "SmtOutcome",
    "declare_claim",
    "encode",
    "export_one",
    "export_smt",
    "recording",
    "render_smt",
    "run_smt",
    "smt_files",
    "smt_summary",
    "solve_claim",
    "solver_version",
    "stale_smt",
    "translate",
    "write_smt",
]
