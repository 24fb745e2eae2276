"""The chain of inequalities behind Proposition 1's stability bound (eq. stabState): premises from Lemma 2 and Lemma 3, steps, the goal, and the checks that the chain is closed and its witnesses hold; used by :mod:`.prop1`."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy as sp

from ._decide import G, Undecided, decide, is_zero, latex, resolve_piecewise
from ._inequalities import Case, case_grid, phi_cases, sign_cases
from ._shared import distance_squared, shared_value
from ._statements import (
    lemma2_decrease,
    lemma2_lower_bound,
    lemma3_hatV_bounds,
    lemma3_hatV_nonincreasing,
    lemma3_V_bounds,
)
from .lemma3 import in_R, region_R


@dataclass(frozen=True)
class Ineq:
    """``lhs ≤ rhs``."""

    lhs: sp.Expr
    rhs: sp.Expr

    @property
    def gap(self) -> sp.Expr:
        """``rhs - lhs`` (nonnegative when the inequality holds)."""
        return sp.sympify(self.rhs) - sp.sympify(self.lhs)

    def latex(self) -> str:
        return f"{latex(self.lhs)} \\le {latex(self.rhs)}"


@dataclass(frozen=True)
class Premise:
    """An analytic fact taken from an earlier result, with its justification."""

    name: str
    claim: Ineq
    why: str


@dataclass(frozen=True)
class Step:
    """``claim`` follows from ``uses`` with nonnegative ``multipliers``."""

    name: str
    claim: Ineq
    uses: tuple[str, ...]
    multipliers: tuple[sp.Expr, ...]
    why: str


@dataclass(frozen=True)
class Goal:
    """In case ``case``, step ``step`` must be ``c₁ĉ₁·distance ≤ c₂ĉ₂·|x(0)|²_𝒜``."""

    case: str
    step: str
    distance: sp.Symbol


@dataclass(frozen=True)
class StabilitySubject:
    """What ``prop1.stability_bound`` checks.

    Attributes
    ----------
    c1, c2, c1_hat, c2_hat : Symbol
        Positive constants of Lemma 3.
    d0 : Symbol
        ``|x(0)|²_𝒜``.
    premises : tuple of Premise
    steps : tuple of Step
        In order; a step may use premises and earlier steps.
    goals : tuple of Goal
        Together they cover every ``t ≥ 0`` in both cases.
    kappa : Expr
        ``√(c₂ĉ₂/(c₁ĉ₁))``.
    kappa_step : str
        The step proving ``c₁ĉ₁ ≤ c₂ĉ₂`` (so ``κ ≥ 1``).
    region : Expr
        ``R = {region ≥ 0}``.
    closed_form : tuple of tuple of (Expr, str)
        ``R`` as a union of sets, each an intersection of relations
        ``expr rel 0`` with ``rel`` in ``≥, ≤, =`` (closed sets).
    witnesses : tuple of (str, tuple, bool)
        ``(name, x, in_R)``: points with ``|x|²_𝒜 = 1`` used by the premises
        that give ``c₁ ≤ c₂`` and ``ĉ₁ ≤ ĉ₂``.
    dist2 : Expr
        ``|x|²_𝒜`` (eq. distFromA).
    state : tuple of Symbol
        ``(σ, φ, v)``.
    cases : tuple of Case
        Split of ``(v, φ)`` for the closedness check.
    """

    c1: sp.Symbol
    c2: sp.Symbol
    c1_hat: sp.Symbol
    c2_hat: sp.Symbol
    d0: sp.Symbol
    premises: tuple[Premise, ...]
    steps: tuple[Step, ...]
    goals: tuple[Goal, ...]
    kappa: sp.Expr
    kappa_step: str
    region: sp.Expr
    closed_form: tuple[tuple[tuple[sp.Expr, str], ...], ...]
    witnesses: tuple[tuple[str, tuple[Any, Any, Any], bool], ...]
    dist2: sp.Expr
    state: tuple[sp.Symbol, sp.Symbol, sp.Symbol]
    cases: tuple[Case, ...]


_RELATIONS = {"≥": sp.GreaterThan, "≤": sp.LessThan, "=": sp.Eq}


def _subject() -> StabilitySubject:
    g = G()
    pos = {"positive": True}
    nonneg = {"nonnegative": True}
    c1, c2, ch1, ch2 = sp.symbols("c_1 c_2 \\hat{c}_1 \\hat{c}_2", **pos)
    # squared distances |x(·)|²_𝒜 and values of V, V̂ at the instants used by the proof
    d0, dt, ds, dt1 = sp.symbols("D_0 D_t D_s D_{t_1}", **nonneg)
    vh0, vht, vhs, vht1 = sp.symbols("\\hat{V}_0 \\hat{V}_t \\hat{V}_s \\hat{V}_{t_1}", **nonneg)
    v0, vt, vt1 = sp.symbols("V_0 V_t V_{t_1}", **nonneg)
    v_star, vh_star = sp.symbols("V_* \\hat{V}_*", **nonneg)
    P = Premise
    # every premise is a conclusion of Lemma 2 or Lemma 3, from the function its obligation checks
    V_at = lambda c_lo, c_hi, D, V: tuple(Ineq(*pair) for pair in lemma3_V_bounds(c_lo, c_hi, D, V))  # noqa: E731
    H_at = lambda c_lo, c_hi, D, W: tuple(Ineq(*pair) for pair in lemma3_hatV_bounds(c_lo, c_hi, D, W))  # noqa: E731
    premises = (
        P("VandR at x*", V_at(c1, c2, 1, v_star)[0], "eq. (VandR) at x* = (1, 0, 0) ∈ R, |x*|²_𝒜 = 1 (lower)"),
        P("VandR at x* (upper)", V_at(c1, c2, 1, v_star)[1], "eq. (VandR) at x* (upper)"),
        P("hatVandHatR at x̂*", H_at(ch1, ch2, 1, vh_star)[0], "eq. (hatVandHatR) at x̂* = (0, 0, 1) ∈ R̂, |x̂*|²_𝒜 = 1 (lower)"),
        P("hatVandHatR at x̂* (upper)", H_at(ch1, ch2, 1, vh_star)[1], "eq. (hatVandHatR) at x̂* (upper)"),
        # case (i): x(t) ∈ R̂ for all t ≥ 0
        P("(i) lower at t", H_at(ch1, ch2, dt, vht)[0], "eq. (hatVandHatR) at x(t) ∈ R̂"),
        P("(i) decrease", Ineq(*lemma3_hatV_nonincreasing(vht, vh0)), "eq. (hatVdot): V̂° ≤ 0 on R̂, so V̂ does not increase while x ∈ R̂"),
        P("upper at 0", H_at(ch1, ch2, d0, vh0)[1], "eq. (hatVandHatR) at x(0) ∈ R̂ (cases (i) and (ii) with t₁ > 0)"),
        # case (ii), t₁ > 0: x(s) ∈ R̂ on [0, t₁), x(t₁) ∈ R
        P("(ii) lower at s", H_at(ch1, ch2, ds, vhs)[0], "eq. (hatVandHatR) at x(s) ∈ R̂, s ∈ [0, t₁)"),
        P("(ii) decrease to s", Ineq(*lemma3_hatV_nonincreasing(vhs, vh0)), "eq. (hatVdot) on [0, s] ⊂ [0, t₁)"),
        P("(ii) lower at t₁", H_at(ch1, ch2, dt1, vht1)[0], "eq. (hatVandHatR) as s → t₁ (continuity of x and V̂)"),
        P("(ii) decrease to t₁", Ineq(*lemma3_hatV_nonincreasing(vht1, vh0)), "eq. (hatVdot) on [0, t₁), then continuity at t₁"),
        P("(ii) VandR at t₁", V_at(c1, c2, dt1, vt1)[1], "eq. (VandR) at x(t₁) ∈ R (upper)"),
        P("(ii) Lemma 2.1 at t", Ineq(*lemma2_lower_bound(c1, dt, vt)), "Lemma 2 item 1 at x(t), t ≥ t₁"),
        P("(ii) Lemma 2.2", Ineq(*lemma2_decrease(vt, vt1)), "Lemma 2 item 2 (eq. Vdecrease) from t₁ to t ≥ t₁"),
        # case (ii), t₁ = 0: x(0) ∈ R
        P("(ii₀) VandR at 0", V_at(c1, c2, d0, v0)[1], "eq. (VandR) at x(0) ∈ R (upper)"),
        P("(ii₀) Lemma 2.2", Ineq(*lemma2_decrease(vt, v0)), "Lemma 2 item 2 from 0 to t"),
    )
    S = Step
    steps = (
        S("c1 ≤ c2", Ineq(c1, c2), ("VandR at x*", "VandR at x* (upper)"), (1, 1), "both bounds of (VandR) at x*"),
        S(
            "ĉ1 ≤ ĉ2",
            Ineq(ch1, ch2),
            ("hatVandHatR at x̂*", "hatVandHatR at x̂* (upper)"),
            (1, 1),
            "both bounds of (hatVandHatR) at x̂*",
        ),
        S("c1ĉ1 ≤ c2ĉ2", Ineq(c1 * ch1, c2 * ch2), ("c1 ≤ c2", "ĉ1 ≤ ĉ2"), (ch2, c1), "product of the two"),
        S(
            "(i) bound",
            Ineq(c1 * ch1 * dt, c2 * ch2 * d0),
            ("(i) lower at t", "(i) decrease", "upper at 0", "c1 ≤ c2"),
            (c1, c1, c1, ch2 * d0),
            "ĉ₁|x(t)|² ≤ V̂(x(t)) ≤ V̂(x(0)) ≤ ĉ₂|x(0)|², times c₁, and 1 ≤ c₂/c₁",
        ),
        S(
            "(ii) boundInHatR",
            Ineq(ch1 * ds, ch2 * d0),
            ("(ii) lower at s", "(ii) decrease to s", "upper at 0"),
            (1, 1, 1),
            "eq. (boundInHatR) for s ∈ [0, t₁)",
        ),
        S(
            "(ii) boundInHatR at t₁",
            Ineq(ch1 * dt1, ch2 * d0),
            ("(ii) lower at t₁", "(ii) decrease to t₁", "upper at 0"),
            (1, 1, 1),
            "eq. (boundInHatR) at t₁ (continuity)",
        ),
        S(
            "(ii) bound before t₁",
            Ineq(c1 * ch1 * ds, c2 * ch2 * d0),
            ("(ii) boundInHatR", "c1 ≤ c2"),
            (c1, ch2 * d0),
            "eq. (boundInHatR) and √(c₂/c₁) ≥ 1",
        ),
        S(
            "(ii) V at t₁",
            Ineq(ch1 * vt1, c2 * ch2 * d0),
            ("(ii) VandR at t₁", "(ii) boundInHatR at t₁"),
            (ch1, c2),
            "V(x(t₁)) ≤ c₂|x(t₁)|² ≤ c₂(ĉ₂/ĉ₁)|x(0)|², times ĉ₁",
        ),
        S(
            "(ii) bound after t₁",
            Ineq(c1 * ch1 * dt, c2 * ch2 * d0),
            ("(ii) V at t₁", "(ii) Lemma 2.2", "(ii) Lemma 2.1 at t"),
            (1, ch1, ch1),
            "eq. (boundInHatRandInR), times ĉ₁",
        ),
        S(
            "(ii₀) bound",
            Ineq(c1 * ch1 * dt, c2 * ch2 * d0),
            ("(ii₀) VandR at 0", "(ii₀) Lemma 2.2", "(ii) Lemma 2.1 at t", "ĉ1 ≤ ĉ2"),
            (ch2, ch2, ch2, c1 * dt),
            "t₁ = 0: the interval [0, t₁) is empty and eq. (boundInHatR) at t = 0 is ĉ₁ ≤ ĉ₂",
        ),
    )
    goals = (
        Goal("(i): x(t) ∉ R for all t ≥ 0", "(i) bound", dt),
        Goal("(ii), t₁ > 0, t ∈ [0, t₁)", "(ii) bound before t₁", ds),
        Goal("(ii), t₁ > 0, t ≥ t₁", "(ii) bound after t₁", dt),
        Goal("(ii), t₁ = 0, t ≥ 0", "(ii₀) bound", dt),
    )
    closed_form = (
        ((g.v, "≥"), (g.phi - g.f_c, "≥")),
        ((g.v, "≤"), (g.phi + g.f_c, "≤")),
        ((g.v, "="),),
    )
    return StabilitySubject(
        c1=c1,
        c2=c2,
        c1_hat=ch1,
        c2_hat=ch2,
        d0=d0,
        premises=premises,
        steps=steps,
        goals=goals,
        kappa=sp.sqrt(c2 * ch2 / (c1 * ch1)),
        kappa_step="c1ĉ1 ≤ c2ĉ2",
        region=shared_value(region_R, g),
        closed_form=closed_form,
        witnesses=(("x*", (1, 0, 0), True), ("x̂*", (0, 0, 1), False)),
        dist2=distance_squared(g),
        state=(g.sigma, g.phi, g.v),
        cases=tuple(case_grid(sign_cases(g.v, "v", "a_v"), phi_cases(g.phi, g.f_c))),
    )


def _tex_rel(rel: str) -> str:
    return {"≥": "\\ge", "≤": "\\le", "=": "="}.get(rel, rel)


def _closedness_failures(s: StabilitySubject) -> list[str]:
    out = []
    for part in s.closed_form:
        for _, rel in part:
            if rel not in _RELATIONS:
                out.append(f"relation {rel!r} in the description of R is not one of ≥, ≤, = (not closed)")
    if out:
        return out
    for case in s.cases:
        try:
            in_r = in_R(case(s.region))
            in_union = any(
                all(decide(_RELATIONS[rel](resolve_piecewise(case(e)), 0)) for e, rel in part) for part in s.closed_form
            )
        except Undecided as exc:
            out.append(f"closedness of R, {case.label}: {exc}")
            continue
        if in_r is None:
            out.append(f"cannot decide whether {case.label} lies in R")
        elif in_r != in_union:
            out.append(f"{case.label}: R and its closed description differ ({in_r} vs {in_union})")
    return out


def _witness_failures(s: StabilitySubject) -> list[str]:
    out = []
    for name, point, want_in_r in s.witnesses:
        sub = dict(zip(s.state, (sp.sympify(c) for c in point)))
        try:
            member = in_R(s.region.xreplace(sub))
            dist = resolve_piecewise(s.dist2.xreplace(sub))
        except Undecided as exc:
            out.append(f"witness {name}: {exc}")
            continue
        if member is not want_in_r:
            out.append(f"witness {name} = {point} is {'not ' if want_in_r else ''}in R")
        if not is_zero(dist - 1):
            out.append(f"witness {name} = {point} has |x|²_𝒜 = {dist}, not 1")
    return out
