"""Each obligation's claims as SMT-LIB 2 text: :func:`export_smt` and the committed files under ``proofs/smt/``.

:func:`export_smt` runs every obligation's ``derive`` and ``verify`` under
:func:`._record.recording` and translates each recorded claim
(:func:`._encode.encode`); equal queries are kept once and sorted, so the
export does not depend on the order in which a verifier happened to ask.

:func:`smt_files` renders one ``<id>.smt2`` per obligation with at least one
expressible claim: a header naming the obligation and what a block means,
then one block per claim (``set-logic``, its declarations, hypotheses and
negated claim, an ``echo`` naming it and the answer expected, ``check-sat``
and ``reset``).  Any SMT-LIB 2 solver runs the file as it is (``z3 FILE``,
``cvc5 FILE``).  The files hold no timings, versions or
paths, so the same code writes the same bytes; :func:`write_smt` writes them
atomically (and removes ``*.smt2`` files no longer produced) and
:func:`stale_smt` compares, byte for byte, as for ``proofs/obligations.md``.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ._encode import ClaimScript, NotExpressible, describe, encode
from ._record import Claim, recording

__all__ = ["SMT_DIR", "SmtObligation", "export_smt", "smt_files", "stale_smt", "write_smt"]

SMT_DIR = "smt"
"""The files' directory under the proofs directory (``proofs/smt/``)."""


@dataclass(frozen=True)
class SmtObligation:
    """One obligation's claims, translated.

    Attributes
    ----------
    id, statement : str
        The obligation's.
    verdict : str
        ``"holds"`` or ``"fails"``: what the package's own check decided while its claims were recorded.
    claims : tuple of ClaimScript
        The expressible claims, deduplicated and sorted.
    inexpressible : tuple of (str, str)
        ``(claim, reason)`` for each claim outside the translation (deduplicated).
    reason : str
        Why nothing was recorded (no claim at all), else ``""``.
    """

    id: str
    statement: str
    verdict: str
    claims: tuple[ClaimScript, ...]
    inexpressible: tuple[tuple[str, str], ...] = ()
    reason: str = ""

    @property
    def expressible(self) -> bool:
        """A polynomial obligation: at least one claim, and every claim translated."""
        return bool(self.claims) and not self.inexpressible

    @property
    def file_name(self) -> str:
        """``<id>.smt2``."""
        return f"{self.id}.smt2"


_PLAIN = {"≻": ">-", "≺": "-<", "⪰": ">=", "⪯": "<=", "⇔": "<=>", "⇒": "=>", "⇐": "<=", "→": "->", "↦": "|->",
          "≥": ">=", "≤": "<=", "≠": "!=", "≡": "==", "∈": "in", "∀": "for all", "∃": "exists", "·": "*", "×": "x",
          "−": "-", "∓": "-+", "±": "+-", "√": "sqrt", "∞": "oo", "²": "^2", "³": "^3", "₁": "1", "₂": "2",
          "₃": "3", "₄": "4", "₀": "0", "…": "...", "—": "--", "–": "-", "’": "'", "σ": "sigma", "φ": "phi",
          "δ": "delta", "ε": "eps", "λ": "lambda", "μ": "mu", "ρ": "rho", "τ": "tau", "κ": "kappa", "𝒜": "A"}


def _ascii(text: str) -> str:
    """``text`` in ASCII for an SMT-LIB comment: common mathematical signs spelled out, others as ``\\uXXXX``."""
    plain = "".join(_PLAIN.get(c, c) for c in text.replace("\n", " "))
    return plain.encode("ascii", "backslashreplace").decode("ascii")


def _no_claims_reason(ob: Any, numerals: int) -> str:
    if numerals:
        return (f"nothing symbolic to re-check: its {numerals} decision(s) are about numerals (sympy's expand or cancel had "
                f"reduced each identity to 0 before is_zero saw it); its method: {ob.method}")
    return f"no decision of sign_of, is_zero, is_nonneg or frac_sign to re-check; its method: {ob.method}"


def export_one(ob: Any) -> SmtObligation:
    """Run ``ob`` (``derive`` and ``verify``) while recording its decisions, and translate them."""
    with recording() as claims:
        try:
            verdict = "holds" if ob.run().holds else "fails"
        except Exception as exc:  # noqa: BLE001 - a crashing check asserts nothing; it is reported, never exported as proved
            return SmtObligation(ob.id, ob.statement, "fails", (), (), f"error while checking: {type(exc).__name__}: {exc}")
    return translate(ob, claims, verdict)


def translate(ob: Any, claims: Sequence[Claim], verdict: str = "holds") -> SmtObligation:
    """The claims recorded while ``ob`` ran (:func:`._record.recording`), translated, deduplicated and sorted.

    For a caller that records around its own run of the obligations (``run_checked`` with an ``on_result``
    that cuts the recorded list per obligation) instead of :func:`export_one`.
    """
    scripts: dict[tuple[str, str], ClaimScript] = {}
    bad: dict[str, str] = {}
    numerals = 0
    seen: set[Claim] = set()
    for claim in claims:
        if getattr(claim.expr, "is_Number", False):  # a decision about a numeral: nothing symbolic to re-decide
            numerals += 1
            continue
        try:  # the same decision made again (most are: 7,309 claims, 1,133 distinct) gives the same script
            if claim in seen:
                continue
            seen.add(claim)
        except TypeError:  # an unhashable expression (a mutable matrix) is encoded each time, as before
            pass
        try:
            script = encode(claim)
        except NotExpressible as exc:
            bad.setdefault(describe(claim), str(exc))
            continue
        scripts.setdefault((script.label, script.text), script)
    ordered = tuple(scripts[k] for k in sorted(scripts))
    reason = "" if (ordered or bad) else _no_claims_reason(ob, numerals)
    return SmtObligation(ob.id, ob.statement, verdict, ordered, tuple(sorted(bad.items())), reason)


def export_smt(obligations: Iterable[Any] | None = None) -> list[SmtObligation]:
    """The claims of ``obligations`` (default: every obligation, in paper order) as SMT-LIB queries.

    Each obligation is derived and verified again, with its decisions recorded (about as long as
    ``check``'s obligations section on one core).
    """
    if obligations is None:
        from .. import all_obligations

        obligations = all_obligations()
    return [export_one(ob) for ob in obligations]


_HEADER = """\
; SMT-LIB 2 queries of the proof obligation `{id}`: {statement}
; Generated by `symbolic-friction check --write`; do not edit by hand.
;
; Each block is one claim that the obligation's verdict rests on, as the package's decision
; procedures (sign_of, is_zero, is_nonneg, frac_sign) decided it for symbolic gains. A block
; declares the claim's symbols as reals, asserts their sympy assumptions (positive: > 0) and the
; conditions under which the expression is defined (every divisor != 0), and then the
; NEGATION of the claim: `unsat` confirms the claim, `sat` refutes it (the model is a counterexample).
; A claim "!= 0 somewhere" is existential: its block asserts the claim itself and expects `sat`.
; The echo before each check-sat names the claim and the answer expected. Blocks are separated
; by (reset), not push/pop, so that every query is solved on its own, non-incrementally (z3's
; incremental solver stalls on large polynomials that its nlsat decides in a moment).
;
; Run: z3 {file}    or    cvc5 {file}
; {count} claim{s}.
"""


def render_file(ob: SmtObligation) -> str:
    """The text of ``<id>.smt2`` (ASCII, ends with a newline)."""
    n = len(ob.claims)
    out = [_HEADER.format(id=ob.id, statement=_ascii(ob.statement), file=ob.file_name, count=n, s="" if n == 1 else "s")]
    for k, c in enumerate(ob.claims, 1):
        out.append(f"; claim {k} of {n}: {c.label}")
        out.append("(set-logic QF_NRA)")
        out.append(c.text)
        out.append(f'(echo "{ob.id} claim {k}: expect {c.expect}")')
        out.append("(check-sat)")
        out.append("(reset)\n")
    out.append("(exit)")
    return "\n".join(out) + "\n"


def smt_files(exported: Sequence[SmtObligation]) -> dict[str, str]:
    """``{file name: text}`` for every obligation with at least one expressible claim."""
    return {ob.file_name: render_file(ob) for ob in exported if ob.claims}


def _directory(proofs_dir: str | os.PathLike[str]) -> Path:
    return Path(proofs_dir) / SMT_DIR


def write_smt(proofs_dir: str | os.PathLike[str], exported: Sequence[SmtObligation]) -> list[Path]:
    """Write ``<proofs_dir>/smt/*.smt2`` atomically and remove the ``*.smt2`` files no longer produced.

    Returns the paths written, sorted.
    """
    from ..._infra.io import ensure_directory
    from .._report import write_atomic

    files = smt_files(exported)
    if not files and not _directory(proofs_dir).exists():
        return []  # nothing to write: no empty directory is made
    target = ensure_directory(_directory(proofs_dir), what="SMT directory")
    written = []
    for name in sorted(files):
        write_atomic(target / name, files[name])
        written.append(target / name)
    for path in sorted(target.glob("*.smt2")):
        if path.name not in files:
            path.unlink()
    return written


def stale_smt(proofs_dir: str | os.PathLike[str], exported: Sequence[SmtObligation]) -> list[tuple[Path, str]]:
    """``[(path, state)]`` for every file that is not up to date; empty when all are.

    ``state`` is ``"missing"`` (not committed), ``"stale"`` (its bytes differ from what
    :func:`write_smt` would write now) or ``"unexpected"`` (a ``*.smt2`` file no obligation produces).
    """
    from .._report import compare_report

    target = _directory(proofs_dir)
    files = smt_files(exported)
    out = []
    for name in sorted(files):
        state = compare_report(target / name, files[name])
        if state != "up to date":
            out.append((target / name, state))
    if target.is_dir():
        out += [(p, "unexpected") for p in sorted(target.glob("*.smt2")) if p.name not in files]
    return out
