"""The closed-form certificate for all gains, and the monotonicity that box certificates rest on.

Each obligation holds on the package's code, and fails when its subject is broken: a wrong
factor in k₃ (in the code, and in the numeric builder only), a dropped margin, a premise that
is not monotone.
"""

from __future__ import annotations

import dataclasses
from fractions import Fraction as F

import sympy as sp

import symbolic_friction._certify.closed_form as closed_form_module
from symbolic_friction._obligations import registry
from symbolic_friction._obligations.closed_form import ClosedFormAllGains, ClosedFormMonotone

from ._helpers import assert_fails, assert_holds, obligation_fixture

all_gains = obligation_fixture(ClosedFormAllGains)
monotone = obligation_fixture(ClosedFormMonotone)


def test_both_hold_and_are_registered(all_gains, monotone):
    for ob, subject in (all_gains, monotone):
        assert_holds(ob, subject)
    ids = [cls.id for cls in registry()]
    assert ids.index(ClosedFormMonotone.id) == ids.index(ClosedFormAllGains.id) + 1


def test_both_are_fast():
    for cls in (ClosedFormAllGains, ClosedFormMonotone):
        cls().run()  # warm (sympy's caches, the case fractions)
        assert cls().run().seconds < 5


def _formulas_with(monkeypatch, transform):
    real = closed_form_module.closed_form_formulas

    def wrong(*args, **kwargs):
        out = real(*args, **kwargs)
        return {**out, **transform(out, args)}

    monkeypatch.setattr(closed_form_module, "closed_form_formulas", wrong)
    import symbolic_friction._obligations.closed_form as ob_module

    monkeypatch.setattr(ob_module, "closed_form_formulas", wrong)


def test_a_wrong_k3_factor_in_the_code_fails(monkeypatch):
    # a valid but different closed form (3 instead of 2): the premises still hold, the statement does not
    _formulas_with(monkeypatch, lambda out, args: {"k3": out["k3"] * F(3, 2) if isinstance(out["k3"], F) else out["k3"] * sp.Rational(3, 2)})
    result = ClosedFormAllGains().run()
    assert not result.holds and "differs from the stated one in k3" in result.reason


def test_a_k3_without_margin_fails_a_premise(all_gains):
    ob, subject = all_gains
    mu = sp.Symbol("mu", positive=True)
    branches = []
    for (choice, rows, picks, roots), constants in zip(subject.branches, subject.constants):
        # what premises() gives for k3 = 2ρ: "k3 > k2" becomes 2ρ − 2, zero at r ≤ 1
        rows = tuple((n, m.xreplace({mu: 0}) if n == "k3 > k2" else m, k) for n, m, k in rows)
        branches.append((choice, rows, picks, roots))
    assert_fails(ob, dataclasses.replace(subject, branches=tuple(branches)), "premise k3 > k2 (> 0) is not proved")


def test_the_numeric_builder_is_bound_to_the_stated_form(all_gains):
    ob, subject = all_gains
    a, kp, mu, c = subject.samples[0]
    bad = dataclasses.replace(c, k3=c.k3 * 2)
    assert_fails(ob, dataclasses.replace(subject, samples=((a, kp, mu, bad),) + subject.samples[1:]),
                 "closed_form_constants at a = 8/5", "differs from the stated closed form in k3")
    loose_c1 = dataclasses.replace(c, c1=c.c1 * 2)
    assert_fails(ob, dataclasses.replace(subject, samples=((a, kp, mu, loose_c1),)), "in c1")


def test_a_wrong_pick_is_caught(all_gains):
    ob, subject = all_gains
    choice, rows, picks, roots = subject.branches[0]
    swapped = tuple((n, k, o, c) if n == "k4" else (n, k, c, o) for n, k, c, o in picks)
    assert_fails(ob, dataclasses.replace(subject, branches=((choice, rows, swapped, roots),) + subject.branches[1:]),
                 "does not pick")


def test_no_samples_or_branches_fails(all_gains):
    ob, subject = all_gains
    assert_fails(ob, dataclasses.replace(subject, samples=()), "no numeric samples")
    assert_fails(ob, dataclasses.replace(subject, branches=subject.branches[:7], constants=subject.constants[:7]), "8 choices")


def test_a_non_monotone_premise_fails(monotone):
    ob, subject = monotone
    a = sp.Symbol("a", positive=True)
    rows = subject.rows + (("made up", ">", (a - 1) ** 2),)
    assert_fails(ob, dataclasses.replace(subject, rows=rows), "premise made up is not shown monotone in a")


def test_a_premise_depending_on_k_i_alone_fails(monotone):
    ob, subject = monotone
    k_i = subject.scale
    rows = subject.rows + (("made up", ">", k_i - 1),)
    assert_fails(ob, dataclasses.replace(subject, rows=rows), "depends on k_i beyond")


def test_a_non_loewner_monotone_matrix_fails(monotone):
    ob, subject = monotone
    a, k_p = sp.symbols("a k_p", positive=True)
    m = sp.Matrix([[a, 0, 0], [0, -k_p * a, 0], [0, 0, 1]])
    rows = subject.rows + (("made up", "psd", m),)
    assert_fails(ob, dataclasses.replace(subject, rows=rows), "premise made up is not shown monotone in a")


def test_an_equation_that_does_not_hold_on_a_box_fails(monotone):
    ob, subject = monotone
    a = sp.Symbol("a", positive=True)
    assert_fails(ob, dataclasses.replace(subject, rows=subject.rows + (("made up", "==", a - 1),)), "equation")
