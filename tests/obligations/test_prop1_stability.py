"""Proposition 1 item 2: prop1.stability_bound."""

from __future__ import annotations

import dataclasses

import sympy as sp

from symbolic_friction._obligations._stability_chain import Ineq
from symbolic_friction._obligations.prop1 import StabilityBound

from ._helpers import assert_fails, assert_holds, replace_item, subject_fixture

subject = subject_fixture(StabilityBound)


def _fails(altered, pattern):
    assert_fails(StabilityBound(), altered, pattern)


def _replace_step(subject, name, **changes):
    return replace_item(subject, "steps", "name", name, **changes)


def _replace_premise(subject, name, claim):
    return replace_item(subject, "premises", "name", name, claim=claim)


def test_holds(subject):
    out = assert_holds(StabilityBound(), subject)
    assert "cover 4 cases" in out.reason
    assert "t₁ = 0 needs ĉ₁ ≤ ĉ₂" in out.reason


def test_negative_multiplier(subject):
    s = _replace_step(subject, "(i) bound", multipliers=(subject.c1, subject.c1, -subject.c1, subject.c2_hat * subject.d0))
    _fails(s, "step '(i) bound': multipliers [-c_1] are not shown nonnegative")


def test_reversed_premise(subject):
    vht, vh0 = sp.Symbol("\\hat{V}_t", nonnegative=True), sp.Symbol("\\hat{V}_0", nonnegative=True)
    _fails(_replace_premise(subject, "(i) decrease", Ineq(vh0, vht)), "step '(i) bound'")


def test_premise_with_the_wrong_constant(subject):
    # V(x(t₁)) ≤ c₁|x(t₁)|² is not what (VandR) gives; the chain then fails
    vt1, dt1 = sp.Symbol("V_{t_1}", nonnegative=True), sp.Symbol("D_{t_1}", nonnegative=True)
    _fails(_replace_premise(subject, "(ii) VandR at t₁", Ineq(vt1, 2 * subject.c2 * dt1)), "step '(ii) V at t₁'")


def test_unknown_fact_and_wrong_count(subject):
    _fails(_replace_step(subject, "c1 ≤ c2", uses=("VandR at x*", "Lemma 7")), "uses unknown or later facts ['Lemma 7']")
    _fails(_replace_step(subject, "c1 ≤ c2", multipliers=(1,)), "has 1 multipliers for 2 facts")


def test_step_order_matters(subject):
    steps = list(subject.steps)
    steps.insert(0, steps.pop(3))  # "(i) bound" before "c1 ≤ c2"
    _fails(dataclasses.replace(subject, steps=tuple(steps)), "uses unknown or later facts ['c1 ≤ c2']")


def test_missing_t1_zero_case(subject):
    steps = tuple(st for st in subject.steps if st.name != "(ii₀) bound")
    _fails(dataclasses.replace(subject, steps=steps), "case (ii), t₁ = 0, t ≥ 0: step '(ii₀) bound' was not proved")


def test_goal_must_be_the_stability_bound(subject):
    ds = sp.Symbol("D_s", nonnegative=True)
    goals = tuple(dataclasses.replace(g, distance=ds) if g.step == "(i) bound" else g for g in subject.goals)
    _fails(dataclasses.replace(subject, goals=goals), "case (i): x(t) ∉ R for all t ≥ 0: step '(i) bound' proves")


def test_wrong_kappa(subject):
    s = subject
    _fails(dataclasses.replace(s, kappa=sp.sqrt(s.c2 / s.c1)), "does not satisfy κ > 0 and κ²·c₁ĉ₁ = c₂ĉ₂")
    _fails(dataclasses.replace(s, kappa_step="(i) bound"), "κ ≥ 1 needs a proved step c₁ĉ₁ ≤ c₂ĉ₂")


def test_R_must_be_closed(subject):
    s = subject
    v, phi = s.state[2], s.state[1]
    f_c = [x for x in s.region.free_symbols if x.name == "f_c"][0]
    strict = (((v, "≥"), (phi - f_c, ">")),) + s.closed_form[1:]
    _fails(dataclasses.replace(s, closed_form=strict), "relation '>' in the description of R is not one of ≥, ≤, = (not closed)")
    wrong = (((v, "≥"), (phi + f_c, "≥")),) + s.closed_form[1:]
    _fails(dataclasses.replace(s, closed_form=wrong), "R and its closed description differ")


def test_witnesses(subject):
    s = subject
    _fails(dataclasses.replace(s, witnesses=(("x*", (1, 0, 0), True), ("x̂*", (0, 0, 1), True))), "witness x̂* = (0, 0, 1) is not in R")
    _fails(dataclasses.replace(s, witnesses=(("x*", (2, 0, 0), True),)), "has |x|²_𝒜 = 4, not 1")
