"""``closed_form.balanced``: the closed form with k₁ = k₄ holds wherever its conditions do, and fails when broken.

Broken subjects: a ĉ₂ below λ_max(K)/2 and a k₄ below T in the code, a condition without its margin
(the cases then no longer cover the code's set), a numeric builder that is not the stated form, a
ρ that picks r, a premise row that no case decides, and an empty subject.
"""

from __future__ import annotations

import dataclasses

import sympy as sp

import symbolic_friction._certify.closed_form as closed_form_module
import symbolic_friction._obligations.closed_form as ob_module
from symbolic_friction._obligations import registry
from symbolic_friction._obligations.closed_form import ClosedFormBalanced

from ._helpers import assert_fails, assert_holds, obligation_fixture

balanced = obligation_fixture(ClosedFormBalanced)


def test_holds_is_registered_and_fast(balanced):
    ob, subject = balanced
    assert_holds(ob, subject)
    assert ClosedFormBalanced.id in [cls.id for cls in registry()]
    ClosedFormBalanced().run()
    assert ClosedFormBalanced().run().seconds < 2


def _patch(monkeypatch, name, fn):
    monkeypatch.setattr(closed_form_module, name, fn)
    monkeypatch.setattr(ob_module, name, fn)


def test_a_c2_hat_below_lambda_max_fails(monkeypatch):
    real = closed_form_module.balanced_formulas
    _patch(monkeypatch, "balanced_formulas", lambda k3, T: {**real(k3, T), "c2_hat": (T + k3 / 2) / 2})
    result = ClosedFormBalanced().run()
    assert not result.holds and "c2_hat·I − K/2 ⪰ 0" in result.reason


def test_a_k4_below_T_fails(monkeypatch):
    real = closed_form_module.balanced_formulas
    _patch(monkeypatch, "balanced_formulas", lambda k3, T: {**real(k3, T), "k4": 2 * T / 3})
    result = ClosedFormBalanced().run()
    assert not result.holds and "premise k4 >" in result.reason


def test_a_condition_without_its_margin_fails(monkeypatch):
    def loose(a, k_p, k3, mu, T):
        return (("T ≥ 2k_p", T - 2 * k_p), ("(1+μ)·T ≤ k₃·a", k3 * a - (1 + mu) * T))

    _patch(monkeypatch, "balanced_conditions", loose)
    result = ClosedFormBalanced().run()
    assert not result.holds and "not the stated T ≥ (1+μ)·2k_p" in result.reason


def test_a_numeric_builder_that_is_not_the_stated_form_fails(balanced):
    ob, subject = balanced
    a, kp, mu, loose, base, got = subject.samples[0]
    bad = dataclasses.replace(got, k4=got.k3)
    assert_fails(ob, dataclasses.replace(subject, samples=((a, kp, mu, loose, base, bad),)), "differs from the stated form in k4")
    assert_fails(ob, dataclasses.replace(subject, samples=((a, kp, mu, loose, base, None),)), "balanced() did not apply")


def test_a_rho_that_picks_r_fails(balanced):
    ob, subject = balanced
    a = sp.Symbol("a", positive=True)
    assert_fails(ob, dataclasses.replace(subject, rho_pick=1 / a - 1), "ρ = max(r, 1) does not pick 1")


def test_a_row_that_fails_in_a_boundary_case_is_named(balanced):
    ob, subject = balanced
    T, k_p, mu = (sp.Symbol(n, positive=True) for n in ("R", "k_p", "mu"))
    c1_choice, rows, base_rows = subject.rows[0]
    made_up = rows + (("made up", T - (1 + mu) * 2 * k_p, ">"),)  # zero on the boundary T = (1+μ)·2k_p
    assert_fails(ob, dataclasses.replace(subject, rows=((c1_choice, made_up, base_rows),) + subject.rows[1:]),
                 "premise made up (> 0) is not proved in the case T = (1+μ)·2k_p")


def test_an_empty_subject_fails(balanced):
    ob, subject = balanced
    assert_fails(ob, dataclasses.replace(subject, samples=()), "no numeric samples")
    assert_fails(ob, dataclasses.replace(subject, rows=tuple((c, (), base) for c, _, base in subject.rows)), "nothing was decided")
