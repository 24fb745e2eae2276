"""The numerical search (cvxpy + Clarabel) and the exact rounding of its candidates.

References are independent of the package: eigenvalues of P from mpmath's
symmetric eigensolver at 50 digits, and the optimal ĉ₂/ĉ₁ from a
high-precision one-dimensional minimisation plus random feasible points.
"""

from __future__ import annotations

import math
import random
from fractions import Fraction as F

import mpmath
import pytest

from symbolic_friction import Parameters
from symbolic_friction.errors import InaccurateSolveError, InfeasibleError, ParameterError
from symbolic_friction._certify import search as search_module
from symbolic_friction._certify.rounding import (
    DIGITS,
    _repair,
    round_significant,
    sqrt_decimal_up,
    to_certificate,
)
from symbolic_friction._certify.search import (
    DEFAULT_MARGIN,
    Search,
    _interpret_status,
    check_margin,
    check_mode,
    eigen_bounds_P,
    find_candidate,
)
from symbolic_friction.errors import CertificateError
from tests.tolerance import assert_close

CASE_A = Parameters.table_i("a")
CASE_B = Parameters.table_i("b")


def _mp_eig_P(params: Parameters) -> tuple[mpmath.mpf, mpmath.mpf]:
    with mpmath.workdps(50):
        kv_ki = mpmath.mpf(params.k_v.numerator) / params.k_v.denominator / (
            mpmath.mpf(params.k_i.numerator) / params.k_i.denominator
        )
        kp = mpmath.mpf(params.k_p.numerator) / params.k_p.denominator
        ev = mpmath.eigsy(mpmath.matrix([[kv_ki, 0, -1], [0, 1, 0], [-1, 0, kp]]), eigvals_only=True)
        values = sorted(ev[i] for i in range(3))
        return values[0], values[-1]


@pytest.mark.parametrize(
    "params",
    [
        CASE_A,
        CASE_B,
        Parameters(k_v=3, k_p=3, k_i=1),  # triple root -1
        # Routh boundary: k_v k_p / k_i = 1 + 1e-9, where λ_min(P) ≈ 1e-9
        Parameters(k_v=(1 + F(1, 10**9)) * F(7, 3) / F(5, 2), k_p=F(5, 2), k_i=F(7, 3)),
        Parameters(k_v=(1 + F(1, 10**9)) * F(10**6) / F(10**-3), k_p=F(1, 1000), k_i=10**6),
        Parameters(k_v=F(3, 10**6) * (1 + F(1, 10**9)), k_p=F(1, 10**6), k_i=F(3, 10**12)),
    ],
)
def test_eigen_bounds_of_P_match_a_50_digit_reference(params):
    lam_min, lam_max = eigen_bounds_P(params)
    ref_min, ref_max = _mp_eig_P(params)
    assert abs(lam_min - float(ref_min)) <= 8e-16 * float(ref_min)
    assert abs(lam_max - float(ref_max)) <= 8e-16 * float(ref_max)


def test_candidate_is_optimal_and_carries_status():
    cand = find_candidate(CASE_A, mode="tightest")
    assert cand.status == "optimal" and cand.solver == "CLARABEL"
    assert cand.mode == "tightest" and cand.margin == DEFAULT_MARGIN["tightest"]
    k1, k2, k3, k4 = cand.k
    lam = max(k2, (k1 + k4 + math.hypot(k1 - k4, 2 * k3)) / 2)
    assert_close(cand.objective, lam / 2, rtol=1e-6, what="t vs λ_max(K)/2")
    # case (a): optimum at k1 = k2 = 2, k3 = 2(1+μ), k4 = 6(1+μ): λ_max/2 = 2 + √2 (μ → 0)
    assert_close(cand.objective, 2 + math.sqrt(2), rtol=1e-5, what="case (a) optimum")


def test_problem_is_compiled_once_per_mode_and_margin():
    find_candidate(CASE_A, mode="feasible")
    searcher = search_module._CACHE[("feasible", DEFAULT_MARGIN["feasible"])]
    find_candidate(CASE_B, mode="feasible")
    assert search_module._CACHE[("feasible", DEFAULT_MARGIN["feasible"])] is searcher
    assert searcher._problem.is_dpp()


def _reduced_ratio(params: Parameters, k1: mpmath.mpf, m: mpmath.mpf) -> mpmath.mpf:
    """λ_max(K)/min(k1,k2,k4) with k2 = 2 and k3, k4 at their margin lower bounds (mpmath)."""
    r = mpmath.mpf(params.k_i.numerator) / params.k_i.denominator / (
        mpmath.mpf(params.k_v.numerator) / params.k_v.denominator
    )
    kp = mpmath.mpf(params.k_p.numerator) / params.k_p.denominator
    k2 = mpmath.mpf(2)
    k3 = m * max(r * k1, k2)
    k4 = m * max(r * k3, kp * k2, k3**2 / k1, k2)
    lam = max(k2, (k1 + k4 + mpmath.sqrt((k1 - k4) ** 2 + 4 * k3**2)) / 2)
    return lam / min(k1, k2, k4)


def _reference_optimum(params: Parameters, margin: F) -> mpmath.mpf:
    with mpmath.workdps(30):
        m = 1 + mpmath.mpf(margin.numerator) / margin.denominator
        grid = [2 * mpmath.mpf(10) ** (j / 200) for j in range(0, 1601)]
        values = [_reduced_ratio(params, k1, m) for k1 in grid]
        j = min(range(len(values)), key=values.__getitem__)
        lo, hi = grid[max(j - 1, 0)], grid[min(j + 1, len(grid) - 1)]
        g = (mpmath.sqrt(5) - 1) / 2
        for _ in range(120):  # golden section on the bracketing cells
            a, b = hi - g * (hi - lo), lo + g * (hi - lo)
            if _reduced_ratio(params, a, m) < _reduced_ratio(params, b, m):
                hi = b
            else:
                lo = a
        return min(values[j], _reduced_ratio(params, (lo + hi) / 2, m))


TIGHT_CASES = [
    CASE_A,
    CASE_B,
    Parameters(k_v=3, k_p=3, k_i=1),
    Parameters(k_v=F(1, 10), k_p=100, k_i=9),  # k_i/k_v = 90: k3 driven by (k_i/k_v)k1
    Parameters(k_v=F(1, 2), k_p=F(1, 100), k_i=F(1, 1000)),
    Parameters(k_v=2, k_p=10**5, k_i=10**5),
]


@pytest.mark.parametrize("params", TIGHT_CASES)
def test_tightest_mode_reaches_the_reference_optimum(params):
    cert = to_certificate(find_candidate(params, mode="tightest"))
    ratio = cert.c2_hat / cert.c1_hat
    ref = _reference_optimum(params, DEFAULT_MARGIN["tightest"])
    # rounding k3, k4 and ĉ₂ up at 9 significant digits costs at most ~3e-8 (relative)
    with mpmath.workdps(30):  # nothing beats the optimum
        assert mpmath.mpf(ratio.numerator) / ratio.denominator >= ref * (1 - mpmath.mpf(10) ** -20)
    assert_close(float(ratio), float(ref), rtol=5e-8, what="ĉ₂/ĉ₁ vs the mpmath optimum")


@pytest.mark.parametrize("params", TIGHT_CASES)
def test_no_random_feasible_point_beats_the_tightest_certificate(params):
    cert = to_certificate(find_candidate(params, mode="tightest"))
    best = float(cert.c2_hat / cert.c1_hat)
    r = float(params.k_i / params.k_v)
    kp = float(params.k_p)
    m = 1 + 1e-6
    rng = random.Random(7)
    for _ in range(3000):
        k1 = 10 ** rng.uniform(-3, 4)
        k2 = 10 ** rng.uniform(-3, 4)
        k3 = m * max(r * k1, k2) * (1 + rng.choice([0, 10 ** rng.uniform(-6, 1)]))
        k4 = m * max(r * k3, kp * k2, k3 * k3 / k1) * (1 + rng.choice([0, 10 ** rng.uniform(-6, 1)]))
        lam = max(k2, (k1 + k4 + math.hypot(k1 - k4, 2 * k3)) / 2)
        # the certificate rounds k3, k4 and ĉ₂ up at 9 significant digits: ≤ 3e-8 relative
        assert lam / min(k1, k2, k4) >= best * (1 - 5e-8)


def test_tightest_beats_feasible_on_table_i():
    for params in (CASE_A, CASE_B):
        tight = to_certificate(find_candidate(params, mode="tightest"))
        loose = to_certificate(find_candidate(params, mode="feasible"))
        assert tight.kappa_squared < loose.kappa_squared


def test_feasible_mode_keeps_its_margin_on_every_strict_inequality():
    cert = to_certificate(find_candidate(CASE_B, mode="feasible"))
    m = 1 + DEFAULT_MARGIN["feasible"]
    r = CASE_B.k_i / CASE_B.k_v
    assert cert.k3 >= m * r * cert.k1 and cert.k3 >= m * cert.k2
    assert cert.k4 >= m * r * cert.k3 and cert.k4 >= m * CASE_B.k_p * cert.k2
    assert cert.k1 * cert.k4 >= m * cert.k3**2


def test_rounding_is_robust_to_last_bit_noise_in_the_solver_output():
    """Perturbing the solver's numbers by 1e-10 (relative) must not change a single byte."""
    from dataclasses import replace

    from symbolic_friction._certify import dumps

    for params in (CASE_A, CASE_B):
        for mode in ("tightest", "feasible"):
            cand = find_candidate(params, mode=mode)
            base = dumps(to_certificate(cand))
            for factor in (1 + 1e-10, 1 - 1e-10):
                noisy = replace(cand, k=tuple(k * factor for k in cand.k), objective=cand.objective * factor)
                assert dumps(to_certificate(noisy)) == base


# -- status handling: a non-optimal status never yields a candidate --------------------
@pytest.mark.parametrize("status", ["infeasible", "infeasible_inaccurate", "unbounded", "unbounded_inaccurate"])
def test_infeasible_statuses_raise_infeasible_error(status):
    with pytest.raises(InfeasibleError, match=rf"reports the tightest search as {status} for gains k_p=3, k_i=4"):
        _interpret_status(status, CASE_A, "tightest")


@pytest.mark.parametrize("status", ["optimal_inaccurate", "user_limit", None, "solver error: boom"])
def test_other_statuses_raise_inaccurate_solve_error(status):
    with pytest.raises(InaccurateSolveError, match=r"not 'optimal'.*k_v=32/5.*no certificate"):
        _interpret_status(status, CASE_A, "feasible")


def test_an_inaccurate_solve_is_never_returned(monkeypatch):
    searcher = Search(mode="tightest")
    monkeypatch.setattr(searcher, "_solve", lambda: "optimal_inaccurate")
    with pytest.raises(InaccurateSolveError, match="'optimal_inaccurate'"):
        searcher(CASE_A)


def test_a_solver_exception_becomes_inaccurate_solve_error(monkeypatch):
    import cvxpy as cp

    searcher = Search(mode="feasible")

    def boom(*args, **kwargs):
        raise cp.error.SolverError("numerical trouble")

    monkeypatch.setattr(searcher._problem, "solve", boom)
    with pytest.raises(InaccurateSolveError, match="solver error: numerical trouble"):
        searcher(CASE_B)


def test_search_rejects_non_parameters():
    with pytest.raises(ParameterError, match="params must be a Parameters instance; got dict"):
        Search(mode="feasible")({"k_p": 3})


def test_mode_and_margin_are_validated():
    assert check_mode("feasible") == "feasible"
    with pytest.raises(ParameterError, match=r"mode must be one of 'feasible', 'tightest'; got 'best'"):
        check_mode("best")
    assert check_margin("1/1000", "tightest") == F(1, 1000)
    assert check_margin(None, "feasible") == F(1, 100)
    with pytest.raises(ParameterError, match=r"margin must be in \(0, 1\].*got margin = 0"):
        check_margin(0, "tightest")
    with pytest.raises(ParameterError, match=r"margin must be in \(0, 1\].*got margin = 3/2"):
        check_margin("1.5", "tightest")


# -- exact rounding helpers ---------------------------------------------------------------
def test_round_significant_is_exact_and_directed():
    q = F(2, 3)
    assert round_significant(q, 3, direction="down") == F(333, 500)
    assert round_significant(q, 3, direction="up") == F(667, 1000)
    assert round_significant(q, 3, direction="nearest") == F(667, 1000)
    assert round_significant(F(12345), 2, direction="down") == 12000
    assert round_significant(F(1, 10**12) * 7, 1, direction="up") == F(7, 10**12)
    assert round_significant(1.0, 9, direction="up") == 1  # exact values are kept
    for digits in (1, 5, 9):
        for value in (F(1, 3), F(10**7, 7), F(31, 10**9)):
            down = round_significant(value, digits, direction="down")
            up = round_significant(value, digits, direction="up")
            assert down <= value <= up and up - down <= value / 10 ** (digits - 1)


def test_round_significant_rejects_bad_input():
    with pytest.raises(ValueError, match="needs q > 0; got 0"):
        round_significant(F(0), 3, direction="down")
    with pytest.raises(ValueError, match="direction must be 'down', 'up' or 'nearest'; got 'sideways'"):
        round_significant(F(1), 3, direction="sideways")


@pytest.mark.parametrize("q", [F(2), F(4), F(99999999, 10**6), F(10**14), F(12020297, 10**6), F(1, 1)])
def test_sqrt_decimal_up_is_the_smallest_upper_bound_with_six_digits(q):
    text = sqrt_decimal_up(q, 6)
    d = F(text)
    if "." in text:
        assert len(text.replace(".", "").lstrip("0")) == 6
        unit = F(1, 10 ** len(text.split(".")[1]))
    else:  # a large integer: six significant digits followed by zeros
        assert len(text.rstrip("0")) <= 6 and len(text) >= 6
        unit = F(10) ** (len(text) - 6)
    assert d * d >= q
    below = d - unit
    assert below * below < q


def test_sqrt_decimal_up_carries_into_a_new_digit():
    assert sqrt_decimal_up(F(999999999, 10**7), 6) == "10.0000"  # √99.9999999 rounds up to 10
    with pytest.raises(ValueError, match="needs q > 0; got -1"):
        sqrt_decimal_up(F(-1), 6)


def test_repair_moves_outward_and_gives_up_loudly():
    # target: smallest value ≥ 1/3 reachable by moving up from 0.3
    fixed = _repair(F(3, 10), lambda v: v >= F(1, 3), outward=+1, what="c2", params=CASE_A)
    assert fixed >= F(1, 3)
    with pytest.raises(CertificateError, match=r"could not repair c1 for Parameters\(k_p=3.*after 200 attempts"):
        _repair(F(1), lambda v: False, outward=-1, what="c1", params=CASE_A)


def test_derived_constants_have_at_most_nine_significant_digits():
    cert = to_certificate(find_candidate(Parameters(k_v="1.234567891", k_p="0.987654321", k_i="0.5"), mode="tightest"))
    for name in ("k3", "k4", "c1", "c2", "c2_hat"):
        q = getattr(cert, name)
        assert round_significant(q, DIGITS, direction="nearest") == q, name


def test_optimal_without_a_point_is_not_a_candidate(monkeypatch):
    searcher = Search(mode="feasible")  # never solved: its variables hold no value
    monkeypatch.setattr(searcher, "_solve", lambda: "optimal")
    with pytest.raises(InaccurateSolveError, match=r"reported optimal but returned no finite point for Parameters\(k_p=3"):
        searcher(CASE_A)


def test_a_formulation_that_is_not_dpp_is_refused(monkeypatch):
    import cvxpy as cp

    from symbolic_friction.errors import SolverError

    monkeypatch.setattr(cp.Problem, "is_dpp", lambda self, context="dcp": False)
    with pytest.raises(SolverError, match="not DPP-compliant"):
        Search(mode="tightest")


def test_gains_beyond_double_precision_are_refused_not_miscertified():
    # k_v k_p / k_i = 1 + 1e-400: λ_min(P) ≈ 1e-400 underflows in double precision
    params = Parameters(k_v=1 + F(1, 10**400), k_p=1, k_i=1)
    with pytest.raises(InaccurateSolveError, match=r"outside the double-precision range of the search .*λ_min\(P\) = 0"):
        find_candidate(params, mode="tightest")
    with pytest.raises(InaccurateSolveError, match=r"outside the double-precision range"):
        find_candidate(Parameters(k_v=F(10**400), k_p=1, k_i=1), mode="feasible")
