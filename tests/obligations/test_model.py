"""Obligations on the model: coordinates, regularization, assumption1.routh,
equilibria, distance (eqs. CoC, xDot, basic, xPhDot, Aph, A, distFromA)."""

import dataclasses

import pytest
import sympy as sp

from symbolic_friction._obligations._decide import G
from symbolic_friction._obligations.model import (
    Assumption1Routh,
    Branch,
    Coordinates,
    Distance,
    Equilibria,
    Regularization,
    hurwitz_minors,
)

g = G()


def _with(matrix, i, j, value):
    m = sp.Matrix(matrix)
    m[i, j] = value
    return sp.ImmutableMatrix(m)


# --------------------------------------------------------------------------- coordinates


@pytest.fixture(scope="module")
def coordinates():
    ob = Coordinates()
    return ob, ob.derive()


def test_coordinates_holds(coordinates):
    ob, subject = coordinates
    out = ob.verify(subject)
    assert out.holds, out.reason
    assert dict(out.details)["\\det T"] == "- k_{i}^{2}"
    assert sp.factor(subject.T.det()) == -g.k_i**2


def test_coordinates_flipped_sign_in_A_fails(coordinates):
    ob, subject = coordinates
    out = ob.verify(dataclasses.replace(subject, A=_with(subject.A, 1, 2, g.k_p)))
    assert out.holds is False
    assert "not identically zero" in out.reason


def test_coordinates_flipped_sign_of_b_fails(coordinates):
    ob, subject = coordinates
    out = ob.verify(dataclasses.replace(subject, b=-subject.b))
    assert out.holds is False
    assert "not identically zero" in out.reason and "f_c*w" in out.reason


def test_coordinates_det_depending_on_k_p_fails(coordinates):
    ob, subject = coordinates
    out = ob.verify(dataclasses.replace(subject, T=_with(subject.T, 0, 0, g.k_p)))
    assert out.holds is False
    assert "does not vanish exactly when k_i = 0" in out.reason


def test_coordinates_wrong_inverse_fails(coordinates):
    ob, subject = coordinates
    out = ob.verify(dataclasses.replace(subject, T_inv=_with(subject.T_inv, 0, 0, 2 * g.k_p / g.k_i**2)))
    assert out.holds is False
    assert "T_inv·T - I" in out.reason


def test_coordinates_T_that_mixes_v_fails(coordinates):
    ob, subject = coordinates
    T = _with(subject.T, 2, 0, 1)
    out = ob.verify(dataclasses.replace(subject, T=T, T_inv=sp.ImmutableMatrix(sp.Matrix(T).inv())))
    assert out.holds is False
    assert "T changes v" in out.reason


# --------------------------------------------------------------------------- regularization


@pytest.fixture(scope="module")
def regularization():
    ob = Regularization()
    return ob, ob.derive()


def _replace_branch(subject, index, **changes):
    branches = list(subject.branches)
    branches[index] = dataclasses.replace(branches[index], **changes)
    return dataclasses.replace(subject, branches=tuple(branches))


def test_regularization_holds(regularization):
    ob, subject = regularization
    out = ob.verify(subject)
    assert out.holds, out.reason
    assert len(subject.branches) == 5
    assert any("\\frac{u}{f_{c}}" in tex for _, tex in out.details)


def test_regularization_friction_helping_the_motion_fails(regularization):
    ob, subject = regularization
    out = ob.verify(_replace_branch(subject, 0, vdot=subject.u + g.f_c))
    assert out.holds is False
    assert "branch 'v > 0'" in out.reason and "w = -1" in out.reason


def test_regularization_too_wide_stick_band_fails(regularization):
    ob, subject = regularization
    out = ob.verify(_replace_branch(subject, 2, u_set=sp.Interval.open(-2 * g.f_c, 2 * g.f_c)))
    assert out.holds is False
    assert "|u| < f_c" in out.reason and "not in SGN" in out.reason


def test_regularization_overlapping_branches_fail(regularization):
    ob, subject = regularization
    out = ob.verify(_replace_branch(subject, 1, u_set=sp.Interval(g.f_c / 2, sp.oo)))
    assert out.holds is False
    assert "do not partition" in out.reason


def test_regularization_missing_branch_fails(regularization):
    ob, subject = regularization
    out = ob.verify(dataclasses.replace(subject, branches=subject.branches[:-1]))
    assert out.holds is False
    assert "sign -1" in out.reason


def test_regularization_wrong_control_law_fails(regularization):
    ob, subject = regularization
    out = ob.verify(dataclasses.replace(subject, u_of_z=subject.u_of_z + 2 * g.k_i * g.e_i))
    assert out.holds is False
    assert "not u =" in out.reason


def test_regularization_unbounded_selection_fails(regularization):
    ob, subject = regularization
    out = ob.verify(_replace_branch(subject, 1, vdot=sp.Integer(0)))
    assert out.holds is False
    assert "unbounded" in out.reason


def test_branch_is_frozen():
    br = Branch("v > 0", 1, sp.S.Reals, sp.Integer(0))
    with pytest.raises(dataclasses.FrozenInstanceError):
        br.v_sign = 0


# --------------------------------------------------------------------------- assumption1.routh


@pytest.fixture(scope="module")
def routh():
    ob = Assumption1Routh()
    return ob, ob.derive()


def test_routh_holds(routh):
    ob, subject = routh
    out = ob.verify(subject)
    assert out.holds, out.reason
    k_p, k_i, k_v = subject.gains
    assert [sp.expand(m) for m in hurwitz_minors(sp.Poly(subject.paper_polynomial, subject.s))] == [
        k_v,
        sp.expand(k_p * k_v - k_i),
        sp.expand(k_i * (k_p * k_v - k_i)),
    ]


def test_routh_flipped_sign_in_A_fails(routh):
    ob, subject = routh
    k_p, k_i, k_v = subject.gains
    out = ob.verify(dataclasses.replace(subject, A=_with(subject.A, 0, 2, k_i)))
    assert out.holds is False
    assert "det(sI - A)" in out.reason


def test_routh_dropping_a_condition_fails(routh):
    ob, subject = routh
    k_p, k_i, k_v = subject.gains
    out = ob.verify(dataclasses.replace(subject, assumption=(k_i, k_v * k_p - k_i)))
    assert out.holds is False
    assert "(⇐) fails" in out.reason


def test_routh_stronger_condition_fails_the_converse(routh):
    ob, subject = routh
    k_p, k_i, k_v = subject.gains
    out = ob.verify(dataclasses.replace(subject, assumption=(k_i, k_p, k_v * k_p - 2 * k_i)))
    assert out.holds is False
    assert "(⇒) fails" in out.reason


def test_routh_wrong_polynomial_fails(routh):
    ob, subject = routh
    k_p, k_i, k_v = subject.gains
    s = subject.s
    out = ob.verify(dataclasses.replace(subject, paper_polynomial=s**3 + k_v * s**2 + k_p * s - k_i))
    assert out.holds is False
    assert "differs from the paper's" in out.reason


# --------------------------------------------------------------------------- equilibria


@pytest.fixture(scope="module")
def equilibria():
    ob = Equilibria()
    return ob, ob.derive()


def test_equilibria_hold(equilibria):
    ob, subject = equilibria
    out = ob.verify(subject)
    assert out.holds, out.reason
    assert subject.attractor_x[1] == sp.Interval(-g.f_c, g.f_c)
    assert subject.attractor_z[0] == sp.Interval(-g.f_c / g.k_i, g.f_c / g.k_i)


def test_equilibria_moved_attractor_bound_fails(equilibria):
    ob, subject = equilibria
    out = ob.verify(dataclasses.replace(subject, attractor_x=(0, sp.Interval(-g.f_c, 2 * g.f_c), 0)))
    assert out.holds is False
    assert "𝒜 says Interval(-f_c, 2*f_c)" in out.reason


def test_equilibria_moved_z_bound_fails(equilibria):
    ob, subject = equilibria
    out = ob.verify(dataclasses.replace(subject, attractor_z=(sp.Interval(-g.f_c, g.f_c), 0, 0)))
    assert out.holds is False
    assert "e_i" in out.reason


def test_equilibria_wrong_integral_gain_in_A_z_fails(equilibria):
    ob, subject = equilibria
    out = ob.verify(dataclasses.replace(subject, A_z=_with(subject.A_z, 2, 0, -2 * g.k_i)))
    assert out.holds is False
    assert "f_c/(2*k_i)" in out.reason


def test_equilibria_singular_A_fails(equilibria):
    ob, subject = equilibria
    out = ob.verify(dataclasses.replace(subject, A=_with(subject.A, 0, 2, 0)))
    assert out.holds is False
    assert "singular" in out.reason


def test_equilibria_with_moving_velocity_fails(equilibria):
    ob, subject = equilibria
    # σ' = -k_i v + k_i φ/f_c... changes the v = ±1 equilibrium to one with v ≠ 0
    A = _with(subject.A, 0, 1, g.k_i / g.f_c)
    out = ob.verify(dataclasses.replace(subject, A=A))
    assert out.holds is False
    assert "equilibrium with v of sign" in out.reason


# --------------------------------------------------------------------------- distance


@pytest.fixture(scope="module")
def distance():
    ob = Distance()
    return ob, ob.derive()


def test_distance_holds(distance):
    ob, subject = distance
    out = ob.verify(subject)
    assert out.holds, out.reason
    assert len(out.details) == 5


def test_distance_wrong_dead_zone_width_fails(distance):
    ob, subject = distance
    from symbolic_friction._symbolic import dz

    wrong = g.sigma**2 + g.v**2 + dz(g.phi, 2 * g.f_c) ** 2
    out = ob.verify(dataclasses.replace(subject, formula=wrong))
    assert out.holds is False
    assert "φ > f_c" in out.reason


def test_distance_missing_velocity_term_fails(distance):
    ob, subject = distance
    out = ob.verify(dataclasses.replace(subject, formula=subject.formula - g.v**2))
    assert out.holds is False
    assert "the formula gives" in out.reason


def test_distance_moved_attractor_bound_fails(distance):
    ob, subject = distance
    out = ob.verify(dataclasses.replace(subject, attractor=(0, sp.Interval(-g.f_c, 2 * g.f_c), 0)))
    assert out.holds is False
    assert "cannot decide" in out.reason


def test_distance_needs_one_interval_component(distance):
    ob, subject = distance
    out = ob.verify(dataclasses.replace(subject, attractor=(0, 0, 0)))
    assert out.holds is False
    assert "exactly one interval component" in out.reason


def test_equilibria_undecidable_velocity_fails(equilibria):
    ob, subject = equilibria
    A = _with(subject.A, 0, 1, (g.k_i - g.k_p) / g.f_c)
    out = ob.verify(dataclasses.replace(subject, A=A))
    assert out.holds is False
    assert "cannot exclude an equilibrium with v of sign 1" in out.reason
