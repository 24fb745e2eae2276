"""Data of ``closed_form.balanced`` (in :mod:`.closed_form`): its subject, its sample gains and the stated form.

:func:`~symbolic_friction._certify.closed_form.balanced` replaces the closed
form's ``k₁ = 2``, ``k₄``, ``ĉ₂`` by ``k₁ = k₄ = T`` and ``ĉ₂ = (T + k₃)/2``
(:func:`~symbolic_friction._certify.closed_form.balanced_formulas`), with ``T``
a rational upper root of ``(1+μ)k₃²``, wherever the two conditions of
:func:`~symbolic_friction._certify.closed_form.balanced_conditions` hold.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import sympy as sp

__all__ = ["BalancedSubject", "BALANCED_SAMPLES", "stated_mismatch"]

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


def stated_mismatch(base: Any, got: Any) -> str:
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
