"""Proposition 1 on trajectories: a κ below the observed overshoot and a trajectory that does not approach 𝒜 are caught."""

from __future__ import annotations

import numpy as np

from symbolic_friction import Parameters
from symbolic_friction._crosscheck import Claims
from symbolic_friction._crosscheck._checker import BatchChecker
from symbolic_friction._crosscheck._run import sample_times
from symbolic_friction._model.coordinates import x_to_z
from symbolic_friction._simulation.batch import simulate_batch
from tests.crosscheck.helpers import _cert
from tests.crosscheck.helpers import _result
from tests.crosscheck.helpers import _synthetic


def test_kappa_below_observed_overshoot_is_caught(wrong_report):
    case, wrong, checks, report = wrong_report
    check = checks["kappa"]
    r = _result(check, "prop1.stability")
    assert r.failures > 0 and not check.passed
    cx = r.counterexample
    assert cx is not None and cx.property == "prop1.stability"
    kappa = float(wrong["kappa"].overshoot_bound)
    assert cx.values["observed_ratio"] > kappa
    assert cx.values["dist"] > kappa * cx.values["dist0"]
    assert cx.t >= 0 and len(cx.z0) == 3


def test_attractivity_failure_without_extension():
    p = Parameters.table_i("a")
    cl = Claims.from_certificate(_cert("a"))
    b = _synthetic(p, [0.0, 1.0], [[0.5, 0.0, 0.0], [0.5, 0.5, 0.0]], [0, 0])  # |x|_A stays 0.5
    chk = BatchChecker(p, [cl], theta=0.5)
    chk.add(b)
    chk.resolve_attractivity(doublings=0)
    r = {r.id: r for r in chk.results()[0]}["prop1.attractivity"]
    assert r.failures == 1
    assert r.counterexample.values["dist_T"] > 0.5 * r.counterexample.values["dist0"]


def test_attractivity_is_resolved_on_a_longer_horizon():
    # from a slow stick (σ small) nothing moves for ≈ 2 f_c/|σ| = 200 time units
    p = Parameters.table_i("a")
    cl = Claims.from_certificate(_cert("a"))
    t = sample_times(20.0, 41)
    b = simulate_batch(p, x_to_z(p, np.array([[0.01, 0.0, 0.0]])), float(t[-1]), t_eval=t)
    chk = BatchChecker(p, [cl])
    chk.add(b)
    assert len(chk._pending) == 1
    chk.resolve_attractivity()
    r = {r.id: r for r in chk.results()[0]}["prop1.attractivity"]
    assert r.failures == 0 and r.details["extended"] == 1 and r.details["latest_time_to_theta"] > 20.0


def test_a_kappa_broken_only_between_samples_is_caught_at_the_refined_peak():
    import dataclasses

    from symbolic_friction._crosscheck._overshoot import refine_peak

    p = Parameters.table_i("a")
    x0 = np.array([[7.838, 1.741, -5.96]])  # peak ≈ 1.318 |x(0)|_A at t ≈ 0.78, between the samples below
    coarse = np.linspace(0.0, 20.0, 11)
    b = simulate_batch(p, x_to_z(p, x0), 20.0, t_eval=coarse)
    cl = Claims.from_certificate(dataclasses.replace(_cert("a"), overshoot_bound="1.25"), label="kappa 1.25")
    chk = BatchChecker(p, [cl])
    chk.add(b, attractivity=False)
    assert _stability(chk).failures == 0  # the grid alone never sees the peak
    ratio, t_peak, x_peak, d0 = refine_peak(p, x0, t_eval=coarse)
    chk.add_peaks(x0, t_peak, x_peak, d0)
    r = _stability(chk)
    assert r.failures == 1 and r.counterexample.values["observed_ratio"] > 1.3
    assert 0.5 < r.counterexample.t < 1.0 and "refined" in r.counterexample.source


def _stability(chk):
    return next(r for r in chk.results()[0] if r.id == "prop1.stability")
