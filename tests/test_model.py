"""The numerical model functions agree with their exact evaluation and with
the paper's formulas (eqs. CoC, xDot, distFromA, lyapLike, Vhat)."""

import random
from fractions import Fraction as F

import numpy as np
import pytest

from symbolic_friction import TABLE_I, Parameters
from symbolic_friction.model import V, V_hat, V_k, distance_x, dz, in_R, squared_distance_x, x_to_z, z_to_x
from symbolic_friction._model.attractor import distance_z, in_attractor_x
from symbolic_friction._model.coordinates import input_vector, system_matrix
from symbolic_friction._model.lyapunov import lyapunov_matrix
from tests.tolerance import assert_close

P_A = TABLE_I["a"]


def _random_states(rng, n, scale=3):
    return [[F(rng.randint(-40, 40), rng.randint(1, 9)) * scale / 4 for _ in range(3)] for _ in range(n)]


def test_coordinate_change_round_trip_exact():
    rng = random.Random(1)
    for p in TABLE_I.values():
        for z in _random_states(rng, 20):
            zz = np.array(z, dtype=object)
            x = z_to_x(p, zz)
            assert list(x) == [-p.k_i * z[1], -p.k_i * z[0] - p.k_p * z[1], z[2]]
            assert list(x_to_z(p, x)) == z


def test_coordinate_change_float_matches_exact():
    rng = np.random.default_rng(0)
    Z = rng.normal(size=(50, 3)) * 10
    X = z_to_x(P_A, Z)
    assert_close(x_to_z(P_A, X), Z, rtol=1e-14, what="round trip")
    assert_close(X[:, 0], -4 * Z[:, 1], rtol=1e-15)


def test_A_and_b_match_the_paper():
    A = system_matrix(P_A)
    assert A.tolist() == [[0, 0, -4], [1, 0, -3], [0, 1, -6.4]]
    assert input_vector(P_A).tolist() == [0, 0, 1]
    assert lyapunov_matrix(P_A).tolist() == [[1.6, 0, -1], [0, 1, 0], [-1, 0, 3]]


def test_dz_exact_and_float():
    assert dz(F(5, 2), F(1)) == F(3, 2)
    assert dz(F(-5, 2), F(1)) == F(-3, 2)
    assert dz(F(1, 2), F(1)) == 0
    np.testing.assert_array_equal(dz(np.array([-3.0, -1.0, 0.2, 1.0, 4.0]), 1.0), [-2.0, 0.0, 0.0, 0.0, 3.0])


def test_V_closed_form_matches_brute_force_minimum():
    # The closed-form minimiser in V must equal a brute-force minimum over f ∈ f_c·SGN(v).
    rng = random.Random(2)
    for x in _random_states(rng, 200):
        sigma, phi, v = x
        if rng.random() < 0.4:
            v = F(0)
        grid = [F(j, 64) for j in range(-64, 65)] if v == 0 else [F(1) if v > 0 else F(-1)]
        brute = min(
            P_A.k_v / P_A.k_i * sigma**2 - 2 * sigma * v + P_A.k_p * v**2 + (phi - P_A.f_c * f) ** 2 for f in grid
        )
        got = V(P_A, np.array([sigma, phi, v], dtype=object))
        assert got <= brute <= got + F(1, 128) ** 2  # grid spacing 1/64 bounds the gap
        if v != 0 or abs(phi) >= 1 or (phi * 64).denominator == 1:
            assert got == brute  # the minimiser lies on the grid


def test_V_float_matches_exact():
    rng = random.Random(3)
    states = _random_states(rng, 100)
    states += [[F(1), F(1, 2), F(0)], [F(0), F(3), F(0)], [F(0), F(0), F(0)]]
    exact = [float(V(P_A, np.array(s, dtype=object))) for s in states]
    got = V(P_A, np.array(states, dtype=float))
    assert_close(got, exact, rtol=1e-14, what="V")


def test_V_discontinuity_example_of_the_paper():
    # Along (0, 0, ε) with ε → 0+, V → f_c² while V(0) = 0 (text after eq. lyapLikeP).
    eps = np.array([1e-3, 1e-6, 1e-9])
    vals = V(P_A, np.stack([0 * eps, 0 * eps, eps], axis=-1))
    assert_close(vals, [1.0, 1.0, 1.0], rtol=1e-2)
    assert V(P_A, np.array([F(0), F(0), F(0)], dtype=object)) == 0


def test_V_k_pieces():
    x = np.array([F(1), F(3), F(2)], dtype=object)
    q = lambda s, y, v: P_A.k_v / P_A.k_i * s**2 - 2 * s * v + P_A.k_p * v**2 + y**2  # noqa: E731
    assert V_k(P_A, x, 1) == q(1, 2, 2)
    assert V_k(P_A, x, -1) == q(1, 4, 2)
    assert V_k(P_A, x, 0) == q(1, 0, 0) == P_A.k_v / P_A.k_i
    with pytest.raises(ValueError, match="k must be -1, 0 or 1; got 2"):
        V_k(P_A, x, 2)


def test_V_hat_and_R():
    k = (F(1), F(1), F(5), F(40))
    x = np.array([F(-2), F(-3), F(1, 2)], dtype=object)
    assert V_hat(P_A, x, k) == F(1, 2) * 4 + F(1, 2) * 4 + 5 * 2 * F(1, 2) + 20 * F(1, 4)
    assert_close(V_hat(P_A, np.array([[-2.0, -3.0, 0.5]]), k), [float(V_hat(P_A, x, k))], rtol=1e-15)
    assert not in_R(P_A, x)  # v > 0, φ < f_c
    assert in_R(P_A, np.array([F(0), F(2), F(1)], dtype=object))
    assert in_R(P_A, np.array([F(0), F(0), F(0)], dtype=object))  # v = 0 is in R
    np.testing.assert_array_equal(in_R(P_A, np.array([[0, -3.0, 0.5], [0, 2.0, 0.5], [0, 0.5, -1.0], [0, -2.0, -1.0]])), [False, True, False, True])


def test_distances():
    assert squared_distance_x(P_A, np.array([F(1), F(3), F(2)], dtype=object)) == 1 + 4 + 4
    assert_close(distance_x(P_A, np.array([[1.0, 3.0, 2.0]])), [3.0], rtol=1e-15)
    p = Parameters(k_p=3, k_i=4, k_v="6.4", f_c=2)
    assert_close(distance_z(p, np.array([[1.0, 0.0, 0.0], [0.25, 3.0, 4.0]])), [0.5, 5.0], rtol=1e-15)
    with pytest.raises(TypeError, match="use squared_distance_x"):
        distance_x(P_A, np.array([F(1), F(0), F(0)], dtype=object))


def test_attractor_membership():
    assert in_attractor_x(P_A, np.array([F(0), F(1), F(0)], dtype=object))
    assert not in_attractor_x(P_A, np.array([F(0), F(11, 10), F(0)], dtype=object))
    np.testing.assert_array_equal(in_attractor_x(P_A, np.array([[0, 0.5, 0], [0, 0.5, 1e-300]])), [True, False])
