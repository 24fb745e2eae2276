"""Closed-form flows and the robust e^{At} (eq. subcasesAffine), against mpmath."""

from __future__ import annotations

from fractions import Fraction as F

import mpmath
import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction.errors import SimulationError
from symbolic_friction._simulation.affine import (
    MatrixExponential,
    ScanTable,
    SlipBounds,
    slip_equilibrium,
    slip_flow,
    stick_flow,
)

from ..tolerance import assert_close, relative_error

DPS = 40

# name -> (k_p, k_i, k_v); each makes a different root configuration of s³ + k_v s² + k_p s + k_i
GAINS = {
    "table_a": (3, 4, "6.4"),  # one real, complex pair
    "table_b": ("0.66", "0.08", "1.5"),  # three distinct real roots
    "triple": (3, 1, 3),  # (s+1)³
    "double": (5, 2, 4),  # (s+1)²(s+2)
    "near_triple_1e-3": (3, "1.001", 3),
    "near_triple_1e-6": (3, "1.000001", 3),
    "near_triple_1e-9": (3, "1.000000001", 3),
    "near_triple_1e-12": (3, "1.000000000001", 3),
    "near_triple_below": (3, "0.999999", 3),
    "near_double_real": ("5.000001", 2, 4),  # the pair splits into two reals
    "near_double_complex": ("4.999999", 2, 4),  # the pair becomes complex
    "complex_small_omega": ("0.25000001", "0.0625", 1),
    "routh_margin_1.01": (1, 1, "1.01"),
    "stiff_complex": ("5.3525", "12.8775", "51.1"),  # roots -0.05 ± 0.5i, -51
    "stiff_real": ("11.1", 1, "11.1"),  # roots -0.1, -1, -10
    "slow": ("1e-4", "1e-9", "1e-2"),
}
TIMES = [0.0, 1e-12, 1e-6, 1e-3, 0.05, 0.3, 1.0, 2.5, 7.0, 20.0, 60.0, 300.0]


def mp_q(value) -> mpmath.mpf:
    q = F(value)
    return mpmath.mpf(q.numerator) / q.denominator


def mp_expm(params: Parameters, t: float) -> np.ndarray:
    with mpmath.workdps(DPS):
        k_p, k_i, k_v = mp_q(params.k_p), mp_q(params.k_i), mp_q(params.k_v)
        A = mpmath.matrix([[0, 0, -k_i], [1, 0, -k_p], [0, 1, -k_v]])
        E = mpmath.expm(A * mpmath.mpf(t))
        return np.array(E.tolist(), dtype=float)


def params_of(name: str) -> Parameters:
    k_p, k_i, k_v = GAINS[name]
    return Parameters(k_p=k_p, k_i=k_i, k_v=k_v)


@pytest.mark.parametrize("name", list(GAINS))
def test_expm_matches_mpmath_for_every_root_configuration(name):
    params = params_of(name)
    E = MatrixExponential.from_params(params)
    got = E(np.array(TIMES))
    for t, g in zip(TIMES, got):
        want = mp_expm(params, t)
        # normwise: entries relative to max(1, max |e^{At}|)
        assert relative_error(g, want) <= 2e-14, (name, t, relative_error(g, want))


@pytest.mark.parametrize("name", ["triple", "near_triple_1e-6", "double", "near_double_complex", "table_a"])
def test_scalar_and_vectorised_w_agree(name):
    E = MatrixExponential.from_params(params_of(name))
    t = np.concatenate([np.array(TIMES), np.linspace(0, 12, 97)])
    w0, w1, w2 = E.w(t)
    for i, ti in enumerate(t):
        s0, s1, s2 = E.w_scalar(float(ti))
        assert_close([s0, s1, s2], [w0[i], w1[i], w2[i]], rtol=1e-15, atol=1e-16, what=f"w at t={ti}")


def test_w_is_continuous_across_the_series_threshold():
    # the series is used where (r-α)²t² + |β²|t² ≤ 1; probe just both sides of it
    params = params_of("near_double_real")
    E = MatrixExponential.from_params(params)
    t_star = 1.0 / np.sqrt((E.r - E.alpha) ** 2 + abs(E.beta2))
    t = np.array([t_star * (1 - 1e-12), t_star * (1 + 1e-12)])
    got = E(t)
    for ti, g in zip(t, got):
        assert relative_error(g, mp_expm(params, float(ti))) <= 1e-15


def test_eigenvector_formula_fails_where_the_closed_form_does_not():
    """The hazard the closed form avoids: V diag(e^{λt}) V⁻¹ at the triple root."""
    params = params_of("triple")
    A = np.array([[0, 0, -1.0], [1, 0, -3.0], [0, 1, -3.0]])
    lam, V = np.linalg.eig(A)
    naive = (V @ np.diag(np.exp(lam * 2.0)) @ np.linalg.inv(V)).real
    want = mp_expm(params, 2.0)
    assert relative_error(naive, want) > 1e-8  # the eigenvector matrix is (nearly) singular
    assert relative_error(MatrixExponential.from_params(params)(2.0), want) <= 1e-15


def test_expm_is_a_semigroup_and_solves_x_prime_equals_a_x():
    params = params_of("table_a")
    E = MatrixExponential.from_params(params)
    A = np.array([[0, 0, -4.0], [1, 0, -3.0], [0, 1, -6.4]])
    assert_close(E(0.7) @ E(1.1), E(1.8), rtol=1e-14, atol=1e-15, what="e^{0.7A} e^{1.1A}")
    h = 1e-6
    deriv = (E(1.0 + h) - E(1.0 - h)) / (2 * h)
    assert_close(deriv, A @ E(1.0), rtol=1e-8, atol=1e-8, what="d/dt e^{At}")


def test_slip_equilibrium_is_exact_and_the_flow_is_affine_around_it():
    params = Parameters(k_p=3, k_i=4, k_v="6.4", f_c="0.75")
    E = MatrixExponential.from_params(params)
    for d in (1, -1):
        star = slip_equilibrium(0.75, d)
        A = np.array([[0, 0, -4.0], [1, 0, -3.0], [0, 1, -6.4]])
        b = np.array([0, 0, 0.75])
        assert np.array_equal(A @ star - d * b, np.zeros(3))
        assert np.array_equal(slip_flow(E, 0.75, star, np.array([0.0, 3.0]), d), np.array([star, star]))
        x0 = np.array([1.0, -2.0, 0.5])
        t = np.array([0.0, 0.4, 3.0])
        want = [star + mp_expm(params, ti) @ (x0 - star) for ti in t]
        assert_close(slip_flow(E, 0.75, x0, t, d), want, rtol=1e-14, atol=1e-15, what="slip flow")


def test_slip_flow_rejects_a_direction_other_than_plus_or_minus_one():
    E = MatrixExponential.from_params(params_of("table_a"))
    with pytest.raises(SimulationError, match=r"slip direction must be \+1 or -1; got 0"):
        slip_flow(E, 1.0, [0, 0, 0], [1.0], 0)


def test_stick_flow_ramps_phi_at_rate_sigma():
    got = stick_flow([2.0, -0.5, 0.0], np.array([0.0, 0.25, 1.0]))
    assert np.array_equal(got, np.array([[2.0, -0.5, 0.0], [2.0, 0.0, 0.0], [2.0, 1.5, 0.0]]))


def test_P_is_a_lyapunov_matrix_of_A_exactly():
    """AᵀP + PA = -c e₃e₃ᵀ (the identity behind eq. dVdt), in exact rationals."""
    for name in ("table_a", "table_b", "triple", "stiff_complex"):
        p = params_of(name)
        A = [[0, 0, -p.k_i], [1, 0, -p.k_p], [0, 1, -p.k_v]]
        P = [[p.k_v / p.k_i, 0, -1], [0, 1, 0], [-1, 0, p.k_p]]
        M = [[sum(A[k][i] * P[k][j] + P[i][k] * A[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
        want = [[0, 0, 0], [0, 0, 0], [0, 0, -p.c]]
        assert M == want


def test_slip_bounds_are_valid_and_tight():
    p = params_of("table_a")
    bounds = SlipBounds.from_params(p)
    P = np.array([[6.4 / 4, 0, -1], [0, 1, 0], [-1, 0, 3.0]])
    A = np.array([[0, 0, -4.0], [1, 0, -3.0], [0, 1, -6.4]])
    rng = np.random.default_rng(3)
    ys = rng.normal(size=(2000, 3))
    norms = np.sqrt(np.einsum("ni,ij,nj->n", ys, P, ys))
    for j in range(6):
        g = np.linalg.matrix_power(A, j).T @ np.array([0, 0, 1.0])
        ratio = np.abs(ys @ g) / norms
        assert ratio.max() <= bounds.m[j]
        y_star = np.linalg.solve(P, g)  # the maximiser
        assert abs(y_star @ g) / np.sqrt(y_star @ P @ y_star) >= bounds.m[j] * (1 - 1e-9)


def test_the_P_norm_does_not_increase_along_a_slip():
    p = params_of("table_a")
    E = MatrixExponential.from_params(p)
    P = np.array([[6.4 / 4, 0, -1], [0, 1, 0], [-1, 0, 3.0]])
    ys = E.apply(np.linspace(0, 10, 401), np.array([3.0, -1.0, 2.0]))
    norms = np.einsum("ni,ij,nj->n", ys, P, ys)
    assert np.all(np.diff(norms) <= 1e-14 * norms[0])


def test_scan_table_holds_w_and_its_derivatives():
    p = params_of("table_a")
    table = ScanTable.build(MatrixExponential.from_params(p))
    assert table.values.shape == (5, 129) and table.cells == 128
    assert table.window == pytest.approx(128 * table.dt)
    with mpmath.workdps(DPS):
        A = mpmath.matrix([[0, 0, -4], [1, 0, -3], [0, 1, -mp_q("6.4")]])
        for j in (0, 1, 37, 100, 128):
            tau = mpmath.mpf(j) * mpmath.mpf(table.dt)
            col = mpmath.expm(A * tau) * mpmath.matrix([1, 0, 0])
            want = []
            for k in range(5):
                want.append(float(col[2]))
                col = A * col
            assert_close(table.values[:, j], want, rtol=1e-13, atol=1e-14, what=f"table column {j}")
    assert np.all(table.noise > 0)
