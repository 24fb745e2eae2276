"""The certificate verifier bound to the proof.

A certificate (``symbolic-friction certify``) claims that its constants make
Lemma 2, Lemma 3 and Proposition 1 hold for its gains, with overshoot bound
``κ``.  The exact verifier (:mod:`symbolic_friction._certify.verify`) decides
a fixed list of inequalities.  These obligations prove that the list is
enough, so that a verifier with a premise dropped or weakened fails
``check`` itself and not only a committed report:

* ``certificate.verifier`` — the verifier's premise builder, run with
  *symbolic* constants, implies every claim of a certificate, each claim
  built from the package's model: Assumption 1 (``lemma2.P``), ``c`` equal to
  the decrease rate of ``lemma2.dVdt``, ``c₁ > 0`` and ``P - c₁I ⪰ 0``
  (Lemma 2 item 1; every principal minor), ``c₂I - P ⪰ 0`` (eq. VandR),
  ``ĉ₁ > 0``, ``ĉ₁ ≤ k_j/2`` and ``ĉ₂I - K/2 ⪰ 0`` (eq. hatVandHatR for the
  nonnegative ``w = (|σ|, |dz(φ)|, |v|)``, which needs ``k₃ ≥ 0``), ``k_j > 0``
  and the conditions that ``lemma3.hatV_derivative`` *derives* from ``V̂``
  and ``F`` (eq. hatVdot), and ``κ > 0``, ``κ² ≥ c₂ĉ₂/(c₁ĉ₁)`` with
  ``c₁ ≤ c₂``, ``ĉ₁ ≤ ĉ₂`` (eq. stabState).  A claim is supported by a premise
  when their margins are equal or one is a positive multiple of the other
  (sign decided exactly), with a strict premise for a strict claim.
* ``certificate.verifier_decision`` — the verifier's exact decision (its
  comparison table, its semidefiniteness test by principal minors, and
  :meth:`~symbolic_friction._model.kconditions.Condition.holds`) on boundary
  instances: ``lhs = rhs`` against strict and non-strict premises, a
  symmetric matrix whose leading minors are all ``≥ 0`` but which is not
  semidefinite, a singular semidefinite matrix.
(Assumption 1's encoding, ``assumption1.encoding``, is in :mod:`.assumption1`.)
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import sympy as sp

from .._certify import verify as _verify
from .._model.kconditions import Condition
from .._model.lyapunov import lyapunov_matrix_entries, vhat_matrix_entries
from . import _fastpoly as fp
from ._base import Obligation, Outcome
from ._decide import G, is_zero, latex, sign_of
from .lemma2 import decrease_rate
from .lemma3 import HatVDerivative, derived_k_conditions, k_symbols

__all__ = ["Claim", "VerifierSubject", "CertificateVerifier", "VerifierDecision", "OBLIGATIONS"]


@dataclass(frozen=True)
class Claim:
    """One thing a certificate claims: ``margin > 0`` (``strict``) or ``≥ 0``, or ``= 0`` (``equal``)."""

    where: str
    text: str
    margin: sp.Expr
    strict: bool = False
    equal: bool = False


@dataclass(frozen=True)
class SymbolicCertificate:
    """A certificate whose numbers are symbols (the verifier's builder reads these attributes)."""

    k_p: Any
    k_i: Any
    k_v: Any
    f_c: Any
    k1: Any
    k2: Any
    k3: Any
    k4: Any
    c: Any
    c1: Any
    c2: Any
    c1_hat: Any
    c2_hat: Any
    kappa: Any


@dataclass(frozen=True)
class VerifierSubject:
    """The verifier's premises for symbolic constants, and the claims built from the model."""

    premises: tuple[tuple[str, sp.Expr, str], ...]
    claims: tuple[Claim, ...]


def _symbolic_certificate() -> SymbolicCertificate:
    g = G()
    k1, k2, k3, k4 = k_symbols()
    c, c1, c2, c1h, c2h, kappa = sp.symbols("c c_1 c_2 chat_1 chat_2 kappa", positive=True)
    return SymbolicCertificate(g.k_p, g.k_i, g.k_v, g.f_c, k1, k2, k3, k4, c, c1, c2, c1h, c2h, kappa)


def _premise_rows(premises: list[Any]) -> tuple[tuple[str, sp.Expr, str], ...]:
    """``(name, margin, kind)`` for every premise; a semidefiniteness premise gives one row per principal minor."""
    rows: list[tuple[str, sp.Expr, str]] = []
    for p in premises:
        if isinstance(p, _verify.Semidefinite):
            for idx, minor in p.minors():
                rows.append((f"{p.name} [minor {{{','.join(str(i + 1) for i in idx)}}}]", fp.expand(minor), ">="))
        else:
            margin, kind = p.margin()
            rows.append((p.name, sp.expand(margin), kind))
    return tuple(rows)


def _psd_claims(where: str, text: str, matrix: sp.Matrix) -> list[Claim]:
    n = matrix.shape[0]
    import itertools

    return [
        Claim(where, f"{text}: principal minor {{{','.join(str(i + 1) for i in idx)}}} ≥ 0", fp.expanded_det(matrix.extract(list(idx), list(idx))))
        for size in range(1, n + 1)
        for idx in itertools.combinations(range(n), size)
    ]


def certificate_claims(cert: SymbolicCertificate) -> list[Claim]:
    """What a certificate claims, built from the package's model (never from the verifier)."""
    g = G()
    P = sp.Matrix(lyapunov_matrix_entries(cert.k_p, cert.k_i, cert.k_v))
    K = sp.Matrix(vhat_matrix_entries(cert.k1, cert.k2, cert.k3, cert.k4))
    eye = sp.eye(3)
    rate = decrease_rate(g).xreplace({g.k_p: cert.k_p, g.k_i: cert.k_i, g.k_v: cert.k_v})
    claims = [
        Claim("Assumption 1", "k_i > 0", cert.k_i, strict=True),
        Claim("Assumption 1", "k_p > 0", cert.k_p, strict=True),
        Claim("Assumption 1", "k_v k_p > k_i", cert.k_v * cert.k_p - cert.k_i, strict=True),
        Claim("model", "f_c > 0", cert.f_c, strict=True),
        Claim("Lemma 2, item 2 (eq. dVdt)", "c is the decrease rate of lemma2.dVdt", cert.c - rate, equal=True),
        Claim("Lemma 2, item 1", "c₁ > 0", cert.c1, strict=True),
        *_psd_claims("Lemma 2, item 1", "P − c₁I ⪰ 0", P - cert.c1 * eye),
        *_psd_claims("Lemma 3, eq. (VandR)", "c₂I − P ⪰ 0", cert.c2 * eye - P),
        Claim("Lemma 3, eq. (hatVandHatR)", "ĉ₁ > 0", cert.c1_hat, strict=True),
        *[Claim("Lemma 3, eq. (hatVandHatR)", f"ĉ₁ ≤ k{j}/2", kj / 2 - cert.c1_hat) for j, kj in ((1, cert.k1), (2, cert.k2), (4, cert.k4))],
        *_psd_claims("Lemma 3, eq. (hatVandHatR)", "ĉ₂I − K/2 ⪰ 0", cert.c2_hat * eye - K / 2),
        *[Claim("Lemma 3 (k₁ … k₄ positive)", f"k{j} > 0", kj, strict=True) for j, kj in enumerate((cert.k1, cert.k2, cert.k3, cert.k4), 1)],
    ]
    # the conditions lemma3.hatV_derivative derives from V̂ and F (their non-strict form suffices)
    derived, failures, _ = derived_k_conditions(HatVDerivative().derive())
    if failures:
        claims.append(Claim("Lemma 3, eq. (hatVdot)", "the derivation of the k-conditions: " + "; ".join(failures), sp.Integer(-1), strict=True))
    for d in derived:
        claims.append(Claim("Lemma 3, eq. (hatVdot)", f"{d.origin}: {sp.sstr(d.expr)} ≥ 0", d.expr))
    claims += [
        Claim("Proposition 1, eq. (stabState)", "c₁ ≤ c₂", cert.c2 - cert.c1),
        Claim("Proposition 1, eq. (stabState)", "ĉ₁ ≤ ĉ₂", cert.c2_hat - cert.c1_hat),
        Claim("Proposition 1, eq. (stabState)", "κ > 0", cert.kappa, strict=True),
        Claim(
            "Proposition 1, eq. (stabState)",
            "κ² ≥ c₂ĉ₂/(c₁ĉ₁)",
            cert.kappa**2 - (cert.c2 * cert.c2_hat) / (cert.c1 * cert.c1_hat),
        ),
    ]
    return claims


@functools.lru_cache(maxsize=1024)
def _symbols(expr: sp.Expr) -> frozenset:
    # each margin's free symbols once: every claim is compared with every premise
    return frozenset(expr.free_symbols)


def _supports(premise: tuple[str, sp.Expr, str], claim: Claim) -> bool:
    """Whether the premise ``margin kind 0`` implies the claim, decided exactly."""
    _, margin, kind = premise
    if _symbols(margin) != _symbols(claim.margin):
        return False  # neither equal nor a multiple by a factor of the shared symbols
    if claim.equal:
        return kind == "==" and is_zero(fp.expand(margin - claim.margin))
    if claim.strict and kind != ">":
        return False
    if kind == "==":
        return False
    if is_zero(fp.expand(margin - claim.margin)):
        return True
    if margin == 0:
        return False
    # the claim's margin is a positive multiple of the premise's (sign_of reduces the fraction itself)
    return sign_of(claim.margin / margin) == 1


class CertificateVerifier(Obligation):
    id = "certificate.verifier"
    paper = "Lemma 2 item 1; eqs. (dVdt), (VandR), (hatVandHatR), (hatVdot), (stabState)"
    statement = (
        "the exact verifier's inequalities, built for symbolic constants, imply every claim of a certificate "
        "(Assumption 1, c, c₁, c₂, ĉ₁, ĉ₂, the derived k-conditions, κ), each claim built from the package's model"
    )
    method = (
        "run the verifier's premise builder on symbols; every claim (every principal minor of a claimed "
        "PSD matrix) must equal a premise's margin or be a positive multiple of it, with a strict premise for a strict claim"
    )

    def derive(self) -> VerifierSubject:
        cert = _symbolic_certificate()
        return VerifierSubject(premises=_premise_rows(_verify.premises(cert)), claims=tuple(certificate_claims(cert)))

    def verify(self, subject: VerifierSubject) -> Outcome:
        unsupported = [c for c in subject.claims if not any(_supports(p, c) for p in subject.premises)]
        if unsupported:
            listed = "; ".join(f"{c.where}: {c.text}" for c in unsupported[:6])
            more = f" (and {len(unsupported) - 6} more)" if len(unsupported) > 6 else ""
            return Outcome.fail(f"no premise of the verifier implies: {listed}{more}")
        details = (
            ("\\text{premises (minors counted)}", str(len(subject.premises))),
            ("\\text{claims supported}", str(len(subject.claims))),
            ("\\kappa^2", latex(sp.Symbol("kappa") ** 2) + " \\ge \\frac{c_2\\hat c_2}{c_1\\hat c_1}"),
        )
        return Outcome(True, f"all {len(subject.claims)} claims follow from the verifier's {len(subject.premises)} premises", details)


@dataclass(frozen=True)
class DecisionSubject:
    """The verifier's exact decision procedure and the condition test of :mod:`symbolic_friction._model.kconditions`."""

    decide: Callable[[Any], Any]
    inequality: Callable[..., Any]
    semidefinite: Callable[..., Any]
    condition: Callable[..., Condition]


_ONE, _TWO = Fraction(1), Fraction(2)
# (lhs, op, rhs, expected verdict): every operator on and off its boundary
_COMPARISONS = tuple(
    (lhs, op, rhs, {">": lhs > rhs, ">=": lhs >= rhs, "<=": lhs <= rhs, "==": lhs == rhs}[op])
    for op in (">", ">=", "<=", "==")
    for lhs, rhs in ((_ONE, _ONE), (_ONE, _TWO), (_TWO, _ONE))
)
_MATRICES = (
    # leading principal minors 1, 0, 0 are all ≥ 0, yet the minor {3} is -1: not semidefinite
    (((1, 0, 0), (0, 0, 0), (0, 0, -1)), False),
    (((0, 0, 0), (0, 1, 0), (0, 0, 0)), True),  # singular, semidefinite
    (((1, 1, 0), (1, 1, 0), (0, 0, 2)), True),  # singular, semidefinite, off-diagonal
    (((1, 2, 0), (2, 1, 0), (0, 0, 1)), False),  # indefinite: minor {1,2} = -3
)


class VerifierDecision(Obligation):
    id = "certificate.verifier_decision"
    paper = "Standard of proof: exact rationals decide every inequality"
    statement = (
        "the verifier decides >, ≥, ≤, = exactly on and off the boundary, tests semidefiniteness by all principal "
        "minors (rejecting a matrix whose leading minors are ≥ 0), and Condition.holds is strict"
    )
    method = "the verifier's own decision code run on 12 boundary comparisons, 4 matrices and 3 k-conditions, each with a known verdict"

    def derive(self) -> DecisionSubject:
        from .._model.kconditions import k_conditions

        def condition(lhs: Fraction, rhs: Fraction) -> Condition:
            cond = k_conditions(1, 1, 1, 1, 1, 1, 1)[5]  # "k3 > k2": a real condition object
            return Condition(cond.name, lhs, rhs, cond.kind, cond.source)

        return DecisionSubject(
            decide=_verify.decide, inequality=_verify.Inequality, semidefinite=_verify.Semidefinite, condition=condition
        )

    def verify(self, subject: DecisionSubject) -> Outcome:
        for lhs, op, rhs, want in _COMPARISONS:
            got = subject.decide(subject.inequality("x", "x", lhs, op, rhs)).holds
            if got is not want:
                return Outcome.fail(f"the verifier decides {lhs} {op} {rhs} as {got}; it is {want}")
        for m, want in _MATRICES:
            matrix = tuple(tuple(Fraction(x) for x in row) for row in m)
            got = subject.decide(subject.semidefinite("x", "M ⪰ 0", matrix)).holds
            if got is not want:
                return Outcome.fail(f"the verifier decides {m} ⪰ 0 as {got}; it is {want}")
        for lhs, rhs in ((_ONE, _ONE), (_ONE, _TWO), (_TWO, _ONE)):
            got = subject.condition(lhs, rhs).holds()
            if got is not (lhs > rhs):
                return Outcome.fail(f"Condition.holds decides {lhs} > {rhs} as {got}; it is {lhs > rhs}")
        return Outcome(True, f"{len(_COMPARISONS)} comparisons, {len(_MATRICES)} matrices and 3 k-conditions decided correctly")


OBLIGATIONS = (CertificateVerifier, VerifierDecision)
