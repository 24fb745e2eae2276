"""Lemma 2 on trajectories: wrong certificates and wrong trajectories are caught."""

from __future__ import annotations

import pytest

from symbolic_friction import Parameters
from symbolic_friction._crosscheck import Claims
from symbolic_friction._crosscheck._checker import BatchChecker
from tests.crosscheck.helpers import _cert
from tests.crosscheck.helpers import _result
from tests.crosscheck.helpers import _synthetic


def test_lemma2_decrease_is_an_equality_on_slips(paper_report):
    # dV_k/dt = -c v² exactly on a slip, so the slack of eq. (Vdecrease) is 0 up to rounding
    for check in paper_report.checks:
        r = _result(check, "lemma2.decrease")
        assert -1e-12 < r.worst_margin <= 1e-12


def test_c_ten_times_too_large_is_caught(wrong_report):
    case, wrong, checks, report = wrong_report
    r = _result(checks["c"], "lemma2.decrease")
    assert r.failures > 0
    cx = r.counterexample
    assert cx.values["integral_v2"] > 0 and cx.t > cx.t_start
    assert cx.values["lhs"] > cx.values["rhs"]  # V(t2) - V(t1) > -c ∫ v²
    assert cx.values["c"] == pytest.approx(float(wrong["c"].c), rel=1e-15)
    # V itself still never increases: only the rate c is wrong
    assert _result(checks["c"], "lemma2.nonincreasing").failures == 0


def test_c1_above_lambda_min_P_is_caught_exactly(wrong_report):
    case, wrong, checks, report = wrong_report
    r = _result(checks["c1"], "lemma2.lower_bound")
    assert r.failures > 0
    cx = r.counterexample
    assert cx.values["V"] < cx.values["c1"] * cx.values["dist2"]
    assert cx.exact is True  # the float state is an exact counterexample to c1|x|² ≤ V


def test_V_increasing_on_a_stick_is_caught():
    # σ grows during a "stick": V_0 = (k_v/k_i)σ² increases (a modelling slip the check must see)
    p = Parameters.table_i("a")
    cl = Claims.from_certificate(_cert("a"))
    b = _synthetic(p, [0.0, 1.0, 2.0], [[0.1, 0.0, 0.0], [0.2, 0.0, 0.0], [0.3, 0.0, 0.0]], [0, 0, 0])
    chk = BatchChecker(p, [cl])
    chk.add(b, attractivity=False)
    res = {r.id: r for r in chk.results()[0]}
    assert res["lemma2.nonincreasing"].failures == 2
    cx = res["lemma2.nonincreasing"].counterexample
    assert cx.values["V_t2"] > cx.values["V_t1"] and (cx.t_start, cx.t) == (0.0, 2.0)
    assert res["lemma2.decrease"].failures == 2


def test_V_jumping_up_at_an_event_is_caught():
    # a slip ending at x*_1 = (0, f_c, 0) (V = 0) whose event records σ = 0.5: V jumps up there
    p = Parameters.table_i("a")
    cl = Claims.from_certificate(_cert("a"))
    b = _synthetic(
        p, [0.0, 2.0], [[0.0, 1.0, 0.0], [0.5, 1.0, 0.0]], [1, 0],
        ev_t=[1.0], ev_x=[[0.5, 1.0, 0.0]], before=[1], after=[0],
    )
    chk = BatchChecker(p, [cl])
    chk.add(b, attractivity=False)
    res = {r.id: r for r in chk.results()[0]}
    assert res["lemma2.nonincreasing"].failures >= 1
    assert res["lemma2.nonincreasing"].counterexample.t == 1.0
