"""Obligations on the model: coordinates, regularization, assumption1.routh,
equilibria, distance (eqs. CoC, xDot, basic, xPhDot, Aph, A, distFromA)."""

import dataclasses

import pytest
import sympy as sp

from symbolic_friction._obligations._decide import G
from symbolic_friction._obligations.assumption1 import Assumption1Routh, hurwitz_minors
from symbolic_friction._obligations.coordinates import Coordinates
from symbolic_friction._obligations.distance import Distance
from symbolic_friction._obligations.equilibria import Equilibria
from symbolic_friction._obligations.regularization import Branch, Regularization

from ._helpers import assert_fails, assert_holds, obligation_fixture, replace_item, with_entry

g = G()


# --------------------------------------------------------------------------- coordinates


coordinates = obligation_fixture(Coordinates)


def test_coordinates_holds(coordinates):
    ob, subject = coordinates
    out = assert_holds(ob, subject)
    assert dict(out.details)["\\det T"] == "- k_{i}^{2}"
    assert sp.factor(subject.T.det()) == -g.k_i**2


def test_coordinates_flipped_sign_in_A_fails(coordinates):
    ob, subject = coordinates
    assert_fails(ob, dataclasses.replace(subject, A=with_entry(subject.A, 1, 2, g.k_p)), "not identically zero")


def test_coordinates_flipped_sign_of_b_fails(coordinates):
    ob, subject = coordinates
    assert_fails(ob, dataclasses.replace(subject, b=-subject.b), "not identically zero", "f_c*w")


def test_coordinates_det_depending_on_k_p_fails(coordinates):
    ob, subject = coordinates
    assert_fails(ob, dataclasses.replace(subject, T=with_entry(subject.T, 0, 0, g.k_p)), "does not vanish exactly when k_i = 0")


def test_coordinates_wrong_inverse_fails(coordinates):
    ob, subject = coordinates
    assert_fails(ob, dataclasses.replace(subject, T_inv=with_entry(subject.T_inv, 0, 0, 2 * g.k_p / g.k_i**2)), "T_inv·T - I")


def test_coordinates_T_that_mixes_v_fails(coordinates):
    ob, subject = coordinates
    T = with_entry(subject.T, 2, 0, 1)
    assert_fails(ob, dataclasses.replace(subject, T=T, T_inv=sp.ImmutableMatrix(sp.Matrix(T).inv())), "T changes v")


# --------------------------------------------------------------------------- regularization


regularization = obligation_fixture(Regularization)


def _replace_branch(subject, label, **changes):
    return replace_item(subject, "branches", "label", label, **changes)


def test_regularization_holds(regularization):
    ob, subject = regularization
    out = assert_holds(ob, subject)
    assert len(subject.branches) == 5
    assert any("\\frac{u}{f_{c}}" in tex for _, tex in out.details)


def test_regularization_friction_helping_the_motion_fails(regularization):
    ob, subject = regularization
    assert_fails(ob, _replace_branch(subject, "v > 0", vdot=subject.u + g.f_c), "branch 'v > 0'", "w = -1")


def test_regularization_too_wide_stick_band_fails(regularization):
    ob, subject = regularization
    assert_fails(
        ob, _replace_branch(subject, "v = 0, |u| < f_c", u_set=sp.Interval.open(-2 * g.f_c, 2 * g.f_c)), "|u| < f_c", "not in SGN"
    )


def test_regularization_overlapping_branches_fail(regularization):
    ob, subject = regularization
    assert_fails(ob, _replace_branch(subject, "v = 0, u ≥ f_c", u_set=sp.Interval(g.f_c / 2, sp.oo)), "do not partition")


def test_regularization_missing_branch_fails(regularization):
    ob, subject = regularization
    assert_fails(ob, dataclasses.replace(subject, branches=subject.branches[:-1]), "sign -1")


def test_regularization_wrong_control_law_fails(regularization):
    ob, subject = regularization
    assert_fails(ob, dataclasses.replace(subject, u_of_z=subject.u_of_z + 2 * g.k_i * g.e_i), "not u =")


def test_regularization_unbounded_selection_fails(regularization):
    ob, subject = regularization
    assert_fails(ob, _replace_branch(subject, "v = 0, u ≥ f_c", vdot=sp.Integer(0)), "unbounded")


def test_branch_is_frozen():
    br = Branch("v > 0", 1, sp.S.Reals, sp.Integer(0))
    with pytest.raises(dataclasses.FrozenInstanceError):
        br.v_sign = 0


# --------------------------------------------------------------------------- assumption1.routh


routh = obligation_fixture(Assumption1Routh)


def test_routh_holds(routh):
    ob, subject = routh
    assert_holds(ob, subject)
    k_p, k_i, k_v = subject.gains
    assert [sp.expand(m) for m in hurwitz_minors(sp.Poly(subject.paper_polynomial, subject.s))] == [
        k_v,
        sp.expand(k_p * k_v - k_i),
        sp.expand(k_i * (k_p * k_v - k_i)),
    ]


def test_routh_flipped_sign_in_A_fails(routh):
    ob, subject = routh
    k_p, k_i, k_v = subject.gains
    assert_fails(ob, dataclasses.replace(subject, A=with_entry(subject.A, 0, 2, k_i)), "det(sI - A)")


def test_routh_dropping_a_condition_fails(routh):
    ob, subject = routh
    k_p, k_i, k_v = subject.gains
    assert_fails(ob, dataclasses.replace(subject, assumption=(k_i, k_v * k_p - k_i)), "(⇐) fails")


def test_routh_stronger_condition_fails_the_converse(routh):
    ob, subject = routh
    k_p, k_i, k_v = subject.gains
    assert_fails(ob, dataclasses.replace(subject, assumption=(k_i, k_p, k_v * k_p - 2 * k_i)), "(⇒) fails")


def test_routh_wrong_polynomial_fails(routh):
    ob, subject = routh
    k_p, k_i, k_v = subject.gains
    s = subject.s
    assert_fails(ob, dataclasses.replace(subject, paper_polynomial=s**3 + k_v * s**2 + k_p * s - k_i), "differs from the paper's")


# --------------------------------------------------------------------------- equilibria


equilibria = obligation_fixture(Equilibria)


def test_equilibria_hold(equilibria):
    ob, subject = equilibria
    assert_holds(ob, subject)
    assert subject.attractor_x[1] == sp.Interval(-g.f_c, g.f_c)
    assert subject.attractor_z[0] == sp.Interval(-g.f_c / g.k_i, g.f_c / g.k_i)


def test_equilibria_moved_attractor_bound_fails(equilibria):
    ob, subject = equilibria
    assert_fails(
        ob, dataclasses.replace(subject, attractor_x=(0, sp.Interval(-g.f_c, 2 * g.f_c), 0)), "𝒜 says Interval(-f_c, 2*f_c)"
    )


def test_equilibria_moved_z_bound_fails(equilibria):
    ob, subject = equilibria
    assert_fails(ob, dataclasses.replace(subject, attractor_z=(sp.Interval(-g.f_c, g.f_c), 0, 0)), "e_i")


def test_equilibria_wrong_integral_gain_in_A_z_fails(equilibria):
    ob, subject = equilibria
    assert_fails(ob, dataclasses.replace(subject, A_z=with_entry(subject.A_z, 2, 0, -2 * g.k_i)), "f_c/(2*k_i)")


def test_equilibria_singular_A_fails(equilibria):
    ob, subject = equilibria
    assert_fails(ob, dataclasses.replace(subject, A=with_entry(subject.A, 0, 2, 0)), "singular")


def test_equilibria_with_moving_velocity_fails(equilibria):
    ob, subject = equilibria
    # σ' = -k_i v + k_i φ/f_c... changes the v = ±1 equilibrium to one with v ≠ 0
    A = with_entry(subject.A, 0, 1, g.k_i / g.f_c)
    assert_fails(ob, dataclasses.replace(subject, A=A), "equilibrium with v of sign")


# --------------------------------------------------------------------------- distance


distance = obligation_fixture(Distance)


def test_distance_holds(distance):
    ob, subject = distance
    out = assert_holds(ob, subject)
    assert len(out.details) == 5


def test_distance_wrong_dead_zone_width_fails(distance):
    ob, subject = distance
    from symbolic_friction._model.symbolic import dz

    wrong = g.sigma**2 + g.v**2 + dz(g.phi, 2 * g.f_c) ** 2
    assert_fails(ob, dataclasses.replace(subject, formula=wrong), "φ > f_c")


def test_distance_missing_velocity_term_fails(distance):
    ob, subject = distance
    assert_fails(ob, dataclasses.replace(subject, formula=subject.formula - g.v**2), "the formula gives")


def test_distance_moved_attractor_bound_fails(distance):
    ob, subject = distance
    assert_fails(ob, dataclasses.replace(subject, attractor=(0, sp.Interval(-g.f_c, 2 * g.f_c), 0)), "cannot decide")


def test_distance_needs_one_interval_component(distance):
    ob, subject = distance
    assert_fails(ob, dataclasses.replace(subject, attractor=(0, 0, 0)), "exactly one interval component")


def test_equilibria_undecidable_velocity_fails(equilibria):
    ob, subject = equilibria
    A = with_entry(subject.A, 0, 1, (g.k_i - g.k_p) / g.f_c)
    assert_fails(ob, dataclasses.replace(subject, A=A), "cannot exclude an equilibrium with v of sign 1")
