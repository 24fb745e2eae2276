"""The model along trajectories: the closed-form ∫v² against an mpmath quadrature (40 digits), V through the modes."""

from __future__ import annotations

from fractions import Fraction
import math
import mpmath
import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction._crosscheck import Claims
from symbolic_friction._crosscheck._checker import BatchChecker
from symbolic_friction._crosscheck._along import observability_gramian
from symbolic_friction._crosscheck._run import sample_times
from symbolic_friction._model.coordinates import x_to_z
from symbolic_friction._simulation.batch import simulate_batch
from symbolic_friction._model.lyapunov import lyapunov_matrix
from tests.tolerance import assert_close
from tests.crosscheck.helpers import _cert


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

    # Gauss-Legendre rather than mpmath's default tanh-sinh: v² is analytic on [0, τ], so its nodes converge in a
    # quarter of the e^{At} evaluations (0.3 s instead of 0.8-1.3 s a case), to the same 40 digits (the two rules
    # agree to the last digit on all three cases); the error estimate says the reference is that good
    ref, error = mpmath.quad(lambda t: v(t) ** 2, [0, tau / 2, tau], method="gauss-legendre", error=True)
    assert error < mpmath.mpf(10) ** -30 * abs(ref), error
    y_end = mpmath.expm(A * tau) * y0
    ya = np.array([float(q) for q in y0])
    yb = np.array([float(q) for q in y_end])
    got = ya @ W @ ya - yb @ W @ yb
    assert_close(got, float(ref), rtol=1e-12, what="∫ v² by the Gramian")


def test_gramian_solves_the_lyapunov_equation():
    # W is taken as P/c (the paper's identity behind eq. dVdt); it must solve AᵀW + WA = −e₃e₃ᵀ, which
    # the mpmath quadrature above checks independently on trajectories
    from symbolic_friction._model.coordinates import system_matrix

    for p in (Parameters.table_i("a"), Parameters.table_i("b"), Parameters(k_p=3, k_i=1, k_v=3, f_c=2)):
        W, A = observability_gramian(p), system_matrix(p)
        E = np.zeros((3, 3))
        E[2, 2] = 1.0
        assert np.abs(A.T @ W + W @ A + E).max() < 1e-13 * max(1.0, np.abs(W).max())
        assert_close(observability_gramian(p) * float(p.c), lyapunov_matrix(p), rtol=1e-13, what="c W = P")


def test_V_read_through_the_modes_is_the_papers_V():
    # the checker evaluates V through the mode pieces V_k (Claim 1, item 2); at every sample whose
    # velocity sign is unambiguous this must be the closed-form V of eq. (lyapLike)
    from symbolic_friction._crosscheck._along import along
    from symbolic_friction._model.lyapunov import V

    p = Parameters.table_i("a")
    rng = np.random.default_rng(5)
    X0 = rng.normal(size=(40, 3)) * 2
    b = simulate_batch(p, x_to_z(p, X0), 30.0, t_eval=sample_times(30.0, 121))
    a = along(b)
    ch = a.ch
    got = a.V
    want = V(p, ch.x)
    sure = ch.valid & ((ch.kind == 1) | ((ch.kind == 3) & ((ch.piece == 0) | (np.abs(ch.x[..., 2]) > 1e-9))))
    assert np.count_nonzero(sure) > 1000
    assert_close(got[sure], want[sure], rtol=1e-13, what="V through modes vs closed form")
