"""prop1.invariance: the largest forward-invariant subset of {v = 0} is 𝒜."""

import dataclasses

import pytest
import sympy as sp

from symbolic_friction._obligations._decide import G
from symbolic_friction._obligations.prop1_attractivity import Prop1Invariance

g = G()


@pytest.fixture(scope="module")
def invariance():
    ob = Prop1Invariance()
    return ob, ob.derive()


def test_invariance_holds(invariance):
    ob, subject = invariance
    out = ob.verify(subject)
    assert out.holds, out.reason
    verdicts = [tex for label, tex in out.details if label.startswith("\\sigma")]
    assert len(verdicts) == 15
    assert sum("equilibria" in v for v in verdicts) == 3


def test_narrower_attractor_fails(invariance):
    ob, subject = invariance
    out = ob.verify(dataclasses.replace(subject, attractor=(0, sp.Interval(-g.f_c / 2, g.f_c / 2), 0)))
    assert out.holds is False
    assert "class σ = 0, φ = f_c consists of equilibria" in out.reason


def test_wider_attractor_fails(invariance):
    ob, subject = invariance
    out = ob.verify(dataclasses.replace(subject, attractor=(0, sp.Interval(-2 * g.f_c, 2 * g.f_c), 0)))
    assert out.holds is False
    assert "cannot decide whether φ = f_c + p_phi lies in" in out.reason


def test_attractor_with_nonzero_sigma_fails(invariance):
    ob, subject = invariance
    out = ob.verify(dataclasses.replace(subject, attractor=(g.f_c, sp.Interval(-g.f_c, g.f_c), 0)))
    assert out.holds is False
    assert "cannot decide σ = s_sigma against 𝒜" in out.reason


def test_no_ramp_makes_more_invariant_points(invariance):
    ob, subject = invariance
    A = sp.Matrix(subject.A)
    A[1, 0] = 0  # φ' no longer driven by σ: σ ≠ 0 points would stick forever
    out = ob.verify(dataclasses.replace(subject, A=sp.ImmutableMatrix(A)))
    assert out.holds is False
    assert "class σ > 0, φ = f_c consists of equilibria" in out.reason


def test_wrong_sigma_set_fails(invariance):
    ob, subject = invariance
    out = ob.verify(dataclasses.replace(subject, ell=g.sigma**2))
    assert out.holds is False
    assert "is not the plane v = 0" in out.reason


def test_friction_vector_not_on_v_fails(invariance):
    ob, subject = invariance
    out = ob.verify(dataclasses.replace(subject, b=sp.ImmutableMatrix([0, g.f_c, g.f_c])))
    assert out.holds is False
    assert "is not (0, 0, positive)" in out.reason


def test_attractor_off_the_plane_fails(invariance):
    ob, subject = invariance
    out = ob.verify(dataclasses.replace(subject, attractor=(0, sp.Interval(-g.f_c, g.f_c), 1)))
    assert out.holds is False
    assert "is not a φ-interval inside v = 0" in out.reason


def test_undecidable_motion_fails(invariance):
    ob, subject = invariance
    A = sp.Matrix(subject.A)
    A[1, 1] = 1 - g.k_p  # makes φ grow exponentially with a sign-indefinite rate
    out = ob.verify(dataclasses.replace(subject, A=sp.ImmutableMatrix(A)))
    assert out.holds is False
    assert "not polynomial in t" in out.reason


def test_undecidable_selection_range_fails(invariance):
    ob, subject = invariance
    sgn = dict(subject.sgn)
    sgn[0] = sp.Interval(-1, g.k_p)
    out = ob.verify(dataclasses.replace(subject, sgn=sgn))
    assert out.holds is False
    assert "cannot decide whether w(0) = 1 + p_phi/f_c lies in [-1, k_p]" in out.reason


def test_undecidable_drift_fails(invariance):
    ob, subject = invariance
    A = sp.Matrix(subject.A)
    A[1, 0] = g.k_p - 1
    out = ob.verify(dataclasses.replace(subject, A=sp.ImmutableMatrix(A)))
    assert out.holds is False
    assert "cannot decide whether (σ', φ')" in out.reason and "vanishes" in out.reason


def test_drift_that_never_breaks_stick_fails(invariance):
    ob, subject = invariance
    A = sp.Matrix(subject.A)
    A[2, 1] = 0  # v' no longer feels φ: σ ≠ 0 drifts φ but never breaks the stick
    out = ob.verify(dataclasses.replace(subject, A=sp.ImmutableMatrix(A)))
    assert out.holds is False
    assert "is not shown to leave [-1, 1]" in out.reason
