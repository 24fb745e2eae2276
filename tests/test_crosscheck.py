"""The cross-check (issue 5): it passes the paper's certificates, and it
catches wrong ones with a counterexample.

Independent references live here, not in the package: the closed form of
``∫ v²`` is compared with an mpmath quadrature of the exact (mpmath ``expm``)
solution at 40 digits.
"""

from __future__ import annotations

import dataclasses
import json
import math
from fractions import Fraction
from pathlib import Path

import mpmath
import numpy as np
import pytest

from symbolic_friction import CertificateFormatError, ParameterError, Parameters, SimulationError
from symbolic_friction._certify import load
from symbolic_friction._crosscheck import (
    PROPERTIES,
    Claims,
    crosscheck,
    decay_fit,
    format_report,
    iss_gain,
    write_counterexamples,
)
from symbolic_friction._crosscheck._adversarial import hat_V_rate
from symbolic_friction._simulation import Trajectories
from symbolic_friction._crosscheck._initial import grid_states, special_states, sphere_states
from symbolic_friction._crosscheck._properties import BatchChecker, observability_gramian
from symbolic_friction._crosscheck._run import default_horizon, sample_times, search_mode
from symbolic_friction._coordinates import x_to_z
from symbolic_friction._simulation.batch import simulate_batch
from symbolic_friction._lyapunov import lyapunov_matrix
from tests.tolerance import assert_close

PROOFS = Path(__file__).resolve().parents[1] / "proofs"
N_SMALL = 300


def _cert(case: str, mode: str = "tightest"):
    return load(PROOFS / f"case_{case}_{mode}.json")


def _result(check, pid: str):
    return next(r for r in check.results if r.id == pid)


# ----------------------------------------------------------------------------------- fixtures
@pytest.fixture(scope="module")
def paper_report():
    """The four committed certificates on a small sample (both modes share trajectories)."""
    files = [PROOFS / f"case_{c}_{m}.json" for c in "ab" for m in ("feasible", "tightest")]
    return crosscheck(files, trajectories=N_SMALL, seed=1, progress=False)


def _lambda_min_P(cert) -> float:
    p = Parameters(k_p=cert.k_p, k_i=cert.k_i, k_v=cert.k_v, f_c=cert.f_c)
    return float(np.linalg.eigvalsh(lyapunov_matrix(p))[0])


def _wrong_certificates(cert, observed_overshoot: float) -> dict:
    """Altered copies the exact verifier would reject (built in memory, never verified)."""
    kappa = 0.5 * (1.0 + observed_overshoot)  # strictly between 1 and the observed overshoot
    c1 = Fraction(_lambda_min_P(cert) * 1.01).limit_denominator(10**9)
    return {
        "kappa": dataclasses.replace(cert, overshoot_bound=f"{kappa:.6f}"),
        "c": dataclasses.replace(cert, c=10 * 2 * (cert.k_v * cert.k_p - cert.k_i)),
        "c1": dataclasses.replace(cert, c1=c1),
        # k4 < k_p k2 violates a derived condition of Lemma 3 (eq. hatVdot)
        "k4": dataclasses.replace(cert, k4=cert.k_p * cert.k2 / 2),
    }


@pytest.fixture(scope="module", params=["a", "b"])
def wrong_report(request, paper_report):
    case = request.param
    cert = _cert(case)
    observed = next(c for c in paper_report.checks if c.label == f"case_{case}_tightest").max_overshoot
    wrong = _wrong_certificates(cert, max(observed.values()))
    claims = [Claims.from_certificate(c, label=name) for name, c in wrong.items()]
    report = crosscheck(claims, trajectories=N_SMALL, seed=2, progress=False, require_proved=False)
    return case, wrong, {c.label: c for c in report.checks}, report


# ------------------------------------------------------------------------ the paper's certificates
def test_paper_certificates_pass(paper_report):
    assert paper_report.passed
    assert len(paper_report.checks) == 4
    for check in paper_report.checks:
        assert check.trajectories == N_SMALL
        for r in check.results:
            assert r.failures == 0, (check.label, r.id, r.counterexample)
            assert r.counterexample is None
            if r.id == "remark.stick_sigma" and check.label.startswith("case_b"):
                continue  # case (b): solutions stick at most once (paper, Section III)
            assert r.samples > 0, (check.label, r.id)
            assert r.worst_margin >= -paper_report.rtol
        # the certified bound is not attained: observed overshoot / κ < 1, per search mode
        tight = check.tightness
        assert set(tight) >= {"random spheres", "grid", "special", "adversarial", "all"}
        assert 0.2 < tight["all"] < 1.0
        assert max(check.max_overshoot.values()) >= 1.0


def test_lemma2_decrease_is_an_equality_on_slips(paper_report):
    # dV_k/dt = -c v² exactly on a slip, so the slack of eq. (Vdecrease) is 0 up to rounding
    for check in paper_report.checks:
        r = _result(check, "lemma2.decrease")
        assert -1e-12 < r.worst_margin <= 1e-12


def test_properties_are_reported_in_paper_order(paper_report):
    ids = [r.id for r in paper_report.checks[0].results]
    assert ids == [p.id for p in PROPERTIES]


def test_report_text_names_every_property(paper_report):
    text = format_report(paper_report)
    for p in PROPERTIES:
        assert p.id in text
    assert "PASSED" in text and "tightness ratio" in text and "rtol = 1e-08" in text


# ------------------------------------------------------------------------ wrong certificates
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


def test_only_the_altered_property_fails(wrong_report):
    case, wrong, checks, report = wrong_report
    expected = {
        "kappa": {"prop1.stability"},
        "c": {"lemma2.decrease"},
        "c1": {"lemma2.lower_bound"},
        "k4": {"lemma3.hatV_nonincreasing", "lemma3.hatV_lower"},
    }
    for name, check in checks.items():
        failed = {r.id for r in check.results if r.failures}
        assert failed and failed <= expected[name], (name, failed)


def test_counterexample_files(wrong_report, tmp_path):
    case, wrong, checks, report = wrong_report
    files = write_counterexamples(report, tmp_path)
    assert len(files) == 4
    for path in files:
        data = json.loads(path.read_text(encoding="utf-8"))
        assert data["counterexamples"]
        for cx in data["counterexamples"]:
            assert {"property", "z0", "x0", "t", "values", "relative_slack"} <= set(cx)
            assert cx["relative_slack"] < -report.rtol
    assert not list(tmp_path.glob(".*.tmp"))  # atomic writes leave no temporary file


# ------------------------------------------------------------------- the closed-form integral
@pytest.mark.parametrize(
    "gains, x0, tau",
    [
        ((3, 4, "6.4", 1), (0.3, 2.0, 1.5), 0.7),
        (("0.66", "0.08", "1.5", 1), (-0.5, 3.0, 2.0), 4.0),
        ((3, 1, 3, 1), (1.0, -2.0, 0.5), 2.5),  # triple root -1
    ],
)
def test_gramian_integral_matches_mpmath_quadrature(gains, x0, tau):
    k_p, k_i, k_v, f_c = gains
    p = Parameters(k_p=k_p, k_i=k_i, k_v=k_v, f_c=f_c)
    W = observability_gramian(p)
    mpmath.mp.dps = 40
    kp, ki, kv = (mpmath.mpf(Fraction(q).numerator) / Fraction(q).denominator for q in (p.k_p, p.k_i, p.k_v))
    A = mpmath.matrix([[0, 0, -ki], [1, 0, -kp], [0, 1, -kv]])
    y0 = mpmath.matrix([x0[0], x0[1] - float(p.f_c), x0[2]])  # offset from x*_1 = (0, f_c, 0)

    def v(t):
        return (mpmath.expm(A * t) * y0)[2]

    ref = mpmath.quad(lambda t: v(t) ** 2, [0, tau / 2, tau])
    y_end = mpmath.expm(A * tau) * y0
    ya = np.array([float(q) for q in y0])
    yb = np.array([float(q) for q in y_end])
    got = ya @ W @ ya - yb @ W @ yb
    assert_close(got, float(ref), rtol=1e-12, what="∫ v² by the Gramian")


def test_gramian_is_P_over_c():
    # not used by the check (W is solved from A alone), but it is the paper's identity behind eq. (dVdt)
    for case in "ab":
        p = Parameters.table_i(case)
        assert_close(observability_gramian(p) * float(p.c), lyapunov_matrix(p), rtol=1e-13, what="c W = P")


# ----------------------------------------------------------------------------- synthetic batches
def _synthetic(params, t, x, mode, ev_t=None, ev_x=None, before=None, after=None):
    x = np.asarray(x, dtype=float)[None]
    mode = np.asarray(mode)[None]
    if ev_t is None:
        ev_t, ev_x, before, after = np.zeros((1, 0)), np.zeros((1, 0, 3)), np.zeros((1, 0)), np.zeros((1, 0))
    else:
        ev_t, ev_x = np.asarray(ev_t, float)[None], np.asarray(ev_x, float)[None]
        before, after = np.asarray(before)[None], np.asarray(after)[None]
    return _trajectories(params, t, x, mode, ev_t, ev_x, before, after)


def _trajectories(params, t, x, mode, ev_t, ev_x, before, after):
    N, E = ev_t.shape
    return Trajectories(
        params=params, method="synthetic", t=np.asarray(t, float), z=x_to_z(params, x), x=x, mode=mode,
        event_t=ev_t, event_x=ev_x, event_before=before, event_after=after, event_residual=np.zeros((N, E)),
        n_events=np.isfinite(ev_t).sum(axis=1), status=np.full(N, "t_end reached", dtype=object),
        t_stop=np.full(N, float(np.asarray(t)[-1])), z0=x_to_z(params, x[:, 0]), x0=x[:, 0],
    )


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


def test_sigma_growing_between_stick_phases_is_caught():
    p = Parameters.table_i("a")
    cl = Claims.from_certificate(_cert("a"))
    # stick from t=0 with σ=-0.1, slip, stick again at t=2 with σ=0.3 (|σ| grew)
    b = _synthetic(
        p, [0.0, 0.5, 1.5, 2.5],
        [[-0.1, 0.0, 0.0], [-0.1, -0.05, 0.0], [-0.05, -1.2, -0.3], [0.3, -0.5, 0.0]],
        [0, 0, -1, 0],
        ev_t=[1.0, 2.0], ev_x=[[-0.1, -1.0, 0.0], [0.3, -0.5, 0.0]], before=[0, -1], after=[-1, 0],
    )
    chk = BatchChecker(p, [cl])
    chk.add(b, attractivity=False)
    r = {r.id: r for r in chk.results()[0]}["remark.stick_sigma"]
    assert r.failures == 1
    assert r.counterexample.values["sigma_next_stick"] == 0.3
    assert r.counterexample.values["sigma_previous_stick"] == -0.1


def test_mode_inconsistent_with_state_is_caught():
    p = Parameters.table_i("a")
    cl = Claims.from_certificate(_cert("a"))
    b = _synthetic(p, [0.0, 1.0], [[0.0, 3.0, 1.0], [0.0, 3.0, -1.0]], [1, 1])  # mode +1 with v < 0
    chk = BatchChecker(p, [cl])
    chk.add(b, attractivity=False)
    r = {r.id: r for r in chk.results()[0]}["model.modes"]
    assert r.failures == 1 and r.counterexample.values["v"] == -1.0


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


def test_run_slack_matches_brute_force():
    rng = np.random.default_rng(0)
    F = rng.normal(size=(5, 30)) * 10
    run = rng.random((5, 29)) < 0.7
    slack, first = BatchChecker._run_slack(F, run)
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


# -------------------------------------------------------------------------------- V̂ rate, inputs
def test_hat_V_rate_matches_a_finite_difference_along_the_flow():
    p = Parameters.table_i("a")
    cl = Claims.from_certificate(_cert("a"))
    x0 = np.array([0.3, -2.0, 0.7])  # v > 0, φ < f_c: in R̂, σ ≠ 0, |φ| ≠ f_c
    t = np.array([0.0, 1e-6])
    b = simulate_batch(p, x_to_z(p, x0[None]), float(t[-1]), t_eval=t)
    from symbolic_friction._lyapunov import V_hat

    vh = V_hat(p, b.x[0], cl.k)
    fd = (vh[1] - vh[0]) / 1e-6 / vh[0]
    assert hat_V_rate(p, cl, x0[None])[0] == pytest.approx(fd, rel=1e-4)
    assert np.isnan(hat_V_rate(p, cl, np.array([[0.3, 2.0, 0.7]])))[0]  # in R


def test_initial_states():
    p = Parameters.table_i("b")
    rng = np.random.default_rng(0)
    s = sphere_states(p, 60, rng, radii=(0.5, 2.0))
    r = np.linalg.norm(s.x, axis=1)
    assert set(np.round(r, 12)) == {0.5, 2.0} and len(s) == 60
    g = grid_states(p, 125)
    assert len(g) == 125 and np.any(np.all(g.x == 0, axis=1))
    sp = special_states(p)
    assert np.any(np.all(np.isclose(sp.x, [0.0, 1.001, 0.0]), axis=1))
    assert search_mode("sphere r=1f_c") == "random spheres" and search_mode("adversarial x") == "adversarial"


def test_default_horizon_and_samples():
    assert default_horizon(Parameters.table_i("b")) == 100.0  # slowest root -0.2
    t = sample_times(10.0, 11)
    assert t[0] == 0 and t[-1] == 10.0 and np.all(np.diff(t) > 0) and t[1] < t[-1] - t[-2]


# ------------------------------------------------------------------------------- decay and ISS
def test_decay_is_a_power_law_in_case_a_and_exponential_in_case_b():
    fa = decay_fit(Parameters.table_i("a"), trajectories=6, horizon=1000.0)
    fb = decay_fit(Parameters.table_i("b"), trajectories=6, horizon=1000.0)
    assert fa.verdict == "power law" and 0.5 < fa.power_exponent < 2.0 and fa.stick_phases >= 3
    assert fb.verdict == "exponential"
    assert fb.exponential_rate == pytest.approx(0.2, rel=0.05)  # the slowest root of case (b)
    assert "power law" in fa.describe()


def test_iss_gain_grows_with_rho_and_vanishes_at_zero():
    p = Parameters.table_i("a")
    est = iss_gain(p, ("0", "0.01", "0.3"), laws=("worst-case",), horizon=30.0, h=1e-2)
    g = est.gamma_from_attractor["worst-case"]
    assert g[0] == 0.0  # from 𝒜 with the paper's law nothing moves
    assert 0 < g[1] < g[2]
    assert est.rows()[0][0] == "worst-case" and len(est.rows()) == 3


def test_iss_stribeck_hunts_for_large_rho():
    p = Parameters.table_i("a")
    est = iss_gain(p, ("1",), laws=("stribeck",), horizon=60.0, h=1e-2)
    assert est.hunting["stribeck"][0] > 0  # a persistent stick–slip cycle (f_s = 2 f_c)
    assert 0 < est.gamma["stribeck"][0] < 10


# ------------------------------------------------------------------------------------- errors
def test_claims_errors():
    cert = _cert("a")

    class Missing:
        pass

    with pytest.raises(CertificateFormatError, match="needs the attribute 'k_p'"):
        Claims.from_certificate(Missing())

    class NoBound:
        def __init__(self):
            for k, v in dataclasses.asdict(cert).items():
                setattr(self, k, v)
            self.overshoot_bound = None

    with pytest.raises(CertificateFormatError, match="needs 'overshoot_bound'"):
        Claims.from_certificate(NoBound())
    bad = NoBound()
    bad.overshoot_bound = "3.5"
    bad.c1 = "abc"
    with pytest.raises(CertificateFormatError, match="c1 must be a number; got 'abc'"):
        Claims.from_certificate(bad)
    bad.c1 = -1
    with pytest.raises(CertificateFormatError, match="c1 must be finite and > 0; got -1"):
        Claims.from_certificate(bad)


def test_checker_rejects_other_gains():
    cl = Claims.from_certificate(_cert("a"))
    with pytest.raises(ParameterError, match="a checker for .* takes only those gains"):
        BatchChecker(Parameters.table_i("b"), [cl])
    chk = BatchChecker(Parameters.table_i("a"), [cl])
    pb = Parameters.table_i("b")
    b = _synthetic(pb, [0.0, 1.0], [[0.1, 0.0, 0.0], [0.1, 0.1, 0.0]], [0, 0])
    with pytest.raises(ParameterError, match="the batch was simulated with"):
        chk.add(b)


def test_malformed_batch():
    p = Parameters.table_i("a")
    z = np.zeros((1, 2, 3))
    ok = dict(
        params=p, method="synthetic", t=np.array([0.0, 1.0]), z=z, x=z, mode=np.zeros((1, 2)),
        event_t=np.zeros((1, 0)), event_x=np.zeros((1, 0, 3)), event_before=np.zeros((1, 0)),
        event_after=np.zeros((1, 0)), event_residual=np.zeros((1, 0)), n_events=np.zeros(1, int),
        status=np.array(["t_end reached"], dtype=object), t_stop=np.ones(1), z0=np.zeros((1, 3)), x0=np.zeros((1, 3)),
    )
    Trajectories(**ok)
    with pytest.raises(SimulationError, match="malformed trajectories: t has shape"):
        Trajectories(**{**ok, "t": np.zeros(3)})
    with pytest.raises(SimulationError, match="nondecreasing"):
        Trajectories(**{**ok, "t": np.array([1.0, 0.0])})
    chk = BatchChecker(p, [Claims.from_certificate(_cert("a"))])
    with pytest.raises(SimulationError, match="strictly increasing"):
        chk.add(Trajectories(**{**ok, "t": np.array([0.0, 0.0])}))


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"trajectories": 0}, "trajectories must be an integer ≥ 1; got 0"),
        ({"samples": 2}, "samples must be an integer ≥ 3; got 2"),
        ({"horizon": -1.0}, "horizon must be a finite number > 0; got -1.0"),
        ({"rtol": 0.0}, r"rtol must be in \(0, 1\); got 0.0"),
        ({"theta": 1.5}, r"theta must be in \(0, 1\]; got 1.5"),
    ],
)
def test_crosscheck_argument_errors(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        crosscheck([PROOFS / "case_a_feasible.json"], **kwargs)


def test_crosscheck_needs_a_certificate():
    with pytest.raises(ParameterError, match="no certificate to cross-check"):
        crosscheck([])


def test_iss_errors():
    p = Parameters.table_i("a")
    with pytest.raises(ParameterError, match="unknown friction law"):
        iss_gain(p, ("0.1",), laws=("coulomb",))
    with pytest.raises(ParameterError, match="rho must be ≥ 0; got rho = -1/10"):
        iss_gain(p, ("-0.1",))


def test_report_is_json_safe(paper_report):
    # counterexample values are plain numbers (no NaN/inf leak into files)
    for check in paper_report.checks:
        for r in check.results:
            assert math.isfinite(r.worst_margin) or r.samples == 0


def test_k4_violating_only_definiteness_cannot_make_V_hat_increase():
    # k1 k4 > k3² fails (2·7 < 4²) but the four derivative conditions of eq. (hatVdot) hold
    # (k3 = 4 > max(k_i/k_v k1, k2) = 2, k4 = 7 > max(k_i/k_v k3, k_p k2) = 6); those four
    # are necessary and sufficient for V̂° ≤ 0 on R̂ (symbolic_friction._kconditions), so no
    # trajectory can show V̂ increasing in R̂, and the cross-check must not report one.
    cert = dataclasses.replace(_cert("a"), k1=2, k2=2, k3=4, k4=7, c1_hat=1, c2_hat=Fraction(427, 100))
    assert not cert.k1 * cert.k4 > cert.k3**2
    cl = Claims.from_certificate(cert, label="definiteness only")
    report = crosscheck([cl], trajectories=200, seed=3, progress=False, require_proved=False)
    res = {r.id: r for r in report.checks[0].results}
    assert res["lemma3.hatV_nonincreasing"].failures == 0 and res["lemma3.hatV_nonincreasing"].samples > 0
    assert res["lemma3.hatV_lower"].failures == 0  # ½wᵀKw ≥ ½min(k1,k2,k4)|w|² on w ≥ 0 anyway
    from symbolic_friction._crosscheck._adversarial import rate_maximisers

    X = rate_maximisers(cl.params, cl, seed=0, count=4)
    assert np.nanmax(hat_V_rate(cl.params, cl, X)) <= 1e-12


def test_V_read_through_the_modes_is_the_papers_V():
    # the checker evaluates V through the mode pieces V_k (Claim 1, item 2); at every sample whose
    # velocity sign is unambiguous this must be the closed-form V of eq. (lyapLike)
    from symbolic_friction._crosscheck._properties import _build_chain
    from symbolic_friction._lyapunov import V

    p = Parameters.table_i("a")
    cl = Claims.from_certificate(_cert("a"))
    rng = np.random.default_rng(5)
    X0 = rng.normal(size=(40, 3)) * 2
    b = simulate_batch(p, x_to_z(p, X0), 30.0, t_eval=sample_times(30.0, 121))
    chk = BatchChecker(p, [cl])
    ch = _build_chain(b)
    got = chk._V_piece(ch.x, ch.piece)
    want = V(p, ch.x)
    sure = ch.valid & ((ch.kind == 1) | ((ch.kind == 3) & ((ch.piece == 0) | (np.abs(ch.x[..., 2]) > 1e-9))))
    assert np.count_nonzero(sure) > 1000
    assert_close(got[sure], want[sure], rtol=1e-13, what="V through modes vs closed form")


def test_unproved_certificate_is_refused_by_default(tmp_path):
    from dataclasses import replace

    from symbolic_friction import UnprovedCertificateError
    from symbolic_friction._certify import load

    cert = load(PROOFS / "case_a_tightest.json")
    forged = replace(cert, c2=cert.c2 / 2)  # c₂ below λ_max(P)
    with pytest.raises(UnprovedCertificateError, match="c2·I − P ⪰ 0"):
        crosscheck([forged], trajectories=10, progress=False)
    with pytest.raises(UnprovedCertificateError, match="cannot be verified exactly"):
        crosscheck([Claims.from_certificate(cert)], trajectories=10, progress=False)


def test_incomplete_trajectories_are_counted_and_never_hold():
    report = crosscheck([PROOFS / "case_a_tightest.json"], trajectories=40, adversarial=False, samples=51,
                        progress=False, max_events=2)
    check = report.checks[0]
    assert 0 < check.incomplete <= 40 + len(report.checks)  # resolution runs may add some
    assert check.verdict == "incomplete" and not check.passed and not report.passed
    assert report.summary().startswith("crosscheck: INCOMPLETE")
    # the unsimulated tail was not used: overshoots of incomplete runs are not measurements
    assert np.isnan(check.overshoots).sum() >= 1


def test_incomplete_batch_keeps_nan_after_the_stop():

    p = Parameters.table_i("a")
    batch = simulate_batch(p, np.array([[0.0, 3.0, 0.0]]), 30.0, t_eval=np.linspace(0, 30, 31), max_events=2)
    assert not batch.complete[0]
    assert np.isnan(batch.x[0, -1]).all()  # never held at the last state
