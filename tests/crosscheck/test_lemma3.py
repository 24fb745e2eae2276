"""Lemma 3 on trajectories: wrong certificates and wrong trajectories are caught."""

from __future__ import annotations

from fractions import Fraction
import dataclasses
import numpy as np
import pytest

from symbolic_friction._crosscheck import Claims
from symbolic_friction._crosscheck import crosscheck
from symbolic_friction._crosscheck._initial import hat_V_rate
from symbolic_friction._crosscheck.lemma3 import run_slack
from tests.crosscheck.helpers import _cert
from tests.crosscheck.helpers import _result


def test_k4_violating_the_derived_conditions_makes_V_hat_increase(wrong_report):
    case, wrong, checks, report = wrong_report
    r = _result(checks["k4"], "lemma3.hatV_nonincreasing")
    assert r.failures > 0
    cx = r.counterexample
    assert cx.values["V_hat_t2"] > cx.values["V_hat_t1"]
    assert cx.values["increase"] > 1e3 * report.rtol * cx.values["V_hat_t1"]
    assert cx.t > cx.t_start
    # exact witness: V̂' > 0 at x(t1) ∈ R̂, in rational arithmetic (eq. hatVdot fails there)
    assert cx.exact is True and cx.values["dV_hat_dt_at_t1"] > 0


def test_k4_violating_only_definiteness_cannot_make_V_hat_increase():
    # k1 k4 > k3² fails (2·7 < 4²) but the four derivative conditions of eq. (hatVdot) hold
    # (k3 = 4 > max(k_i/k_v k1, k2) = 2, k4 = 7 > max(k_i/k_v k3, k_p k2) = 6); those four
    # are necessary and sufficient for V̂° ≤ 0 on R̂ (symbolic_friction._model.kconditions), so no
    # trajectory can show V̂ increasing in R̂, and the cross-check must not report one.
    cert = dataclasses.replace(_cert("a"), k1=2, k2=2, k3=4, k4=7, c1_hat=1, c2_hat=Fraction(427, 100))
    assert not cert.k1 * cert.k4 > cert.k3**2
    cl = Claims.from_certificate(cert, label="definiteness only")
    report = crosscheck([cl], trajectories=200, seed=3, progress=False, require_proved=False)
    res = {r.id: r for r in report.checks[0].results}
    assert res["lemma3.hatV_nonincreasing"].failures == 0 and res["lemma3.hatV_nonincreasing"].samples > 0
    assert res["lemma3.hatV_lower"].failures == 0  # ½wᵀKw ≥ ½min(k1,k2,k4)|w|² on w ≥ 0 anyway
    from symbolic_friction._crosscheck._initial import rate_maximisers

    X = rate_maximisers(cl.params, cl, seed=0, count=4)
    assert np.nanmax(hat_V_rate(cl.params, cl, X)) <= 1e-12


def test_run_slack_matches_brute_force():
    rng = np.random.default_rng(0)
    F = rng.normal(size=(5, 30)) * 10
    run = rng.random((5, 29)) < 0.7
    slack, first = run_slack(F, run)
    for i in range(5):
        for p in range(29):
            if not run[i, p]:
                continue
            a = p
            while a > 0 and run[i, a - 1]:
                a -= 1
            assert first[i, p] == a
            want = min(F[i, a : p + 1]) - F[i, p + 1]
            assert slack[i, p] == pytest.approx(want, abs=1e-9)


def test_slip_points_flow_is_the_matrix_exponentials_bit_for_bit():
    """``slip_points`` evaluates ``w`` once per distinct time; the flow is ``MatrixExponential.apply``'s, to the bit."""
    from symbolic_friction import Parameters
    from symbolic_friction._crosscheck.lemma3 import _distinct_times
    from symbolic_friction._simulation.affine import MatrixExponential

    params = Parameters.table_i("a")
    rng = np.random.default_rng(3)
    h = np.repeat(rng.uniform(0.0, 2.0, size=7), 5)  # interval lengths that repeat, as on a uniform grid
    taus = h[:, None] * np.array([0.125, 0.5, 0.875, 1.0])[None, :]
    y = rng.normal(size=taus.shape + (3,))
    got = _distinct_times(params).apply(taus, y)
    want = MatrixExponential.from_params(params).apply(taus, y)
    assert got.shape == want.shape and np.array_equal(got.view(np.int64), want.view(np.int64))
