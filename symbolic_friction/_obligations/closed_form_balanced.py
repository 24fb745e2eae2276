"""``closed_form.balanced`` — the closed form with ``k₁ = k₄`` proved for all gains where it applies.

:func:`~symbolic_friction._certify.closed_form.balanced` replaces the closed
form's ``k₁ = 2``, ``k₄``, ``ĉ₂`` by ``k₁ = k₄ = T`` and ``ĉ₂ = (T + k₃)/2``
(:func:`~symbolic_friction._certify.closed_form.balanced_formulas`), with ``T``
a rational upper root of ``(1+μ)k₃²``, wherever the two conditions of
:func:`~symbolic_friction._certify.closed_form.balanced_conditions` hold.  This
obligation runs those functions and the verifier's
:func:`~symbolic_friction._certify.verify.premises` on symbols and shows:

* for ``r = k_i/k_v > 1`` the second condition fails for every ``μ > 0``,
  ``k_p > 0`` and ``T ≥ 0`` with ``T² ≥ (1+μ)k₃²`` (so ``ρ = 1`` wherever the
  form applies), and where the conditions hold the code's ``ρ = max(r, 1)``
  picks 1;
* where the conditions hold, parametrised exactly by
  :func:`._closed_form_cases.balanced_cases` (boundaries as their own cases),
  every premise holds: a premise row equal to the ``k₁ = 2`` form's (the
  premises on ``P``, ``c₁``, ``c₂``, which the form does not change) is
  ``closed_form.all_gains``'; every other row is decided here, ``T`` entering
  as ``A + B·T`` with ``T² = (1+μ)k₃² + v``;
* the numeric builder gives these constants at sample gains.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import sympy as sp

from .._certify import verify as _verify
from .._certify.closed_form import (
    balanced,
    balanced_conditions,
    balanced_formulas,
    balanced_radicand,
    closed_form_constants,
    closed_form_formulas,
)
from ._base import Obligation, Outcome
from ._closed_form_cases import BASE, balanced_cases, decide_cases, decide_in, p_cases
from ._decide import is_zero
from .closed_form import _certificate, _rows, _SymOps

__all__ = ["ClosedFormBalanced", "BalancedSubject", "BALANCED_SAMPLES"]

_F = Fraction
BALANCED_SAMPLES: tuple[tuple[Fraction, Fraction, Fraction, bool], ...] = (
    (_F(75, 4), _F(33, 50), _F(1, 100), True),  # Table I, case (b), feasible
    (_F(75, 4), _F(33, 50), _F(1, 10**6), False),  # Table I, case (b), tightest
    (_F(10**12), _F(1, 10**6), _F(1, 10**6), False),  # ratios of 10¹²
)
"""Gains ``(a, k_p, μ, loose)`` at which :func:`balanced` applies and is compared with the stated form."""


@dataclass(frozen=True)
class BalancedSubject:
    """Per ``c₁`` choice: the rows of the ``k₁ = k₄`` form and of the ``k₁ = 2`` form; the conditions and picks."""

    rows: tuple[tuple[int, tuple, tuple], ...]  # (c1 choice, balanced rows, k₁ = 2 rows), ρ = 1
    region: tuple[tuple[str, sp.Expr], ...]  # the conditions' margins, ρ = 1
    rho_pick: sp.Expr  # 1 − 1/a: ρ = max(r, 1) picks 1
    radicand: sp.Expr  # (1+μ)k₃², ρ = 1
    above: tuple[tuple[str, sp.Expr], ...]  # the conditions' margins for r > 1
    radicand_above: sp.Expr
    samples: tuple[tuple[Fraction, Fraction, Fraction, bool, Any, Any], ...] = ()  # (a, k_p, μ, loose, k₁ = 2, balanced)


def _stated_mismatch(base: Any, got: Any) -> str:
    """Why ``got`` is not ``base`` with ``k₁ = k₄ = T``, ``ĉ₂ = (T + k₃)/2``, ``T ≥ 0``, ``T² ≥ (1+μ)k₃²`` (empty if it is)."""
    if got is None:
        return "balanced() did not apply"
    T = got.k1
    wrong = [n for n in ("k2", "k3", "c1", "c2", "c1_hat", "mu") if getattr(got, n) != getattr(base, n)]
    if not (T >= 0 and T * T >= (1 + base.mu) * base.k3 * base.k3):
        wrong.append("k1 (its T)")
    if got.k4 != T:
        wrong.append("k4")
    if got.c2_hat != (T + base.k3) / 2:
        wrong.append("c2_hat")
    return ", ".join(wrong)


class ClosedFormBalanced(Obligation):
    id = "closed_form.balanced"
    paper = "Lemma 3 (k₁ … k₄), Lemma 2, Proposition 1; the exact verifier's premises"
    statement = (
        "for all gains with k_v·k_p > k_i > 0, f_c > 0, all μ > 0 and all T ≥ 0 with T² ≥ (1+μ)k₃²: where "
        "T ≥ (1+μ)·2k_p and (1+μ)·T ≤ k₃·a, the closed form with k₁ = k₄ = T, ĉ₂ = (T + k₃)/2 satisfies every premise "
        "of the exact verifier; for k_i/k_v > 1 those conditions never hold"
    )
    method = (
        "balanced_formulas, balanced_conditions and verify.premises run on symbols; the conditions' set "
        "parametrised exactly (k_p = T/(2(1+μ)(1+α)), a = T(1+β)/2, T² = (1+μ)k₃² + v, each slack = 0 or > 0); "
        "rows unchanged from the k₁ = 2 form are closed_form.all_gains'; the others decided as A + B·T"
    )

    def derive(self) -> BalancedSubject:
        a, k_p, mu, T = BASE["a"], BASE["k_p"], BASE["mu"], BASE["R"]
        rows = []
        region: tuple = ()
        rho_pick = radicand = sp.Integer(0)
        for c1_choice in (0, 1):
            ops = _SymOps({"rho": 1, "k4": 0, "c1": c1_choice})
            base = closed_form_formulas(a, a, k_p, k_p, mu, ops)
            constants = {**base, **balanced_formulas(base["k3"], T)}
            rows.append((c1_choice, _rows(_verify.premises(_certificate(constants))), _rows(_verify.premises(_certificate(base)))))
            region = tuple((n, sp.sympify(m)) for n, m in balanced_conditions(a, k_p, base["k3"], mu, T))
            rho_pick = next(chosen - other for name, _, chosen, other in ops.picks if name == "rho")
            radicand = sp.sympify(balanced_radicand(base["k3"], mu))
        ops = _SymOps({"rho": 0, "k4": 0, "c1": 0})
        base = closed_form_formulas(a, a, k_p, k_p, mu, ops)
        above = tuple((n, sp.sympify(m)) for n, m in balanced_conditions(a, k_p, base["k3"], mu, T))
        samples = []
        for a_, kp, mu_, loose in BALANCED_SAMPLES:
            c = closed_form_constants(a_, a_, kp, kp, mu=mu_, loose=loose)
            samples.append((a_, kp, mu_, loose, c, balanced(c, a_, kp)))
        return BalancedSubject(tuple(rows), region, sp.sympify(rho_pick), radicand, above,
                               sp.sympify(balanced_radicand(base["k3"], mu)), tuple(samples))

    def verify(self, subject: BalancedSubject) -> Outcome:
        if not subject.rows or not subject.region or not subject.samples:
            return Outcome.fail("the subject has no premise rows, no conditions or no numeric samples")
        # the cases are written for the stated conditions: the code's must be those, or the cases would not cover them
        a, k_p, mu, T = BASE["a"], BASE["k_p"], BASE["mu"], BASE["R"]
        stated = (T - (1 + mu) * 2 * k_p, 2 * (1 + mu) * a - (1 + mu) * T)  # k₃ = 2(1+μ) where ρ = 1
        if len(subject.region) != 2 or any(not is_zero(m - want) for (_, m), want in zip(subject.region, stated)):
            return Outcome.fail("the code's conditions are not the stated T ≥ (1+μ)·2k_p and (1+μ)·T ≤ k₃·a: "
                                + "; ".join(f"{n}: {m} ≥ 0" for n, m in subject.region))
        cases, cases_above = balanced_cases(1), balanced_cases(0)
        # r > 1: the second condition (1+μ)·T ≤ k₃·a fails, so the form never applies there
        name, margin = subject.above[-1]
        why = decide_cases(-margin, ">", cases_above, subject.radicand_above)
        if why:
            return Outcome.fail(f"for r > 1 the condition {name} is not shown to fail in the case {why}")
        # ρ = 1: the cases lie in the conditions' set, and the code's max(r, 1) picks 1 there
        for name, margin in subject.region:
            why = decide_cases(margin, ">=", cases, subject.radicand)
            if why:
                return Outcome.fail(f"the case {why} is not inside the condition {name}")
        why = decide_cases(subject.rho_pick, ">=", cases, subject.radicand)
        if why:
            return Outcome.fail(f"ρ = max(r, 1) does not pick 1 in the case {why}")
        decided = kept = 0
        for c1_choice, rows, base_rows in subject.rows:
            same = {(n, k): m for n, m, k in base_rows}
            cases_p = p_cases(c1_choice)
            for name, margin, kind in rows:
                if BASE["R"] not in margin.free_symbols and (name, kind) in same and is_zero(margin - same[(name, kind)]):
                    kept += 1  # the k₁ = 2 form's own row: closed_form.all_gains
                    continue
                decided += 1
                why = decide_in(margin, kind, cases_p, cases, subject.radicand)
                if why:
                    return Outcome.fail(f"premise {name} ({kind} 0) is not proved in the case {why} (c₁ choice {c1_choice + 1})")
        if not decided:
            return Outcome.fail("no premise row differs from the k₁ = 2 form: nothing was decided")
        for a_, kp, mu_, loose, base, got in subject.samples:
            why = _stated_mismatch(base, got)
            if why:
                return Outcome.fail(f"balanced() at a = {a_}, k_p = {kp}, μ = {mu_} differs from the stated form in {why}")
        return Outcome(True, f"{decided} premise rows decided over {len(cases)} cases of the conditions' set, "
                             f"{kept} unchanged from closed_form.all_gains; for r > 1 the conditions fail "
                             f"({len(cases_above)} cases); the numeric builder is the stated form at {len(subject.samples)} gains")


OBLIGATIONS: tuple[type[Obligation], ...] = (ClosedFormBalanced,)
