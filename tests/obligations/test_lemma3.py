"""Lemma 3: lemma3.R, lemma3.hatV_bounds, lemma3.hatV_derivative."""

from __future__ import annotations

import dataclasses
import itertools
from fractions import Fraction as F

import numpy as np
import pytest
import sympy as sp

from symbolic_friction import Parameters
from symbolic_friction._model import lyapunov as _lyapunov
from symbolic_friction._obligations import lemma3
from symbolic_friction._obligations._inequalities import case_grid, line_cases
from symbolic_friction._obligations._derived_k import _leading_witness
from symbolic_friction._obligations.lemma3 import HatVBounds, HatVDerivative, LemmaR

from ..tolerance import assert_close
from ._helpers import assert_fails, assert_holds, subject_fixture

r_subject = subject_fixture(LemmaR)
bounds_subject = subject_fixture(HatVBounds)
deriv_subject = subject_fixture(HatVDerivative)


@pytest.fixture(scope="module")
def deriv_outcome(deriv_subject):
    return HatVDerivative().verify(deriv_subject)


# ---------------------------------------------------------------- lemma3.R


def test_R_holds(r_subject):
    out = assert_holds(LemmaR(), r_subject)
    assert out.reason.startswith("9 pieces of R")
    labels = dict(out.details)
    assert "\\frac{\\delta}{k_{i}}" in labels["\\det(\\text{outer block of }P)\\text{ under Assumption 1}"]


def test_R_perturbed_P_breaks_the_upper_bound(r_subject):
    P = r_subject.P.copy()
    P[0, 0] = 2 * P[0, 0]
    assert_fails(LemmaR(), dataclasses.replace(r_subject, P=P), "is not ≥ every eigenvalue of P")


def test_R_coupled_P_breaks_the_block_structure(r_subject):
    P = r_subject.P.copy()
    P[0, 1] = P[1, 0] = sp.Rational(1, 10)
    assert_fails(LemmaR(), dataclasses.replace(r_subject, P=P), "the middle row and column of P are decoupled fails")


def test_R_wrong_minimiser_at_stick(r_subject):
    g = r_subject
    wrong = sp.Piecewise((g.f_c * sp.sign(g.v), sp.Ne(g.v, 0)), (g.f_c, True))
    assert_fails(LemmaR(), dataclasses.replace(r_subject, minimizer=wrong), "does not minimise")


def test_R_minimiser_outside_SGN(r_subject):
    g = r_subject
    wrong = sp.Piecewise((-g.f_c * sp.sign(g.v), sp.Ne(g.v, 0)), (g.phi, True))
    assert_fails(LemmaR(), dataclasses.replace(r_subject, minimizer=wrong), "is not in f_c·SGN(v)")


def test_R_moved_attractor_bound(r_subject):
    g = r_subject
    dz2 = sp.Piecewise((g.phi + 2 * g.f_c, g.phi < -2 * g.f_c), (g.phi - 2 * g.f_c, g.phi > 2 * g.f_c), (0, True))
    # with the old case split the moved breakpoints cannot even be placed
    assert_fails(LemmaR(), dataclasses.replace(r_subject, dz=dz2), "cannot decide the branch condition")
    # with a split at the moved breakpoints, the minimum is no longer dz²
    cases = case_grid(
        line_cases(g.v, [0], name="v", beyond="a_v"),
        line_cases(g.phi, [-2 * g.f_c, 2 * g.f_c], name="φ", beyond="d_phi", weights=("u_phi", "w_phi")),
    )
    moved = dataclasses.replace(r_subject, dz=dz2, dist2=g.sigma**2 + g.v**2 + dz2**2, cases=tuple(cases))
    assert_fails(LemmaR(), moved, "differs from dz(φ)")


def test_R_wrong_region(r_subject):
    g = r_subject
    assert_fails(LemmaR(), dataclasses.replace(r_subject, region=g.v * (g.phi + sp.sign(g.v) * g.f_c)), "differs from dz(φ)")


def test_R_constants_too_tight(r_subject):
    assert_fails(LemmaR(), dataclasses.replace(r_subject, c2=r_subject.c2 * sp.Rational(99, 100)), "c₂ =")
    assert_fails(LemmaR(), dataclasses.replace(r_subject, c1=sp.Integer(1)), "c₁ = 1 is not ≤")


def test_R_needs_assumption1(r_subject):
    # a P whose outer determinant is not positive under k_v k_p > k_i
    P = r_subject.P.copy()
    P[0, 2] = P[2, 0] = -2
    assert_fails(LemmaR(), dataclasses.replace(r_subject, P=P), "cannot show λ_min(P) > 0 under Assumption 1")


def _outward(value: sp.Expr, *, up: bool) -> F:
    """A rational within 1e-30 of the algebraic number ``value``, rounded outward."""
    scaled = (sp.ceiling if up else sp.floor)(value * 10**30)
    return F(int(scaled), 10**30)


def test_R_matches_the_package_V_on_rational_points(r_subject):
    """Exact: the package's V equals wᵀPw on R and lies between the subject's c₁, c₂ times |x|²_𝒜."""
    g = lemma3.G()
    for case in ("a", "b"):
        p = Parameters.table_i(case)
        sub = {g.k_p: sp.Rational(str(p.k_p)), g.k_i: sp.Rational(str(p.k_i)), g.k_v: sp.Rational(str(p.k_v))}
        c1 = _outward(r_subject.c1.xreplace(sub), up=False)
        c2 = _outward(r_subject.c2.xreplace(sub), up=True)
        assert 0 < c1 < c2
        values = [F(-3), F(-1), F(-1, 2), F(0), F(1, 3), F(1), F(5, 2)]
        checked = 0
        for x in itertools.product(values, repeat=3):
            x = np.array(x, dtype=object)
            if not _lyapunov.in_R(p, x):
                continue
            sigma, phi, v = x
            d = phi - p.f_c if phi > p.f_c else (phi + p.f_c if phi < -p.f_c else F(0))
            w = (sigma, d, v)
            entries = _lyapunov.lyapunov_matrix_entries(p.k_p, p.k_i, p.k_v)
            quad = sum(F(r) * wi * wj for row, wi in zip(entries, w) for r, wj in zip(row, w))
            assert _lyapunov.V(p, x) == quad
            dist2 = sigma**2 + d**2 + v**2
            assert c1 * dist2 <= quad <= c2 * dist2
            checked += 1
        assert checked > 100


def test_R_constants_match_numeric_eigenvalues(r_subject):
    g = lemma3.G()
    for case in ("a", "b"):
        p = Parameters.table_i(case)
        sub = {g.k_p: sp.Rational(str(p.k_p)), g.k_i: sp.Rational(str(p.k_i)), g.k_v: sp.Rational(str(p.k_v))}
        lam = np.linalg.eigvalsh(_lyapunov.lyapunov_matrix(p))
        assert_close(float(r_subject.c1.xreplace(sub)), lam[0], rtol=1e-12, what="c1 = λ_min(P)")
        assert_close(float(r_subject.c2.xreplace(sub)), lam[-1], rtol=1e-12, what="c2 = λ_max(P)")


# ------------------------------------------------------- lemma3.hatV_bounds


def test_bounds_hold(bounds_subject):
    out = assert_holds(HatVBounds(), bounds_subject)
    assert "needs no k₁k₄ > k₃²" in out.reason
    assert "e_1: 0" in dict(out.details)["\\tfrac12 w^TKw - \\hat c_1|w|^2 \\text{ at the minimising unit vector}"]


def test_bounds_negative_k3_in_K(bounds_subject):
    K = bounds_subject.K.copy()
    K[0, 2] = K[2, 0] = -K[0, 2]
    assert_fails(HatVBounds(), dataclasses.replace(bounds_subject, K=K), "V̂ − ½wᵀKw")


def test_bounds_wrong_Vhat(bounds_subject):
    s = bounds_subject
    assert_fails(HatVBounds(), dataclasses.replace(s, Vhat=s.Vhat + s.k[1] * s.phi**2 / 7), "V̂ − ½wᵀKw")


def test_bounds_wrong_definiteness_condition(bounds_subject):
    k1, k2, k3, k4 = bounds_subject.k
    assert_fails(HatVBounds(), dataclasses.replace(bounds_subject, definiteness=k1 * k4 - 2 * k3**2), "is not a positive multiple")


def test_bounds_c2_hat_lowered_one_percent(bounds_subject):
    s = bounds_subject
    assert_fails(HatVBounds(), dataclasses.replace(s, c2_hat=s.c2_hat * sp.Rational(99, 100)), "2ĉ₂")


def test_bounds_c1_hat_too_large(bounds_subject):
    k1, k2, k3, k4 = bounds_subject.k
    assert_fails(HatVBounds(), dataclasses.replace(bounds_subject, c1_hat=sp.Max(k1, k2, k4) / 2), "½wᵀKw ≥ ĉ₁|w|² not shown")
    assert_fails(HatVBounds(), dataclasses.replace(bounds_subject, c1_hat_eig=k2 / 2), "eigenvalue route")


def test_bounds_sharp_constant_beats_eigenvalue_and_matches_package(bounds_subject):
    """½min(k₁,k₂,k₄) ≥ ½λ_min(K), and the package's V_hat equals ½wᵀKw at rational points."""
    s = bounds_subject
    p = Parameters.table_i("a")
    ks = (F(1), F(1), F(2), F(5))
    K = np.array(_lyapunov.vhat_matrix_entries(*[float(k) for k in ks]))
    lam = np.linalg.eigvalsh(K)
    sub = dict(zip(s.k, [sp.Rational(str(k)) for k in ks]))
    assert bool(s.c1_hat.xreplace(sub) > s.c1_hat_eig.xreplace(sub))  # ½min(k₁,k₂,k₄) beats ½λ_min(K), exactly
    assert_close(float(s.c2_hat.xreplace(sub)), lam[-1] / 2, rtol=1e-12, what="ĉ2")
    for x in itertools.product([F(-2), F(-1, 3), F(0), F(1, 2), F(3)], repeat=3):
        sigma, phi, v = x
        d = phi - 1 if phi > 1 else (phi + 1 if phi < -1 else F(0))
        w = (abs(sigma), abs(d), abs(v))
        quad = F(1, 2) * sum(F(K_ij) * wi * wj for row, wi in zip(_lyapunov.vhat_matrix_entries(*ks), w) for K_ij, wj in zip(row, w))
        assert _lyapunov.V_hat(p, np.array(x, dtype=object), ks) == quad
        assert quad >= min(ks[0], ks[1], ks[3]) / 2 * sum(wi**2 for wi in w)


# ---------------------------------------------------- lemma3.hatV_derivative


def test_derivative_holds(deriv_outcome):
    assert deriv_outcome.holds, deriv_outcome.reason
    assert "derived set = stated set (9 conditions)" in deriv_outcome.reason
    assert "only sufficient" not in deriv_outcome.reason
    details = dict(deriv_outcome.details)
    derived = details["\\text{derived from } \\hat V^\\circ \\le 0 \\text{ (necessary and sufficient)}"]
    assert derived.count("\\ge 0") == 4 and "sufficient only" not in derived


def test_derived_conditions_are_the_papers(deriv_subject):
    derived, failures, _ = lemma3.derived_k_conditions(deriv_subject)
    assert failures == []
    k1, k2, k3, k4 = deriv_subject.k
    k_p, k_i, k_v = deriv_subject.gains
    want = {k3 * k_v - k_i * k1, k3 - k2, k4 * k_v - k_i * k3, k4 - k_p * k2}
    assert {sp.expand(d.expr) for d in derived} == {sp.expand(w) for w in want}
    assert all(d.necessary and not d.strict for d in derived)


def test_derivative_dropped_condition(deriv_subject):
    stated = tuple(c for c in deriv_subject.stated if c.name != "k4 > k_p·k2")
    assert_fails(HatVDerivative(), dataclasses.replace(deriv_subject, stated=stated), "-k_2*k_p + k_4 ≥ 0")


def test_derivative_dropped_definiteness(deriv_subject):
    stated = tuple(c for c in deriv_subject.stated if c.kind != "definiteness")
    assert_fails(HatVDerivative(), dataclasses.replace(deriv_subject, stated=stated), "K ≻ 0 (Sylvester)")


def test_derivative_weakened_condition(deriv_subject):
    stated = tuple(dataclasses.replace(c, rhs=c.rhs / 2) if c.name == "k3 > k2" else c for c in deriv_subject.stated)
    assert_fails(HatVDerivative(), dataclasses.replace(deriv_subject, stated=stated), "stated condition k3 > k2")


def test_derivative_non_strict_definiteness(deriv_subject):
    stated = tuple(dataclasses.replace(c, strict=False) if c.kind == "definiteness" else c for c in deriv_subject.stated)
    assert_fails(HatVDerivative(), dataclasses.replace(deriv_subject, stated=stated), "stated k1·k4 > k3² must be strict")


def test_derivative_flipped_friction_sign(deriv_subject):
    s = deriv_subject
    F_ = (s.F[0], s.F[1], s.F[2] + 2 * s.f_c * sp.sign(s.v))  # +b SGN(v) instead of −b SGN(v)
    assert_fails(HatVDerivative(), dataclasses.replace(s, F=F_), "is positive for every choice of k")


def test_derivative_flipped_sign_in_A(deriv_subject):
    s = deriv_subject
    F_ = (-s.F[0], s.F[1], s.F[2])  # σ' = +k_i v
    out = assert_fails(HatVDerivative(), dataclasses.replace(s, F=F_))
    assert "not stated" in out.reason or "bracketed bound" in out.reason


def test_derivative_not_C1(deriv_subject):
    s = deriv_subject
    k2 = s.k[1]
    dz = sp.Piecewise((s.phi + s.f_c, s.phi < -s.f_c), (s.phi - s.f_c, s.phi > s.f_c), (0, True))
    Vhat = s.Vhat - k2 * dz**2 / 2 + k2 * dz / 2  # dz itself has a kink at ±f_c
    assert_fails(HatVDerivative(), dataclasses.replace(s, Vhat=Vhat), "∂V̂/∂φ jumps at φ")


def test_derivative_checks_the_papers_f_v_bound(deriv_subject):
    s = deriv_subject
    dz = sp.Piecewise((s.phi + s.f_c, s.phi < -s.f_c), (s.phi - s.f_c, s.phi > s.f_c), (0, True))
    wrong = -s.gains[2] * sp.Abs(s.v) - 2 * sp.Abs(dz) - s.f_c  # claims too much
    assert_fails(HatVDerivative(), dataclasses.replace(s, f_v_bound=wrong), "sign(v)·f_v ≤ −k_v|v| − |dz(φ)| fails")


def test_derivative_checks_the_zeta_claim(deriv_subject):
    s = deriv_subject
    assert_fails(HatVDerivative(), dataclasses.replace(s, zeta_claim=-s.zeta_claim), "max over ∂|σ| exceeds")


def test_derivative_checks_the_pairing(deriv_subject):
    s = deriv_subject
    pairs = list(s.paper_pairs)
    bracket, coeff, mono = pairs[1]
    pairs[1] = (bracket, coeff - s.k[2], mono)  # claims k₂ − 2k₃ instead of k₂ − k₃
    assert_fails(HatVDerivative(), dataclasses.replace(s, paper_pairs=tuple(pairs)), "is not ≤")


def test_derivative_paper_bound_too_small(deriv_subject):
    s = deriv_subject
    assert_fails(HatVDerivative(), dataclasses.replace(s, paper_bound=s.paper_bound - s.k[3] * s.gains[2] * s.v**2), "bracketed bound is below")


def test_derivative_records_the_erratum(deriv_outcome):
    assert "equals k_i k₃|v|² in 12 pieces and is smaller in 6" in deriv_outcome.reason
    (erratum,) = HatVDerivative.errata
    assert "equality iff σ ≤ 0" in erratum.correct


def test_leading_witness_detects_a_merely_sufficient_condition():
    a, w, c = sp.symbols("a w c", positive=True)
    # c·a·w − a² − w² ≤ 0 holds for c ≤ 2: "c ≤ 0" would be sufficient, not necessary
    assert _leading_witness(c * a * w - a**2 - w**2, c, (a, w)) is None
    assert _leading_witness(c * a * w - w**2 - a, c, (a, w)) == (2, 1)
