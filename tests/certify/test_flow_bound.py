"""The enclosure of κ_lin = sup_t ‖e^{At}‖₂: it contains a 30-digit estimate, each step can fail, and it refuses
what it cannot show."""

from __future__ import annotations

import functools
from fractions import Fraction

import flint
import mpmath
import pytest

from symbolic_friction import Parameters
from symbolic_friction._certify import flow_bound
from symbolic_friction._certify.flow_bound import kappa_lin_bound
from symbolic_friction.errors import ParameterError


def _norm_mp(params: Parameters, t: float) -> mpmath.mpf:
    mpmath.mp.dps = 30
    k_p, k_i, k_v = (mpmath.mpf(Fraction(q).numerator) / Fraction(q).denominator for q in (params.k_p, params.k_i, params.k_v))
    A = mpmath.matrix([[0, 0, -k_i], [1, 0, -k_p], [0, 1, -k_v]])
    M = mpmath.expm(A * mpmath.mpf(t))
    return mpmath.sqrt(max(mpmath.eigsy(M.T * M)[0]))


def _mp(q: Fraction) -> mpmath.mpf:
    return mpmath.mpf(q.numerator) / q.denominator


@functools.cache
def _bound(params: Parameters):
    """:func:`kappa_lin_bound` (a pure function of the gains) once per gains for the tests that read it unpatched."""
    return kappa_lin_bound(params)


GAINS = [Parameters.table_i("a"), Parameters.table_i("b"), Parameters(k_p=3, k_i=1, k_v=3),  # triple root -1
         Parameters(k_p=1, k_i=Fraction(1, 10**6), k_v=1)]


@pytest.mark.parametrize("params", GAINS, ids=["a", "b", "triple root", "k_i 1e-6"])
def test_the_enclosure_contains_a_30_digit_sampled_supremum(params):
    b = _bound(params)
    assert b.lower <= b.upper <= b.lower * Fraction(1001, 1000) + Fraction(1, 10**6)
    # the norm at the peak, and on a grid around it, in 30 digits: never above the upper end
    peak = _norm_mp(params, b.t_peak)
    assert _mp(b.lower) <= peak <= _mp(b.upper)
    for k in range(-20, 21):
        assert _norm_mp(params, b.t_peak * (1 + k / 100)) <= _mp(b.upper)


def test_table_i_values():
    a, b = _bound(Parameters.table_i("a")), _bound(Parameters.table_i("b"))
    assert Fraction("1.373267") < a.lower and a.upper < Fraction("1.3750")
    assert Fraction("2.396915") < b.lower and b.upper < Fraction("2.4000")


def test_a_target_below_the_supremum_cannot_be_covered():
    params = Parameters.table_i("a")
    b = _bound(params)
    old = flint.ctx.prec
    flint.ctx.prec = flow_bound.PRECISION
    try:
        A = flow_bound._system(params)
        low = flow_bound._arb(b.lower * b.lower * Fraction(99, 100))
        done, above = flow_bound._cover(A, low, b.horizon, 10_000)
        assert above is not None and abs(above - b.t_peak) < 0.5
        high = flow_bound._arb(b.upper_squared)
        assert flow_bound._cover(A, high, b.horizon, 10_000)[1] is None
    finally:
        flint.ctx.prec = old


def test_the_lower_end_is_a_norm_reached():
    params = Parameters.table_i("b")
    old = flint.ctx.prec
    flint.ctx.prec = flow_bound.PRECISION
    try:
        A = flow_bound._system(params)
        for t in (0.3, 1.0, 2.5):
            low = _mp(flow_bound._lower(A, t))
            assert low <= _norm_mp(params, t) <= low * (1 + mpmath.mpf(10) ** -12)
    finally:
        flint.ctx.prec = old


def test_the_tail_constant_bounds_the_condition_number_of_P():
    import numpy as np

    from symbolic_friction._model.lyapunov import lyapunov_matrix

    for params in GAINS:
        eig = np.linalg.eigvalsh(lyapunov_matrix(params))
        assert flow_bound._p_condition(params) >= eig[-1] / eig[0]


def test_a_missed_peak_is_found_again_and_a_cover_that_accepts_everything_is_caught(monkeypatch):
    params = Parameters.table_i("a")
    real_peak = flow_bound._peak

    def missed(A, horizon, near=None):  # the sampling finds a point far from the peak
        return 0.05 if near is None else real_peak(A, horizon, near)

    monkeypatch.setattr(flow_bound, "_peak", missed)
    b = kappa_lin_bound(params)  # the cover fails near the real peak and the restart finds it
    true_sup = _norm_mp(params, b.t_peak)
    assert _mp(b.lower) <= true_sup <= _mp(b.upper) and abs(b.t_peak - 0.05) > 0.5
    monkeypatch.setattr(flow_bound, "_below", lambda mu, S: True)
    weak = kappa_lin_bound(params)
    assert _mp(weak.upper) < true_sup  # what the 30-digit check above would refuse


def test_bad_input_is_refused():
    with pytest.raises(ParameterError, match="rel_tol must be in"):
        kappa_lin_bound(Parameters.table_i("a"), rel_tol=0)
    with pytest.raises(ParameterError, match="cannot show|did not settle"):
        kappa_lin_bound(Parameters(k_p=1, k_i=1, k_v=1 + Fraction(1, 10**6)), max_pieces=200)


def test_the_tail_constant_does_not_trust_the_float_eigenvalues(monkeypatch):
    # floats only seed the search: a wrong guess (λ_min ≤ 0, λ_max far too small) still ends in an exact bound
    import numpy as np

    from symbolic_friction._model.lyapunov import lyapunov_matrix

    params = Parameters.table_i("b")
    true = np.linalg.eigvalsh(lyapunov_matrix(params))
    monkeypatch.setattr(np.linalg, "eigvalsh", lambda M: np.array([-1.0, 0.0, 1e-3]))
    q = flow_bound._p_condition(params)
    assert q > 0 and q >= true[-1] / true[0]
