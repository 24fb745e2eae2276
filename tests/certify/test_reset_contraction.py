"""The reset-contraction certificate: found, written, read back and proved; every premise refused by name; the
refusals of the search; and the numbers against scipy, a return map iterated in numpy and the event kernel."""

from __future__ import annotations

import dataclasses
import functools
import json
import math
from fractions import Fraction as F
from pathlib import Path

import numpy as np
import pytest
from scipy.linalg import expm
from scipy.optimize import brentq

from symbolic_friction import Parameters
from symbolic_friction.errors import CertificateFormatError, ParameterError
from symbolic_friction._certify.reset_contraction import (
    RESET_CONTRACTION, ContractionCertificate, certify_contraction, dumps_contraction, load_contraction,
    verify_contraction,
)
from symbolic_friction._certify.reset_contraction_proof import NO_OVERSHOOT_PREMISES, OVERSHOOT_PREMISES, PREMISES
from symbolic_friction._certify.self_check import DIRECTORY
from symbolic_friction._certify.templates import check_listed_certificates, read_certificate_file, verify_template_file
from symbolic_friction._cli.main import main

ROOT = Path(__file__).resolve().parents[2]
COMMITTED = ROOT / "proofs" / "reset" / "case_a_contraction.json"
MANIFEST = [e for e in json.loads((DIRECTORY / "manifest.json").read_text(encoding="utf-8"))["false_certificates"]
            if e["template"] == "reset-contraction"]
FALSE = [e for e in MANIFEST if e["premise"] is not None]
CASE_A = Parameters.table_i("a")
NO_OVERSHOOT = Parameters(k_p=1, k_i=F(1, 5), k_v=F(3, 10))


@pytest.fixture(scope="module")
def case_a() -> ContractionCertificate:
    return certify_contraction(CASE_A, label="Table I, case (a)")


def _a(params: Parameters) -> np.ndarray:
    k_p, k_i, k_v, _ = params.as_floats()
    return np.array([[0.0, 0.0, -k_i], [1.0, 0.0, -k_p], [0.0, 1.0, -k_v]])


@functools.cache  # a pure function of the gains, which three tests ask for: computed once per gain set
def _tau_star(params: Parameters) -> float:
    """The first zero of E31 by scipy alone: a grid, then brentq."""
    A = _a(params)
    grid = np.linspace(1e-3, 40.0, 8000)
    values = expm(A * grid[:, None, None])[:, 2, 0]  # scipy's expm of each grid point at once (the same numbers)
    i = next(j for j in range(1, len(grid)) if values[j] < 0)
    return brentq(lambda t: expm(A * t)[2, 0], grid[i - 1], grid[i], xtol=1e-15)


# -- the file: written, read back, proved, checked -----------------------------------------------------------


def test_round_trip_write_read_verify_and_staleness(case_a, tmp_path):
    path = RESET_CONTRACTION.write(case_a, tmp_path / "reset" / "a.json")
    template, read = read_certificate_file(path)
    assert template is RESET_CONTRACTION and read == case_a and load_contraction(path) == case_a
    template, report = verify_template_file(path)
    assert report.proved and len(report.checks) == len(OVERSHOOT_PREMISES)
    assert [c.name for c in report.checks] == list(OVERSHOOT_PREMISES)
    (entry,) = check_listed_certificates(tmp_path, ["reset/a.json"], strict=True)
    assert entry.ok and not entry.drift, entry.describe()
    path.write_text(path.read_text(encoding="utf-8").replace("\n", "\n "), encoding="utf-8")  # same numbers
    (entry,) = check_listed_certificates(tmp_path, ["reset/a.json"])
    assert entry.proved and entry.stale and "canonical" in entry.reason


def test_the_committed_file_is_what_the_search_writes_and_is_proved(case_a, capsys):
    assert COMMITTED.read_text(encoding="utf-8") == dumps_contraction(case_a)
    assert main(["verify", str(COMMITTED)]) == 0
    out = capsys.readouterr().out
    assert out.startswith(f"PROVED {COMMITTED}: all 16 premises") and "|σ_k| ≤ 0.458633^k" in out


def test_case_a_numbers(case_a):
    c = case_a
    assert c.overshoot and c.rho == F(458633, 10**6) and c.radius == F(131077, 10**4) and c.dwell == 0
    assert c.tau_lo < F("4.1362166819") < c.tau_hi and c.tau_hi - c.tau_lo <= F(1, 10**8)
    assert c.cycle_time == F("4.13622") and (c.cycles, c.tol) == (9, F(1, 1000))
    assert c.settling_time == 9 * c.cycle_time
    assert c.rho ** 9 <= c.tol < c.rho ** 8


def test_a_dwell_longer_than_the_slip_shrinks_the_radius_and_sets_the_cycle(case_a):
    long = certify_contraction(CASE_A, dwell=6)
    assert long.cycle_time == 6 and long.radius < 1.1 < case_a.radius and verify_contraction(long).proved
    # a dwell shorter than the slip changes nothing but the number recorded
    short = certify_contraction(dataclasses.replace(CASE_A, reset_dwell=F(1, 100)))
    assert short.dwell == F(1, 100) and (short.radius, short.cycle_time) == (case_a.radius, case_a.cycle_time)


def test_gains_without_overshoot_get_the_stick_in_their_cycle():
    c = certify_contraction(NO_OVERSHOOT)
    report = verify_contraction(c)
    assert not c.overshoot and report.proved and [ch.name for ch in report.checks] == list(NO_OVERSHOOT_PREMISES)
    A = _a(NO_OVERSHOOT)
    E = expm(A * _tau_star(NO_OVERSHOOT))
    assert float(c.cycle_time) == pytest.approx(_tau_star(NO_OVERSHOOT) + abs(E[1, 0]) / E[0, 0], rel=1e-5)
    assert float(c.radius) == pytest.approx(2 / abs(E[1, 0]), rel=1e-5)


# -- every premise, broken, is refused by name -----------------------------------------------------------------


def test_every_premise_has_a_shipped_false_certificate():
    assert sorted({e["premise"] for e in FALSE}) == sorted(PREMISES)
    assert any(e["file"] == "reset-contraction_rho_below.json" for e in FALSE)


@pytest.mark.parametrize("entry", FALSE, ids=lambda e: e["file"])
def test_each_false_certificate_is_refused_naming_its_premise(entry):
    _, report = verify_template_file(DIRECTORY / entry["file"])
    failing = [c.name for c in report.checks if not c.holds]
    assert not report.proved and entry["premise"] in failing and failing == entry["fails"]
    assert f"{entry['premise']}: " in report.summary()


def test_rho_below_the_proven_value_is_refused(case_a):
    """ρ one unit of its last digit lower: |E₁₁(τ*)| = 0.4586327… is above it."""
    low = dataclasses.replace(case_a, rho=case_a.rho - F(1, 10**6))
    report = verify_contraction(low)
    assert [c.name for c in report.failures] == ["|E11| ≤ rho on [τ_lo, τ_hi]"]


@pytest.mark.parametrize("edit, premise", [
    ({"monotone_from": F(4), "tau_lo": F("4.1"), "tau_hi": F("4.13")}, "E31(τ_hi) < 0"),  # before τ*
    ({"monotone_from": F(1)}, "E31 > 0 on (0, τ_lo]"),
    ({"overshoot": False}, "E11 > 0 on [τ_lo, τ_hi]"),
    ({"radius": F(14)}, "radius·(|E21| + rho·max(0, dwell − τ_lo)) ≤ f_c on [τ_lo, τ_hi]"),
    ({"dwell": F(5)}, "radius·(|E21| + rho·max(0, dwell − τ_lo)) ≤ f_c on [τ_lo, τ_hi]"),
    ({"cycle_time": F(4)}, "cycle_time ≥ max(τ_hi, dwell)"),
    ({"cycles": 8}, "rho^cycles ≤ tol"),
    ({"settling_time": F(37)}, "settling_time ≥ cycles·cycle_time"),
    ({"rho": F(1)}, "rho < 1"),
    ({"radius": F(0)}, "radius > 0"),
    ({"dwell": F(-1)}, "dwell ≥ 0"),
    ({"k_v": F(1)}, "k_v·k_p > k_i"),
])
def test_an_edited_certificate_is_refused_naming_the_premise(case_a, edit, premise):
    report = verify_contraction(dataclasses.replace(case_a, **edit))
    assert not report.proved and premise in [c.name for c in report.failures]


def test_a_file_with_a_float_is_malformed_one_line_exit_2(case_a, tmp_path, capsys):
    data = json.loads(dumps_contraction(case_a))
    data["rho"] = 0.458633
    path = tmp_path / "float.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    with pytest.raises(CertificateFormatError, match="rho must be a string holding an exact rational"):
        read_certificate_file(path)
    assert main(["verify", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "rho must be" in err


# -- what the search refuses -----------------------------------------------------------------------------------


def test_table_i_b_has_no_contraction_certificate():
    """Real roots: E31 is the impulse response of 1/det(sI − A), positive for every τ > 0 — the slip never ends."""
    with pytest.raises(ParameterError, match=r"only real roots.*slip from a stick never ends"):
        certify_contraction(Parameters.table_i("b"))
    A = _a(Parameters.table_i("b"))
    assert min(expm(A * t)[2, 0] for t in np.linspace(0.01, 200, 2000)) > 0


def test_complex_roots_with_a_slower_real_one_need_not_end_the_slip():
    with pytest.raises(ParameterError, match="E31 has no sign change"):
        certify_contraction(Parameters(k_p=1, k_i=F(1, 10), k_v=F(1, 2)))


def test_static_friction_above_coulomb_is_refused():
    with pytest.raises(ParameterError, match=r"f_s = 6/5 > f_c = 1.*hunts"):
        certify_contraction(dataclasses.replace(CASE_A, f_s=F(6, 5)))


@pytest.mark.parametrize("options, match", [({"tol": 1}, "tol in"), ({"tol": 0}, "tol in"), ({"dwell": -1}, "dwell must")])
def test_options_out_of_range_are_refused(options, match):
    with pytest.raises(ParameterError, match=match):
        certify_contraction(CASE_A, **options)


# -- the numbers against independent computations ---------------------------------------------------------------


def test_rho_and_tau_star_match_scipy_expm(case_a):
    tau = _tau_star(CASE_A)
    E = expm(_a(CASE_A) * tau)
    assert case_a.tau_lo < tau < case_a.tau_hi
    proof = verify_contraction(case_a).proof
    lo, hi = proof.e11
    assert lo <= E[0, 0] <= hi and hi - lo < 1e-7
    assert abs((lo + hi) / 2 - E[0, 0]) < 1e-9
    assert 0 <= float(case_a.rho) - abs(E[0, 0]) <= 1e-6  # rounded up at 6 digits
    assert abs(E[2, 0]) < 1e-12 and E[1, 0] < 0  # E21(τ*) = E31'(τ*) < 0: the mass sticks


def _slip(A: np.ndarray, sigma: float, d: int) -> tuple[float, np.ndarray]:
    """From the stick exit (σ, d f_c, 0) with f_c = 1: the slip's length and its end, by expm and brentq."""
    w0 = np.array([sigma, 0.0, 0.0])
    grid = np.linspace(1e-3, 40.0, 4000)
    v = (expm(A * grid[:, None, None]) @ w0)[:, 2] * d  # scipy's expm of each grid point at once (the same numbers)
    i = next(j for j in range(1, len(grid)) if v[j] < 0)
    tau = brentq(lambda t: (expm(A * t) @ w0)[2], grid[i - 1], grid[i], xtol=1e-14)
    return tau, expm(A * tau) @ w0 + np.array([0.0, d, 0.0])


def test_the_return_map_is_what_iterating_the_dynamics_gives(case_a):
    """Stick exits iterated in numpy (slip by expm, stick by φ' = σ; reset PID resets where σφ ≤ 0): σ_{k+1} = E11 σ_k,
    each cycle τ* with resets, while plain PID's sticks grow as σ shrinks."""
    A = _a(CASE_A)
    e11 = expm(A * _tau_star(CASE_A))[0, 0]
    sigma, t_reset, t_plain, sticks = float(case_a.radius) * 0.99, 0.0, 0.0, []
    for k in range(8):
        d = 1 if sigma > 0 else -1
        tau, (s1, phi1, v1) = _slip(A, sigma, d)
        assert abs(v1) < 1e-9 and abs(phi1) <= 1 and s1 == pytest.approx(e11 * sigma, rel=1e-9, abs=1e-15)
        assert s1 * phi1 <= 0  # within the radius the reset fires at once
        stick = (math.copysign(1, s1) - phi1) / s1  # plain PID: φ moves at the rate σ to sign(σ) f_c
        assert stick > 0
        sticks.append(stick)
        t_reset, t_plain = t_reset + tau, t_plain + tau + stick
        assert t_reset <= (k + 1) * float(case_a.cycle_time)
        sigma = s1
    assert abs(sigma) <= float(case_a.rho) ** 8 * float(case_a.radius)
    # plain PID: each stick ~ 2f_c/|σ|, growing by 1/ρ a cycle — asymptotic, not exponential, settling
    assert all(b > a for a, b in zip(sticks, sticks[1:]))
    assert sticks[-1] / sticks[-2] == pytest.approx(1 / abs(e11), rel=0.05) and sticks[-1] > 50
    assert t_plain > 4 * t_reset


def test_the_event_kernel_settles_within_the_certified_time(case_a):
    """The package's kernel (an independent implementation of the law) from a stick exit at σ₀ = 13: |σ| ≤ tol·σ₀
    after settling_time; its resets' σ contract by E11(τ*) and come τ* apart."""
    from symbolic_friction._simulation import simulate

    params = dataclasses.replace(CASE_A, reset_dwell=F(1, 100))
    sigma0 = 13.0
    s0 = -sigma0 / 4.0
    z0 = (-(1.0 + 3.0 * s0) / 4.0, s0, 0.0)  # σ = −k_i s, φ = −k_i e_i − k_p s = f_c
    t = np.linspace(float(case_a.settling_time), float(case_a.settling_time) + 20.0, 201)
    sol = simulate(params, z0, float(t[-1]), t_eval=t)
    assert np.max(np.abs(4.0 * sol.z[:, 1])) <= float(case_a.tol) * sigma0
    resets = [(time, x[0]) for (time, a, b), x in zip(sol.events, sol.event_x) if (a, b) == (0, 0)]
    assert len(resets) >= 8
    for (t1, s1), (t2, s2) in zip(resets, resets[1:]):
        assert s2 / s1 == pytest.approx(-0.4586327, abs=1e-6) and t2 - t1 <= float(case_a.cycle_time)


def test_the_cross_check_leaves_the_file_out_with_its_reason(tmp_path, monkeypatch):
    from symbolic_friction._crosscheck._files import SKIPPED, default_certificate_selection

    (tmp_path / "proofs").mkdir()
    (tmp_path / "proofs" / "reset.json").write_bytes(COMMITTED.read_bytes())
    (tmp_path / "proofs" / "a.json").write_bytes((ROOT / "proofs" / "case_a_tightest.json").read_bytes())
    monkeypatch.chdir(tmp_path)
    assert default_certificate_selection() == (["proofs/a.json"], [("proofs/reset.json", SKIPPED["reset-contraction/v1"])])
