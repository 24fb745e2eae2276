"""The ``ivp-events`` method against the independent reference, its mode table
and its guards."""

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction.errors import SimulationError
from symbolic_friction._simulation import Status, simulate
from symbolic_friction._model.coordinates import x_to_z
from symbolic_friction._reference import Reference, reference_table_mode
from tests.tolerance import relative_error

F_C = 1.0
# (sigma, phi, v) on each row of the appendix table, and the mode it selects
ROWS = {
    "i": ((0.3, 0.0, 0.5), 1),
    "ii": ((-0.3, 1.5, 0.0), 1),
    "iii": ((0.3, 1.0, 0.0), 1),
    "iv": ((0.0, 1.0, 0.0), 0),
    "v": ((-0.3, 1.0, 0.0), 0),
    "vi": ((0.3, 0.2, 0.0), 0),
    "vii": ((0.3, -1.0, 0.0), 0),
    "viii": ((0.0, -1.0, 0.0), 0),
    "ix": ((-0.3, -1.0, 0.0), -1),
    "x": ((0.3, -1.5, 0.0), -1),
    "xi": ((0.3, 0.0, -0.5), -1),
}


@pytest.mark.parametrize("row", ROWS)
def test_the_first_mode_is_the_tables_on_every_row(row):
    x, k = ROWS[row]
    assert reference_table_mode(*x, F_C) == k
    params = Parameters(k_p=2, k_i=1, k_v=3, f_c=F_C)  # σ = -s and φ = -e_i - 2s: exact in floats
    z0 = x_to_z(params, np.array(x))
    sol = simulate(params, z0, 0.5, method="ivp-events", t_eval=[0.0, 0.5])
    assert sol.mode[0] == k


CASES = {
    "a": (Parameters.table_i("a"), (0.0, 5.0, 0.0), 40.0),
    "b": (Parameters.table_i("b"), (0.0, 0.0, 3.0), 30.0),
    "triple root": (Parameters(k_p=3, k_i=1, k_v=3), (0.0, 2.0, 0.0), 30.0),
    "f_c = 1e-6": (Parameters(k_p=5, k_i=2, k_v=4, f_c="1e-6"), (0.0, 1.0, 0.0), 20.0),
}


@pytest.mark.parametrize("name", CASES)
def test_matches_the_reference_at_rtol_1e_10(name):
    params, z0, t_end = CASES[name]
    te = np.linspace(0.0, t_end, 301)
    ref = Reference(params, z0, t_end, dps=40)
    z_ref, mode_ref = ref.sample(te)
    sol = simulate(params, z0, t_end, method="ivp-events", rtol=1e-10, atol=1e-12, t_eval=te)
    scale = max(1.0, float(np.max(np.abs(z0))))
    assert relative_error(sol.z, z_ref, scale=scale) < 1e-8
    events = ref.event_list()
    assert [e[1:] for e in sol.events] == [e[1:] for e in events]
    assert max(abs(a[0] - b[0]) for a, b in zip(sol.events, events)) < 1e-8
    # modes agree away from the switching times
    far = np.min(np.abs(te[:, None] - np.array([e[0] for e in events])[None, :]), axis=1) > 1e-6
    assert np.array_equal(sol.mode[far], np.array(mode_ref)[far])


def test_looser_tolerance_is_less_accurate():
    params, z0, t_end = CASES["a"]
    te = np.linspace(0.0, t_end, 301)
    z_ref = Reference(params, z0, t_end, dps=40).sample(te)[0]
    errors = [
        relative_error(simulate(params, z0, t_end, method="ivp-events", rtol=r, atol=r * 1e-2, t_eval=te).z, z_ref)
        for r in (1e-6, 1e-9, 1e-12)
    ]
    assert errors[0] > errors[1] > errors[2]


def test_equilibrium_and_event_cap():
    params = Parameters.table_i("a")
    sol = simulate(params, (0.2, 0.0, 0.0), 5.0, method="ivp-events")
    assert sol.status == Status.EQUILIBRIUM and np.all(sol.z == [0.2, 0.0, 0.0]) and sol.t[-1] == 5.0
    sol = simulate(params, (0.0, 5.0, 0.0), 40.0, method="ivp-events", max_events=3)
    assert sol.status == Status.MAX_EVENTS and len(sol.events) == 3
    te = np.linspace(0, 40, 401)
    sol = simulate(params, (0.0, 5.0, 0.0), 40.0, method="ivp-events", max_events=3, t_eval=te)
    assert sol.t[-1] <= sol.events[-1][0] and np.array_equal(sol.t, te[: sol.t.size])


def test_samples_at_switching_times_take_the_new_mode():
    params, z0, t_end = CASES["a"]
    first = simulate(params, z0, t_end, method="ivp-events", rtol=1e-10, atol=1e-12)
    te = np.array(sorted({0.0, t_end, *(e[0] for e in first.events)}))
    sol = simulate(params, z0, t_end, method="ivp-events", rtol=1e-10, atol=1e-12, t_eval=te)
    for t_e, _, after in first.events:
        assert sol.mode[np.searchsorted(te, t_e)] == after


@pytest.mark.parametrize(
    "options, match",
    [
        ({"rtol": -1.0}, r"option rtol must be finite and > 0; got rtol = -1\.0"),
        ({"atol": "tiny"}, r"option atol must be a number > 0; got 'tiny'"),
        ({"integrator": "Euler"}, r"option integrator must be one of 'DOP853', 'RK45', 'Radau', 'BDF', 'LSODA'; got 'Euler'"),
        ({"max_events": 0}, r"option max_events must be an integer ≥ 1; got 0"),
        ({"max_events": 2.5}, r"option max_events must be an integer ≥ 1; got 2\.5"),
    ],
)
def test_bad_options(options, match):
    with pytest.raises(SimulationError, match=match):
        simulate(Parameters.table_i("a"), (0.0, 1.0, 0.0), 1.0, method="ivp-events", **options)


def test_integrator_failure_is_reported(monkeypatch):
    import types

    import scipy.integrate

    def failing(*args, **kwargs):
        return types.SimpleNamespace(status=-1, t=np.array([0.0, 0.5]), message="step size too small")

    monkeypatch.setattr(scipy.integrate, "solve_ivp", failing)
    with pytest.raises(SimulationError, match=r"the DOP853 integrator failed at t = 0\.5: step size too small"):
        simulate(Parameters.table_i("a"), (0.0, 1.0, 0.0), 1.0, method="ivp-events")


def test_an_explicit_integrator_is_refused_on_stiff_gains_with_the_reason():
    from fractions import Fraction as F

    from symbolic_friction import Parameters
    from symbolic_friction.errors import SimulationError
    from symbolic_friction._simulation import IvpEvents, simulate

    # (s + 1e8)(s² + 0.2 s + 1): spectral radius 1e8, 2e9 over t_end = 20
    stiff = Parameters(k_v=F(10**8) + F(1, 5), k_p=F(2 * 10**7) + 1, k_i=F(10**8))
    with pytest.raises(SimulationError, match=r"stiff gains for the explicit integrator DOP853.*Radau"):
        simulate(stiff, (0.0, 1.0, 0.0), 20.0, method=IvpEvents())
    # an implicit one is not refused (a short horizon keeps the run cheap)
    sol = simulate(stiff, (0.0, 1.0, 0.0), 1e-3, method=IvpEvents(integrator="Radau"))
    assert sol.complete
