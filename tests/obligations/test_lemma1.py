"""lemma1.uniqueness: M(t) ≤ 0 in all nine sign cases (Lemma 1's proof)."""

import dataclasses

import sympy as sp

from symbolic_friction._obligations._decide import G
from symbolic_friction._obligations.lemma1 import Lemma1Uniqueness

from ._helpers import assert_fails, assert_holds, obligation_fixture, replace_key

g = G()
uniqueness = obligation_fixture(Lemma1Uniqueness)


def test_uniqueness_holds(uniqueness):
    ob, subject = uniqueness
    out = assert_holds(ob, subject)
    assert len(out.details) == 1 + 9  # the friction identity and nine cases
    assert "2 f_{c} \\left(p + q\\right)" in "".join(tex for _, tex in out.details)


def test_friction_that_accelerates_breaks_uniqueness(uniqueness):
    ob, subject = uniqueness
    assert_fails(ob, dataclasses.replace(subject, b=-subject.b), "sign(z_1v) = 1, sign(z_1v - δ_v) = 0", "M(t) ≥ 2*f_c*p > 0")


def test_wider_sgn_at_zero_fails(uniqueness):
    ob, subject = uniqueness
    assert_fails(ob, replace_key(subject, "sgn", 0, sp.Interval(-2, 2)), "sign(z_1v) = 1, sign(z_1v - δ_v) = 0", "> 0")


def test_open_sgn_set_is_not_decided(uniqueness):
    ob, subject = uniqueness
    assert_fails(ob, replace_key(subject, "sgn", 0, sp.Interval.open(-1, 1)), "closed bounded interval")


def test_friction_not_along_v_fails(uniqueness):
    ob, subject = uniqueness
    assert_fails(ob, dataclasses.replace(subject, b=sp.ImmutableMatrix([0, g.f_c, g.f_c])), "not δ_v(f_2 - f_1)")
