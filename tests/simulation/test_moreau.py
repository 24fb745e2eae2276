"""The ``moreau`` method: the implicit step satisfies the inclusion exactly,
stick is exact, output conventions, and its options' errors."""

import math

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction.errors import SimulationError
from symbolic_friction._model.coordinates import system_matrix, z_to_x
from symbolic_friction._simulation import Status, simulate
from symbolic_friction._simulation.moreau import step_grid
from tests.tolerance import assert_close

CASE_A = Parameters.table_i("a")
CASE_B = Parameters.table_i("b")


@pytest.mark.parametrize("params", [CASE_A, CASE_B, Parameters(k_p=3, k_i=1, k_v=3, f_c="0.25")])
@pytest.mark.parametrize("h", [1e-3, 0.05, 0.7])
def test_one_step_satisfies_the_implicit_inclusion(params, h):
    # x1 = x0 + h (A x1 - b λ) with λ ∈ SGN(v1): recover λ from the residual and check it.
    rng = np.random.default_rng(3)
    A = system_matrix(params)
    f_c = float(params.f_c)
    states = rng.normal(scale=2.0, size=(40, 3))
    # a third of the starts at rest near phi = 0 with small s, so that stick steps occur
    k_p, k_i = float(params.k_p), float(params.k_i)
    states[::3, 1] *= 0.01
    states[::3, 0] = -k_p * states[::3, 1] / k_i
    states[::3, 2] = 0.0
    n_stick = 0
    for z0 in states:
        sol = simulate(params, z0, h, method="moreau", h=h)
        x0, x1 = z_to_x(params, sol.z[0]), z_to_x(params, sol.z[-1])
        residual = (x1 - x0) / h - A @ x1
        scale = max(1.0, float(np.max(np.abs(A @ x1))), float(np.max(np.abs(x0))) / h)
        assert abs(residual[0]) <= 1e-12 * scale and abs(residual[1]) <= 1e-12 * scale
        lam = -residual[2] / f_c
        v1 = x1[2]
        if v1 == 0.0:
            n_stick += 1
            assert abs(lam) <= 1.0 + 1e-9 * scale
        else:
            assert abs(lam - math.copysign(1.0, v1)) <= 1e-9 * scale
    assert n_stick > 0


def test_stick_is_exact_and_ends_at_the_closed_form_time():
    # z0 = (0.1, 0.05, 0) in case (a): phi = -0.55, sigma = -0.2, so the stick lasts until
    # phi(t) = -0.55 - 0.2 t = -1, i.e. t = 2.25; meanwhile v = 0 and s = 0.05 exactly.
    h = 1e-3
    sol = simulate(CASE_A, (0.1, 0.05, 0.0), 4.0, method="moreau", h=h)
    stick = sol.t < 2.25 - 2 * h
    assert np.all(sol.z[stick, 2] == 0.0)
    assert np.all(sol.z[stick, 1] == 0.05)
    assert np.all(sol.mode[stick] == 0)
    assert_close(sol.z[stick, 0], 0.1 + 0.05 * sol.t[stick], rtol=1e-12, what="e_i ramp during stick")
    t_exit, before, after = sol.events[0]
    assert (before, after) == (0, -1)
    assert abs(t_exit - 2.25) <= 2 * h


def test_start_in_the_attractor_is_an_equilibrium():
    sol = simulate(CASE_A, (0.2, 0.0, 0.0), 10.0, method="moreau", h=0.01)
    assert sol.status == Status.EQUILIBRIUM
    assert np.all(sol.z == np.array([0.2, 0.0, 0.0]))
    assert sol.t[-1] == 10.0 and sol.events == ()
    te = np.linspace(0, 10, 7)
    sol = simulate(CASE_A, (0.2, 0.0, 0.0), 10.0, method="moreau", h=0.01, t_eval=te)
    assert np.array_equal(sol.t, te) and np.all(sol.z == np.array([0.2, 0.0, 0.0]))


def test_grid_ends_exactly_at_t_end_and_t_eval_interpolates_the_steps():
    assert step_grid(1.0, 0.3) == 4
    assert step_grid(1.0, 0.1) == 10  # no sliver step from 1.0/0.1 = 9.999...
    assert step_grid(0.05, 0.1) == 1
    sol = simulate(CASE_A, (0.0, 1.0, 0.0), 1.0, method="moreau", h=0.3)
    assert np.allclose(sol.t, [0.0, 0.3, 0.6, 0.9, 1.0], rtol=0, atol=1e-15) and sol.t[-1] == 1.0
    grid = simulate(CASE_A, (0.0, 1.0, 0.0), 3.0, method="moreau", h=0.01)
    te = np.array([0.0, 0.005, 0.01, 1.234, 2.999, 3.0])
    dense = simulate(CASE_A, (0.0, 1.0, 0.0), 3.0, method="moreau", h=0.01, t_eval=te)
    assert np.array_equal(dense.t, te)
    for j in range(3):
        assert_close(dense.z[:, j], np.interp(te, grid.t, grid.z[:, j]), rtol=1e-13, what=f"component {j}")
    assert np.array_equal(dense.z[-1], grid.z[-1])


def test_mode_and_events_are_consistent():
    sol = simulate(CASE_A, (0.0, 5.0, 0.0), 40.0, method="moreau", h=1e-3)
    assert len(sol.events) >= 10
    # mode[n] is the mode of the step starting at t[n]; events are where it changes.
    changes = np.flatnonzero(np.diff(sol.mode)) + 1
    assert [float(sol.t[i]) for i in changes] == [te for te, _, _ in sol.events]
    for (te, before, after), i in zip(sol.events, changes):
        assert (sol.mode[i - 1], sol.mode[i]) == (before, after)
    assert np.all(np.sign(sol.z[1:, 2]) == sol.mode[:-1])


def test_converges_to_the_attractor_in_case_b():
    sol = simulate(CASE_B, (0.0, 3.0, 0.0), 150.0, method="moreau", h=1e-2)
    d = sol.distance
    assert d[0] > 1.0 and d[-1] < 1e-3
    # e_i approaches the edge f_c/k_i = 12.5 of the attractor (paper, Section III)
    assert abs(abs(sol.z[-1, 0]) - 12.5) < 0.05


@pytest.mark.parametrize(
    "options, match",
    [
        ({"h": -1e-3}, r"option h \(the step size\) must be finite and > 0; got h = -0\.001"),
        ({"h": 0.0}, r"option h \(the step size\) must be finite and > 0; got h = 0\.0"),
        ({"h": float("nan")}, r"option h .* got h = nan"),
        ({"h": "small"}, r"option h must be a number > 0; got 'small'"),
        ({"friction": "stribeck"}, r"option friction must be None \(Coulomb\) or a FrictionLaw .*; got str"),
        ({"max_steps": 0}, r"option max_steps must be an integer ≥ 1; got 0"),
        ({"h": 1e-6, "max_steps": 1000}, r"h = 1e-06 needs 1000000 steps to reach t_end = 1, more than max_steps = 1000"),
        ({"hh": 1e-3}, r"unknown option\(s\) 'hh' for method 'moreau'; expected some of friction, h, max_steps"),
    ],
)
def test_bad_options(options, match):
    with pytest.raises(SimulationError, match=match):
        simulate(CASE_A, (0.0, 1.0, 0.0), 1.0, method="moreau", **options)
