"""Step and initial responses (``_simulation/response.py``), shaped like python-control's."""

from __future__ import annotations

import sys
from fractions import Fraction

import numpy as np
import pytest

import symbolic_friction
from symbolic_friction import Parameters, Response, initial_response, simulate, step_response
from symbolic_friction.errors import SimulationError

CASE_A = Parameters.table_i("a")


def _derivative_residual(response_at, params: Parameters, *, r: float, d: float, times) -> float:
    """Largest |v' - (u + d - f_c sign v)| at slip instants, ``v'`` by a central difference (eq. basic).

    ``u = -k_i e_i - k_p (y - r) - k_v v`` is read off the response's own states and output, so this
    checks the response against the physical loop, not against the change of coordinates it uses.
    """
    k_p, k_i, k_v, f_c = params.as_floats()
    h = 1e-5
    worst, checked = 0.0, 0
    for t0 in times:
        resp = response_at(np.array([0.0, t0 - h, t0, t0 + h]))
        e_i, s, v = resp.states[:, 2]
        if np.any(resp.solution.mode[1:] == 0) or len(set(resp.solution.mode[1:])) != 1:
            continue  # stick, or an event inside the stencil
        vdot = (resp.states[2, 3] - resp.states[2, 1]) / (2 * h)
        u = -k_i * e_i - k_p * (resp.outputs[2] - r) - k_v * v
        worst = max(worst, abs(vdot - (u + d - f_c * np.sign(v))))
        checked += 1
    assert checked >= min(len(times), 10), f"only {checked} slip instants checked"  # never vacuous
    return worst


def test_shapes_follow_python_control():
    response = step_response(CASE_A, 30)
    assert response.time.shape == (1001,) and response.outputs.shape == (1001,) and response.inputs.shape == (1001,)
    assert response.states.shape == (3, 1001) and response.state_labels == ("e_i", "s", "v")
    np.testing.assert_array_equal(response.states.T[:, 1], response.solution.z[:, 1])  # (3, n_t) = z transposed
    t, y = response
    assert t is response.time and y is response.outputs
    assert repr(response).count("\n") == 0 and len(repr(response)) < 200


def test_reference_step_is_the_loop_of_the_paper():
    response = step_response(CASE_A, 30, amplitude=2)
    assert response.outputs[0] == 0.0 and np.all(response.inputs == 2.0)  # at rest at 0; the setpoint jumps to 2
    assert response.amplitude == 2 and response.input == "reference"
    residual = _derivative_residual(lambda T: step_response(CASE_A, T, amplitude=2), CASE_A, r=2.0, d=0.0,
                                    times=np.linspace(0.1, 20, 25))
    assert residual < 1e-5
    # the same check on a wrong reference fails: it can tell
    assert _derivative_residual(lambda T: step_response(CASE_A, T, amplitude=2), CASE_A, r=1.0, d=0.0,
                                times=[0.5]) > 1


def test_disturbance_step_is_a_force_on_the_mass():
    response = step_response(CASE_A, 30, input="disturbance", amplitude=3)
    assert response.outputs[0] == 0.0 and response.states[0, 0] == 0.0  # at the setpoint, integrator empty
    residual = _derivative_residual(
        lambda T: step_response(CASE_A, T, input="disturbance", amplitude=3), CASE_A, r=0.0, d=3.0,
        times=np.linspace(0.1, 20, 25),
    )
    assert residual < 1e-5
    # the integral absorbs the force: e_i ends within f_c/k_i of d/k_i, the mass at rest near the setpoint
    e_i_end = response.states[0, -1]
    assert abs(e_i_end - 3 / 4) <= 1 / 4 + 1e-9 and abs(response.outputs[-1]) < 0.1


def test_friction_holds_a_small_disturbance_and_signs_are_symmetric():
    held = step_response(CASE_A, 10, input="disturbance", amplitude="0.9")  # |d| < f_c
    assert np.all(held.outputs == 0.0) and len(held.solution.events) == 0
    up, down = step_response(CASE_A, 20), step_response(CASE_A, 20, amplitude=-1)
    np.testing.assert_allclose(down.outputs, -up.outputs, atol=1e-12)
    assert step_response(CASE_A, 20, amplitude="1/3").amplitude == Fraction(1, 3)


def test_initial_response_is_simulate():
    response = initial_response(CASE_A, [0, 1, 2.5], z0=(1, 1, 1))
    sol = simulate(CASE_A, (1, 1, 1), 2.5, t_eval=[0, 1, 2.5])
    np.testing.assert_array_equal(response.states, sol.z.T)
    np.testing.assert_array_equal(response.outputs, sol.z[:, 1])
    assert np.all(response.inputs == 0) and response.input is None and "initial response" in repr(response)


def test_default_horizon_and_bad_input():
    assert step_response(CASE_A).time[-1] == 52.0  # 10/|Re λ| of the slowest root, rounded up
    with pytest.raises(SimulationError, match="input must be one of reference, disturbance; got 'force'"):
        step_response(CASE_A, input="force")
    with pytest.raises(SimulationError, match="the final time T must be finite and > 0; got -1"):
        step_response(CASE_A, -1)
    with pytest.raises(SimulationError, match="T must be a final time or an array of sample times; got 'x'"):
        step_response(CASE_A, "x")
    with pytest.raises(SimulationError, match="T must hold at least one sample time; got an empty array"):
        step_response(CASE_A, [])
    with pytest.raises(SimulationError, match="T must be a final time or an array of sample times"):
        step_response(CASE_A, [0, "x"])
    with pytest.raises(SimulationError, match="nondecreasing, from t ≥ 0 to a final time > 0; got 3 times from 0 to 1"):
        step_response(CASE_A, [0, 2, 1])
    with pytest.raises(SimulationError, match="got 2 times from 0 to nan"):
        step_response(CASE_A, [0, float("nan")])
    with pytest.raises(SimulationError, match="params must be a Parameters instance; got dict"):
        step_response({"k_p": 3})


def test_a_step_response_plots_in_one_line():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.axes import Axes

    ax = symbolic_friction.step_response(Parameters.table_i("a")).plot()
    assert isinstance(ax, Axes) and [line.get_label() for line in ax.get_lines()] == ["position", "reference"]
    plt.close("all")


def test_to_pandas_and_to_xarray():
    response = step_response(CASE_A, [0, 1, 2])
    frame = response.to_pandas()
    assert frame.index.name == "time" and list(frame.columns) == ["input", "output", "e_i", "s", "v", "mode"]
    np.testing.assert_array_equal(frame["s"].to_numpy(), response.states[1])
    assert frame.attrs["input"] == "reference"
    xr = pytest.importorskip("xarray")
    data = response.to_xarray()
    assert isinstance(data, xr.Dataset) and data["output"].dims == ("time",)
    np.testing.assert_array_equal(data["e_i"].to_numpy(), response.states[0])


@pytest.mark.parametrize(("module", "method"), [("pandas", "to_pandas"), ("xarray", "to_xarray")])
def test_a_missing_extra_names_itself(monkeypatch, module, method):
    monkeypatch.setitem(sys.modules, module, None)  # as if not installed
    with pytest.raises(ImportError, match=rf"pip install 'symbolic-friction\[{module}\]'"):
        getattr(step_response(CASE_A, [0, 1]), method)()


def test_response_is_exported():
    assert symbolic_friction.Response is Response and "step_response" in symbolic_friction.__all__
