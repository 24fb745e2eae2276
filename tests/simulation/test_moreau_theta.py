"""The Moreau θ-method: θ = 1 is the implicit Euler step bit for bit, one θ-step satisfies its inclusion,
θ = ½ is second order against the independent reference (and a wrong weight is seen), bad θ is refused."""

import math

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction.errors import SimulationError
from symbolic_friction._model.coordinates import system_matrix, z_to_x
from symbolic_friction._reference import Reference
from symbolic_friction._simulation import Moreau, simulate
from symbolic_friction._simulation import moreau as moreau_module
from symbolic_friction._simulation.friction import InflatedCoulomb
from symbolic_friction._simulation.moreau import step_grid

CASE_A = Parameters.table_i("a")
CASE_B = Parameters.table_i("b")


def implicit_euler(params, z0, t_end, h):
    """The implicit Euler (catching-up) step as the package computed it before the θ-method: step points."""
    k_p, k_i, k_v, f_c = params.as_floats()
    e, s, v = (float(c) for c in z0)
    out = [(e, s, v)]
    n_steps = step_grid(t_end, h)
    for n in range(n_steps):
        t0 = n * h
        t1 = t_end if n == n_steps - 1 else (n + 1) * h
        hn = t1 - t0
        D = 1.0 + hn * (k_v + hn * (k_p + hn * k_i))
        phi = -k_i * e - k_p * s
        sigma = -k_i * s
        r = v + hn * (phi + hn * sigma)
        a = hn * f_c
        w = (r - a) / D if r > a else (r + a) / D if r < -a else 0.0
        s1 = s + hn * w
        e1 = e + hn * s1
        e, s, v = e1, s1, w
        out.append((e, s, v))
    return np.array(out)


@pytest.mark.parametrize("params, z0", [(CASE_A, (0.0, 1.0, 0.0)), (CASE_B, (0.0, 0.0, 3.0)), (CASE_A, (1.0, -2.0, 3.0))])
@pytest.mark.parametrize("h", [0.1, 0.03, 0.007])
def test_theta_one_is_implicit_euler_bit_for_bit(params, z0, h):
    expected = implicit_euler(params, z0, 7.3, h)
    for sol in (simulate(params, z0, 7.3, method="moreau", h=h, theta=1.0),
                simulate(params, z0, 7.3, method="moreau", h=h)):
        assert sol.t.size == expected.shape[0]  # no equilibrium reached on these runs
        assert np.array_equal(sol.z, expected)  # the same floats, not merely close


@pytest.mark.parametrize("params", [CASE_A, CASE_B])
@pytest.mark.parametrize("h", [1e-3, 0.05, 0.7])
def test_one_theta_step_satisfies_its_inclusion(params, h):
    # x1 = x0 + h (θ A x1 + (1-θ) A x0 - b λ) with λ ∈ SGN(v1): recover λ from the residual and check it
    theta = 0.5
    rng = np.random.default_rng(5)
    A = system_matrix(params)
    f_c = float(params.f_c)
    k_p, k_i = float(params.k_p), float(params.k_i)
    states = rng.normal(scale=2.0, size=(40, 3))
    states[::3, 1] *= 0.01
    states[::3, 0] = -k_p * states[::3, 1] / k_i
    states[::3, 2] = 0.0
    n_stick = 0
    for z0 in states:
        sol = simulate(params, z0, h, method="moreau", h=h, theta=theta)
        x0, x1 = z_to_x(params, sol.z[0]), z_to_x(params, sol.z[-1])
        smooth = theta * (A @ x1) + (1 - theta) * (A @ x0)
        residual = (x1 - x0) / h - smooth
        scale = max(1.0, float(np.max(np.abs(A @ x1))), float(np.max(np.abs(A @ x0))), float(np.max(np.abs(x0))) / h)
        assert abs(residual[0]) <= 1e-12 * scale and abs(residual[1]) <= 1e-12 * scale
        lam = -residual[2] / f_c
        if x1[2] == 0.0:
            n_stick += 1
            assert abs(lam) <= 1.0 + 1e-9 * scale
        else:
            assert abs(lam - math.copysign(1.0, x1[2])) <= 1e-9 * scale
    assert n_stick > 0


T_END = 10.0
TIMES = np.linspace(0.0, T_END, 101)
_REF: dict = {}


def _errors(hs, theta):
    if not _REF:
        ref = Reference(CASE_A, (0.0, 1.0, 0.0), T_END, dps=40)
        _REF["z"] = np.array(ref.sample(TIMES)[0], dtype=float)
        _REF["sticks"] = len(ref.stick_starts())
    errs = []
    for h in hs:
        sol = simulate(CASE_A, (0.0, 1.0, 0.0), T_END, method="moreau", h=h, theta=theta, t_eval=TIMES)
        errs.append(float(np.max(np.abs(sol.z - _REF["z"]))))
    return errs


def _slope(hs, errs):
    return float(np.polyfit(np.log(hs), np.log(errs), 1)[0])


HS = (0.02, 0.01, 0.005, 0.0025)


def test_theta_half_is_second_order_through_stick_slip():
    errs = _errors(HS, 0.5)
    assert _REF["sticks"] >= 2  # the stick–slip events are inside the measured window
    assert 1.9 <= _slope(HS, errs) <= 2.1, errs  # measured 2.00
    assert errs[1] <= 5e-5  # h = 0.01
    assert 0.85 <= _slope(HS, _errors(HS, 1.0)) <= 1.15  # and θ = 1 stays first order


def test_a_wrong_weight_breaks_the_order(monkeypatch):
    # the order is measured, not assumed: weight the step's end 0.55 instead of θ = 0.5
    monkeypatch.setattr(moreau_module, "_weights", lambda theta, h: (0.55 * h, 0.45 * h))
    assert _slope(HS, _errors(HS, 0.5)) < 1.5


@pytest.mark.parametrize("theta, match", [
    (0.49, r"theta.*\[1/2, 1\].*0\.49"),
    (1.01, r"theta.*\[1/2, 1\].*1\.01"),
    (math.nan, r"theta.*\[1/2, 1\].*nan"),
    ("0.5", "theta must be a number"),
    (True, "theta must be a number"),
])
def test_bad_theta_is_refused(theta, match):
    with pytest.raises(SimulationError, match=match):
        Moreau(theta=theta)
    with pytest.raises(SimulationError, match=match):
        simulate(CASE_A, (0.0, 1.0, 0.0), 1.0, method="moreau", theta=theta)


def test_theta_below_one_takes_coulomb_friction_only():
    with pytest.raises(SimulationError, match=r"theta = 0\.5 takes Coulomb friction only"):
        simulate(CASE_A, (0.0, 1.0, 0.0), 1.0, method="moreau", theta=0.5, friction=InflatedCoulomb("0.1"))
    sol = simulate(CASE_A, (0.0, 1.0, 0.0), 1.0, method="moreau", theta=1.0, friction=InflatedCoulomb("0.1"))
    assert sol.t[-1] == 1.0


def test_accuracy_order_and_equilibrium():
    assert Moreau(theta=0.5).accuracy_order == 2.0 and Moreau().accuracy_order == 1.0
    assert Moreau(theta=0.75).accuracy_order == 1.0
    sol = simulate(CASE_A, (0.2, 0.0, 0.0), 10.0, method="moreau", h=0.01, theta=0.5)
    assert str(sol.status) == "at an equilibrium" and np.all(sol.z == np.array([0.2, 0.0, 0.0]))
