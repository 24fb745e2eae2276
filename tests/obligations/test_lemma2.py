"""Lemma 2 obligations: lemma2.P, lemma2.lower_bound, lemma2.dVdt and remark.armstrong."""

import dataclasses

import pytest
import sympy as sp

from symbolic_friction._obligations._decide import G
from symbolic_friction._obligations.lemma2 import Lemma2dVdt, Lemma2LowerBound, Lemma2P, RemarkArmstrong

g = G()


def _with(matrix, i, j, value, symmetric=False):
    m = sp.Matrix(matrix)
    m[i, j] = value
    if symmetric:
        m[j, i] = value
    return sp.ImmutableMatrix(m)


# --------------------------------------------------------------------------- lemma2.P


@pytest.fixture(scope="module")
def lemma_p():
    ob = Lemma2P()
    return ob, ob.derive()


def test_P_holds(lemma_p):
    ob, subject = lemma_p
    out = ob.verify(subject)
    assert out.holds, out.reason
    minors = [sp.factor(subject.P[:k, :k].det()) for k in (1, 2, 3)]
    assert sp.simplify(minors[2] - (g.k_v * g.k_p - g.k_i) / g.k_i) == 0


def test_P_perturbed_entry_fails(lemma_p):
    ob, subject = lemma_p
    out = ob.verify(dataclasses.replace(subject, P=_with(subject.P, 0, 2, -2, symmetric=True)))
    assert out.holds is False
    assert "(⇐) fails" in out.reason and "Δ_3" in out.reason


def test_P_not_symmetric_fails(lemma_p):
    ob, subject = lemma_p
    out = ob.verify(dataclasses.replace(subject, P=_with(subject.P, 0, 2, 1)))
    assert out.holds is False
    assert "not symmetric" in out.reason


def test_P_with_a_stronger_condition_fails_the_converse(lemma_p):
    ob, subject = lemma_p
    out = ob.verify(dataclasses.replace(subject, condition=g.k_v * g.k_p - 2 * g.k_i))
    assert out.holds is False
    assert "(⇒) fails" in out.reason


def test_P_condition_not_solvable_fails(lemma_p):
    ob, subject = lemma_p
    out = ob.verify(dataclasses.replace(subject, condition=g.k_p - g.k_i))
    assert out.holds is False
    assert "cannot write the condition" in out.reason


# --------------------------------------------------------------------------- lemma2.lower_bound


@pytest.fixture(scope="module")
def lower_bound():
    ob = Lemma2LowerBound()
    return ob, ob.derive()


def test_lower_bound_holds(lower_bound):
    ob, subject = lower_bound
    out = ob.verify(subject)
    assert out.holds, out.reason
    # c₁ is λ_min(P) on a sample of exact gains (checked here independently with sympy's eigenvalues)
    sub = {g.k_p: 3, g.k_i: 4, g.k_v: sp.Rational(32, 5)}
    eigs = sp.Matrix(subject.P.subs(sub)).eigenvals()
    assert sp.simplify(subject.c1.subs(sub) - sp.Min(*eigs)) == 0


def test_lower_bound_P_not_matching_the_form_fails(lower_bound):
    ob, subject = lower_bound
    out = ob.verify(dataclasses.replace(subject, P=_with(subject.P, 1, 1, sp.Rational(1, 2))))
    assert out.holds is False
    assert "is not (σ, y, v) P (σ, y, v)ᵀ" in out.reason


def test_lower_bound_coupled_friction_row_fails(lower_bound):
    ob, subject = lower_bound
    P = _with(subject.P, 0, 1, 1, symmetric=True)
    y = subject.y
    X = sp.Matrix([g.sigma, y, g.v])
    out = ob.verify(dataclasses.replace(subject, P=P, form=sp.expand((X.T * P * X)[0])))
    assert out.holds is False
    assert "not decoupled" in out.reason


def test_lower_bound_larger_eigenvalue_fails(lower_bound):
    ob, subject = lower_bound
    M2 = sp.Matrix(subject.P).extract([0, 2], [0, 2])
    bigger = (M2.trace() + sp.sqrt(sp.expand(M2.trace() ** 2 - 4 * M2.det()))) / 2
    out = ob.verify(dataclasses.replace(subject, g_min=bigger, c1=sp.Min(bigger, 1)))
    assert out.holds is False
    assert "not the smaller eigenvalue" in out.reason


def test_lower_bound_not_an_eigenvalue_fails(lower_bound):
    ob, subject = lower_bound
    out = ob.verify(dataclasses.replace(subject, g_min=subject.g_min / 2))
    assert out.holds is False
    assert "is not an eigenvalue" in out.reason


def test_lower_bound_wrong_c1_fails(lower_bound):
    ob, subject = lower_bound
    out = ob.verify(dataclasses.replace(subject, c1=sp.Min(subject.g_min, 2)))
    assert out.holds is False
    assert "is not min{𝔤, 1}" in out.reason


def test_lower_bound_doubled_distance_fails(lower_bound):
    ob, subject = lower_bound
    dz2 = subject.dist2 - g.sigma**2 - g.v**2
    out = ob.verify(dataclasses.replace(subject, dist2=subject.dist2 + dz2))
    assert out.holds is False
    assert "is not shown ≥ dz(φ)²" in out.reason


def test_lower_bound_distance_mixing_states_fails(lower_bound):
    ob, subject = lower_bound
    out = ob.verify(dataclasses.replace(subject, dist2=subject.dist2 + g.sigma * g.v))
    assert out.holds is False
    assert "depends on σ or v" in out.reason


def test_lower_bound_narrow_stick_friction_fails(lower_bound):
    ob, subject = lower_bound
    sgn = dict(subject.sgn)
    sgn[0] = sp.Interval(sp.Rational(-1, 2), sp.Rational(1, 2))
    out = ob.verify(dataclasses.replace(subject, sgn=sgn))
    assert out.holds is False
    assert "V ≠ 0 on 𝒜" in out.reason


# --------------------------------------------------------------------------- lemma2.dVdt


@pytest.fixture(scope="module")
def dvdt():
    ob = Lemma2dVdt()
    return ob, ob.derive()


def test_dVdt_holds(dvdt):
    ob, subject = dvdt
    out = ob.verify(subject)
    assert out.holds, out.reason
    lyap = sp.Matrix(subject.A).T * subject.P + subject.P * sp.Matrix(subject.A)
    assert lyap.applyfunc(sp.simplify) == sp.diag(0, 0, -subject.c)


def test_dVdt_paper_V0_with_xi_v_fails(dvdt):
    """The appendix's V₀ = (k_v/k_i)ξ_v² (the erratum) is caught."""
    ob, subject = dvdt
    V = dict(subject.V)
    V[0] = g.k_v / g.k_i * g.v**2
    out = ob.verify(dataclasses.replace(subject, V=V))
    assert out.holds is False
    assert "differs from (k_v/k_i)σ²" in out.reason


def test_dVdt_flipped_friction_in_f1_fails(dvdt):
    ob, subject = dvdt
    f = dict(subject.f)
    f[1] = subject.f[-1]
    out = ob.verify(dataclasses.replace(subject, f=f))
    assert out.holds is False
    assert "d/dt V_1 along f_1" in out.reason


def test_dVdt_wrong_rate_fails(dvdt):
    ob, subject = dvdt
    out = ob.verify(dataclasses.replace(subject, c=2 * g.k_v * g.k_p))
    assert out.holds is False
    assert "not" in out.reason and "V_1" in out.reason


def test_dVdt_negative_rate_fails(dvdt):
    ob, subject = dvdt
    out = ob.verify(dataclasses.replace(subject, c=-subject.c))
    assert out.holds is False
    assert "not shown positive" in out.reason


def test_dVdt_stick_field_moving_v_fails(dvdt):
    ob, subject = dvdt
    f = dict(subject.f)
    f[0] = sp.ImmutableMatrix([0, g.sigma, g.sigma])
    out = ob.verify(dataclasses.replace(subject, f=f))
    assert out.holds is False
    assert "f_0 moves v" in out.reason


def test_dVdt_wrong_V0_changing_along_f0_fails(dvdt):
    ob, subject = dvdt
    V = dict(subject.V)
    V[0] = g.phi**2
    out = ob.verify(dataclasses.replace(subject, V=V))
    assert out.holds is False
    assert "d/dt V_0 along f_0" in out.reason


# --------------------------------------------------------------------------- remark.armstrong


@pytest.fixture(scope="module")
def armstrong():
    ob = RemarkArmstrong()
    return ob, ob.derive()


def test_armstrong_holds(armstrong):
    ob, subject = armstrong
    out = ob.verify(subject)
    assert out.holds, out.reason
    assert sum("V = \\frac{k_{v} \\sigma^{2}}{k_{i}}" == tex for _, tex in out.details) == 3


def test_armstrong_without_stick_friction_fails(armstrong):
    ob, subject = armstrong
    sgn = dict(subject.sgn)
    sgn[0] = sp.FiniteSet(0)
    out = ob.verify(dataclasses.replace(subject, sgn=sgn))
    assert out.holds is False
    assert "stick with φ = f_c" in out.reason and "f_c**2" in out.reason


def test_armstrong_wrong_stick_value_fails(armstrong):
    ob, subject = armstrong
    out = ob.verify(dataclasses.replace(subject, stick_value=g.k_p * g.sigma**2))
    assert out.holds is False
    assert "not k_p*sigma**2" in out.reason


def test_armstrong_non_strict_decrease_fails(armstrong):
    ob, subject = armstrong
    out = ob.verify(dataclasses.replace(subject, c=-subject.c))
    assert out.holds is False
    assert "decrease of V is not strict" in out.reason


def test_armstrong_negative_coefficient_fails(armstrong):
    ob, subject = armstrong
    flipped = subject.form - 2 * subject.stick_value
    out = ob.verify(dataclasses.replace(subject, form=flipped, stick_value=-subject.stick_value))
    assert out.holds is False
    assert "coefficient -k_v/k_i is not shown positive" in out.reason


def test_armstrong_stick_value_with_other_terms_fails(armstrong):
    ob, subject = armstrong
    shifted = subject.form + g.sigma
    out = ob.verify(dataclasses.replace(subject, form=shifted, stick_value=subject.stick_value + g.sigma))
    assert out.holds is False
    assert "multiple of σ² alone" in out.reason
