"""Methods as configured objects, and no method returns a silently wrong answer."""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
import pytest

from symbolic_friction import EventDriven, IvpEvents, Moreau, Parameters, Regularized, simulate
from symbolic_friction.errors import SimulationError
from symbolic_friction._simulation import SimulationMethod, Status, configure

P = Parameters.table_i("a")


def test_each_method_is_a_frozen_configuration_with_its_order_declared():
    for cls, knob, order in ((EventDriven, None, math.inf), (Moreau, "h", 1.0), (Regularized, "epsilon", 1.0), (IvpEvents, "rtol", 1.0)):
        m = cls()
        assert isinstance(m, SimulationMethod) and cls.knob == knob and cls.order == order
        with pytest.raises(dataclasses.FrozenInstanceError):
            m.max_events = 3  # type: ignore[misc]
        if knob is not None:
            assert knob in m.options
    assert Moreau(h=1e-2).options["h"] == 1e-2
    with pytest.raises(TypeError):
        Moreau(1e-2)  # keyword-only


def test_a_configured_method_and_its_name_give_the_same_solution():
    a = simulate(P, (0, 1, 0), 5.0, method=Moreau(h=1e-2))
    b = simulate(P, (0, 1, 0), 5.0, method="moreau", h=1e-2)
    c = simulate(P, (0, 1, 0), 5.0, method=Moreau(), h=1e-2)  # options applied to a configured method
    assert np.array_equal(a.z, b.z) and np.array_equal(a.z, c.z) and a.options == b.options
    e = simulate(P, (0, 5, 0), 30.0, method=EventDriven(max_events=3))
    assert e.status == Status.MAX_EVENTS and len(e.events) == 3


@pytest.mark.parametrize(
    "method, options, message",
    [
        ("moreau", {"hh": 1}, r"unknown option\(s\) 'hh' for method 'moreau'; expected some of friction, h, max_steps"),
        ("moreau", {"h": -1}, r"option h \(the step size\) must be finite and > 0; got h = -1"),
        ("nope", {}, r"unknown method 'nope'"),
        (3, {}, r"method must be a name .* or a configured method such as Moreau\(h=1e-3\); got int"),
    ],
)
def test_bad_configurations_are_refused_by_name(method, options, message):
    with pytest.raises(SimulationError, match=message):
        configure(method, options)


# -- never silently wrong ---------------------------------------------------------------
@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: simulate(P, (0, 1e307, 0), 40.0), r"the solution from z0 = \(0, 1e\+307, 0\) leaves the range of float64"),
        (lambda: simulate(P, (0, 5, 0), 40.0, method="regularized", epsilon=1e-300),
         r"option epsilon = 1e-300 is below what float64 can resolve for this state .* use epsilon ≥ 1.11e-12"),
        (lambda: simulate(P, (0, 5, 0), 1.0, method="moreau", h=5.0),
         r"option h = 5 is larger than the horizon t_end = 1: one step would cover it"),
        (lambda: simulate(P, (0, 5, 0), 1.0, method="moreau", h=1e-300),
         r"h = 1e-300 needs 1e\+300 steps to reach t_end = 1, more than max_steps = 10000000"),
        (lambda: simulate(P, (0, 5, 0), 1.0, method="ivp-events", rtol=1e-300),
         r"option rtol = 1e-300 is below what float64 can resolve \(scipy would silently use 2.22e-14\)"),
        (lambda: simulate(P, (0, 5, 0), 1.0, method="regularized", rtol=1e-20), r"option rtol = 1e-20 is below"),
        (lambda: simulate(P, (0, 1e307, 0), 5.0, method="ivp-events"), r"DOP853 integrator failed at t = 0"),
        (lambda: simulate(P, (0, 1e307, 0), 5.0, method="regularized", epsilon=1e300),
         r"the regularized solution leaves the range of float64"),
    ],
)
def test_leaving_the_valid_range_is_an_error_that_names_it(call, message):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises(SimulationError, match=message):
            call()


def test_the_batch_marks_a_trajectory_that_leaves_the_range_of_float64_incomplete():
    from symbolic_friction import simulate_batch

    b = simulate_batch(P, [[0, 1e307, 0], [0, 5, 0]], 30.0, t_eval=[0.0, 30.0])
    assert b.status.tolist() == [Status.NONFINITE, Status.T_END]
    assert b.complete.tolist() == [False, True]
    assert np.isnan(b.z[0, 1:]).all()
