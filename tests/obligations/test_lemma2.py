"""Lemma 2 obligations: lemma2.P, lemma2.lower_bound, lemma2.dVdt and remark.armstrong."""

import dataclasses

import sympy as sp

from symbolic_friction._obligations._decide import G
from symbolic_friction._obligations.lemma2 import Lemma2dVdt, Lemma2LowerBound, Lemma2P
from symbolic_friction._obligations.remark import RemarkArmstrong

from ._helpers import assert_fails, assert_holds, obligation_fixture, replace_key, with_entry

g = G()


# --------------------------------------------------------------------------- lemma2.P


lemma_p = obligation_fixture(Lemma2P)


def test_P_holds(lemma_p):
    ob, subject = lemma_p
    assert_holds(ob, subject)
    minors = [sp.factor(subject.P[:k, :k].det()) for k in (1, 2, 3)]
    assert sp.simplify(minors[2] - (g.k_v * g.k_p - g.k_i) / g.k_i) == 0


def test_P_perturbed_entry_fails(lemma_p):
    ob, subject = lemma_p
    assert_fails(ob, dataclasses.replace(subject, P=with_entry(subject.P, 0, 2, -2, symmetric=True)), "(⇐) fails", "Δ_3")


def test_P_not_symmetric_fails(lemma_p):
    ob, subject = lemma_p
    assert_fails(ob, dataclasses.replace(subject, P=with_entry(subject.P, 0, 2, 1)), "not symmetric")


def test_P_with_a_stronger_condition_fails_the_converse(lemma_p):
    ob, subject = lemma_p
    assert_fails(ob, dataclasses.replace(subject, condition=g.k_v * g.k_p - 2 * g.k_i), "(⇒) fails")


def test_P_condition_not_solvable_fails(lemma_p):
    ob, subject = lemma_p
    assert_fails(ob, dataclasses.replace(subject, condition=g.k_p - g.k_i), "cannot write the condition")


# --------------------------------------------------------------------------- lemma2.lower_bound


lower_bound = obligation_fixture(Lemma2LowerBound)


def test_lower_bound_holds(lower_bound):
    ob, subject = lower_bound
    assert_holds(ob, subject)
    # c₁ is λ_min(P) on a sample of exact gains (checked here independently with sympy's eigenvalues)
    sub = {g.k_p: 3, g.k_i: 4, g.k_v: sp.Rational(32, 5)}
    eigs = sp.Matrix(subject.P.subs(sub)).eigenvals()
    assert sp.simplify(subject.c1.subs(sub) - sp.Min(*eigs)) == 0


def test_lower_bound_P_not_matching_the_form_fails(lower_bound):
    ob, subject = lower_bound
    assert_fails(
        ob, dataclasses.replace(subject, P=with_entry(subject.P, 1, 1, sp.Rational(1, 2))), "is not (σ, y, v) P (σ, y, v)ᵀ"
    )


def test_lower_bound_coupled_friction_row_fails(lower_bound):
    ob, subject = lower_bound
    P = with_entry(subject.P, 0, 1, 1, symmetric=True)
    y = subject.y
    X = sp.Matrix([g.sigma, y, g.v])
    assert_fails(ob, dataclasses.replace(subject, P=P, form=sp.expand((X.T * P * X)[0])), "not decoupled")


def test_lower_bound_larger_eigenvalue_fails(lower_bound):
    ob, subject = lower_bound
    M2 = sp.Matrix(subject.P).extract([0, 2], [0, 2])
    bigger = (M2.trace() + sp.sqrt(sp.expand(M2.trace() ** 2 - 4 * M2.det()))) / 2
    assert_fails(ob, dataclasses.replace(subject, g_min=bigger, c1=sp.Min(bigger, 1)), "not the smaller eigenvalue")


def test_lower_bound_not_an_eigenvalue_fails(lower_bound):
    ob, subject = lower_bound
    assert_fails(ob, dataclasses.replace(subject, g_min=subject.g_min / 2), "is not an eigenvalue")


def test_lower_bound_wrong_c1_fails(lower_bound):
    ob, subject = lower_bound
    assert_fails(ob, dataclasses.replace(subject, c1=sp.Min(subject.g_min, 2)), "is not min{𝔤, 1}")


def test_lower_bound_doubled_distance_fails(lower_bound):
    ob, subject = lower_bound
    dz2 = subject.dist2 - g.sigma**2 - g.v**2
    assert_fails(ob, dataclasses.replace(subject, dist2=subject.dist2 + dz2), "is not shown ≥ dz(φ)²")


def test_lower_bound_distance_mixing_states_fails(lower_bound):
    ob, subject = lower_bound
    assert_fails(ob, dataclasses.replace(subject, dist2=subject.dist2 + g.sigma * g.v), "depends on σ or v")


def test_lower_bound_narrow_stick_friction_fails(lower_bound):
    ob, subject = lower_bound
    assert_fails(ob, replace_key(subject, "sgn", 0, sp.Interval(sp.Rational(-1, 2), sp.Rational(1, 2))), "V ≠ 0 on 𝒜")


# --------------------------------------------------------------------------- lemma2.dVdt


dvdt = obligation_fixture(Lemma2dVdt)


def test_dVdt_holds(dvdt):
    ob, subject = dvdt
    assert_holds(ob, subject)
    lyap = sp.Matrix(subject.A).T * subject.P + subject.P * sp.Matrix(subject.A)
    assert lyap.applyfunc(sp.simplify) == sp.diag(0, 0, -subject.c)


def test_dVdt_paper_V0_with_xi_v_fails(dvdt):
    """The appendix's V₀ = (k_v/k_i)ξ_v² (the erratum) is caught."""
    ob, subject = dvdt
    assert_fails(ob, replace_key(subject, "V", 0, g.k_v / g.k_i * g.v**2), "differs from (k_v/k_i)σ²")


def test_dVdt_flipped_friction_in_f1_fails(dvdt):
    ob, subject = dvdt
    assert_fails(ob, replace_key(subject, "f", 1, subject.f[-1]), "d/dt V_1 along f_1")


def test_dVdt_wrong_rate_fails(dvdt):
    ob, subject = dvdt
    assert_fails(ob, dataclasses.replace(subject, c=2 * g.k_v * g.k_p), "not", "V_1")


def test_dVdt_negative_rate_fails(dvdt):
    ob, subject = dvdt
    assert_fails(ob, dataclasses.replace(subject, c=-subject.c), "not shown positive")


def test_dVdt_stick_field_moving_v_fails(dvdt):
    ob, subject = dvdt
    assert_fails(ob, replace_key(subject, "f", 0, sp.ImmutableMatrix([0, g.sigma, g.sigma])), "f_0 moves v")


def test_dVdt_wrong_V0_changing_along_f0_fails(dvdt):
    ob, subject = dvdt
    assert_fails(ob, replace_key(subject, "V", 0, g.phi**2), "d/dt V_0 along f_0")


# --------------------------------------------------------------------------- remark.armstrong


armstrong = obligation_fixture(RemarkArmstrong)


def test_armstrong_holds(armstrong):
    ob, subject = armstrong
    out = assert_holds(ob, subject)
    assert sum("V = \\frac{k_{v} \\sigma^{2}}{k_{i}}" == tex for _, tex in out.details) == 3


def test_armstrong_without_stick_friction_fails(armstrong):
    ob, subject = armstrong
    assert_fails(ob, replace_key(subject, "sgn", 0, sp.FiniteSet(0)), "stick with φ = f_c", "f_c**2")


def test_armstrong_wrong_stick_value_fails(armstrong):
    ob, subject = armstrong
    assert_fails(ob, dataclasses.replace(subject, stick_value=g.k_p * g.sigma**2), "not k_p*sigma**2")


def test_armstrong_non_strict_decrease_fails(armstrong):
    ob, subject = armstrong
    assert_fails(ob, dataclasses.replace(subject, c=-subject.c), "decrease of V is not strict")


def test_armstrong_negative_coefficient_fails(armstrong):
    ob, subject = armstrong
    flipped = subject.form - 2 * subject.stick_value
    assert_fails(
        ob,
        dataclasses.replace(subject, form=flipped, stick_value=-subject.stick_value),
        "coefficient -k_v/k_i is not shown positive",
    )


def test_armstrong_stick_value_with_other_terms_fails(armstrong):
    ob, subject = armstrong
    shifted = subject.form + g.sigma
    assert_fails(
        ob, dataclasses.replace(subject, form=shifted, stick_value=subject.stick_value + g.sigma), "multiple of σ² alone"
    )
