"""prop1.invariance: the largest forward-invariant subset of {v = 0} is 𝒜."""

import dataclasses

import sympy as sp

from symbolic_friction._obligations._decide import G
from symbolic_friction._obligations.prop1 import Prop1Invariance

from ._helpers import assert_fails, assert_holds, obligation_fixture, replace_key, with_entry

g = G()
invariance = obligation_fixture(Prop1Invariance)


def test_invariance_holds(invariance):
    ob, subject = invariance
    out = assert_holds(ob, subject)
    verdicts = [tex for label, tex in out.details if label.startswith("\\sigma")]
    assert len(verdicts) == 15
    assert sum("equilibria" in v for v in verdicts) == 3


def test_narrower_attractor_fails(invariance):
    ob, subject = invariance
    assert_fails(
        ob,
        dataclasses.replace(subject, attractor=(0, sp.Interval(-g.f_c / 2, g.f_c / 2), 0)),
        "class σ = 0, φ = f_c consists of equilibria",
    )


def test_wider_attractor_fails(invariance):
    ob, subject = invariance
    assert_fails(
        ob,
        dataclasses.replace(subject, attractor=(0, sp.Interval(-2 * g.f_c, 2 * g.f_c), 0)),
        "cannot decide whether φ = f_c + p_phi lies in",
    )


def test_attractor_with_nonzero_sigma_fails(invariance):
    ob, subject = invariance
    assert_fails(
        ob, dataclasses.replace(subject, attractor=(g.f_c, sp.Interval(-g.f_c, g.f_c), 0)), "cannot decide σ = s_sigma against 𝒜"
    )


def test_no_ramp_makes_more_invariant_points(invariance):
    ob, subject = invariance
    # φ' no longer driven by σ: σ ≠ 0 points would stick forever
    assert_fails(
        ob, dataclasses.replace(subject, A=with_entry(subject.A, 1, 0, 0)), "class σ > 0, φ = f_c consists of equilibria"
    )


def test_wrong_sigma_set_fails(invariance):
    ob, subject = invariance
    assert_fails(ob, dataclasses.replace(subject, ell=g.sigma**2), "is not the plane v = 0")


def test_friction_vector_not_on_v_fails(invariance):
    ob, subject = invariance
    assert_fails(ob, dataclasses.replace(subject, b=sp.ImmutableMatrix([0, g.f_c, g.f_c])), "is not (0, 0, positive)")


def test_attractor_off_the_plane_fails(invariance):
    ob, subject = invariance
    assert_fails(
        ob, dataclasses.replace(subject, attractor=(0, sp.Interval(-g.f_c, g.f_c), 1)), "is not a φ-interval inside v = 0"
    )


def test_undecidable_motion_fails(invariance):
    ob, subject = invariance
    # makes φ grow exponentially with a sign-indefinite rate
    assert_fails(ob, dataclasses.replace(subject, A=with_entry(subject.A, 1, 1, 1 - g.k_p)), "not polynomial in t")


def test_undecidable_selection_range_fails(invariance):
    ob, subject = invariance
    assert_fails(
        ob, replace_key(subject, "sgn", 0, sp.Interval(-1, g.k_p)), "cannot decide whether w(0) = 1 + p_phi/f_c lies in [-1, k_p]"
    )


def test_undecidable_drift_fails(invariance):
    ob, subject = invariance
    assert_fails(
        ob, dataclasses.replace(subject, A=with_entry(subject.A, 1, 0, g.k_p - 1)), "cannot decide whether (σ', φ')", "vanishes"
    )


def test_drift_that_never_breaks_stick_fails(invariance):
    ob, subject = invariance
    # v' no longer feels φ: σ ≠ 0 drifts φ but never breaks the stick
    assert_fails(ob, dataclasses.replace(subject, A=with_entry(subject.A, 2, 1, 0)), "is not shown to leave [-1, 1]")
