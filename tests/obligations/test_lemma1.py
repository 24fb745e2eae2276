"""lemma1.uniqueness: M(t) ≤ 0 in all nine sign cases (Lemma 1's proof)."""

import dataclasses

import pytest
import sympy as sp

from symbolic_friction._obligations._decide import G
from symbolic_friction._obligations.lemma1 import Lemma1Uniqueness

g = G()


@pytest.fixture(scope="module")
def uniqueness():
    ob = Lemma1Uniqueness()
    return ob, ob.derive()


def test_uniqueness_holds(uniqueness):
    ob, subject = uniqueness
    out = ob.verify(subject)
    assert out.holds, out.reason
    assert len(out.details) == 1 + 9  # the friction identity and nine cases
    assert "2 f_{c} \\left(p + q\\right)" in "".join(tex for _, tex in out.details)


def test_friction_that_accelerates_breaks_uniqueness(uniqueness):
    ob, subject = uniqueness
    out = ob.verify(dataclasses.replace(subject, b=-subject.b))
    assert out.holds is False
    assert "sign(z_1v) = 1, sign(z_1v - δ_v) = 0" in out.reason and "M(t) ≥ 2*f_c*p > 0" in out.reason


def test_wider_sgn_at_zero_fails(uniqueness):
    ob, subject = uniqueness
    sgn = dict(subject.sgn)
    sgn[0] = sp.Interval(-2, 2)
    out = ob.verify(dataclasses.replace(subject, sgn=sgn))
    assert out.holds is False
    assert "sign(z_1v) = 1, sign(z_1v - δ_v) = 0" in out.reason and "> 0" in out.reason


def test_open_sgn_set_is_not_decided(uniqueness):
    ob, subject = uniqueness
    sgn = dict(subject.sgn)
    sgn[0] = sp.Interval.open(-1, 1)
    out = ob.verify(dataclasses.replace(subject, sgn=sgn))
    assert out.holds is False
    assert "closed bounded interval" in out.reason


def test_friction_not_along_v_fails(uniqueness):
    ob, subject = uniqueness
    out = ob.verify(dataclasses.replace(subject, b=sp.ImmutableMatrix([0, g.f_c, g.f_c])))
    assert out.holds is False
    assert "not δ_v(f_2 - f_1)" in out.reason
