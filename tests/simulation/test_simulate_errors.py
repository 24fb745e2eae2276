"""simulate(): bad input raises SimulationError naming what was wrong."""

from __future__ import annotations

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction.errors import SimulationError
from symbolic_friction._simulation import simulate

P = Parameters.table_i("a")


@pytest.mark.parametrize(
    "z0, message",
    [
        ((np.nan, 0.0, 0.0), r"all components of the initial state z0 must be finite; got \[nan, 0.0, 0.0\]"),
        ((0.0, np.inf, 0.0), r"must be finite; got \[0.0, inf, 0.0\]"),
        ((0.0, 0.0, -np.inf), r"must be finite; got \[0.0, 0.0, -inf\]"),
        ((0.0, 1.0), r"z0 must have shape \(3,\) as \(e_i, s, v\); got shape \(2,\)"),
        ([[0.0, 1.0, 2.0]], r"got shape \(1, 3\)"),
        (("a", "b", "c"), r"z0 must be three numbers \(e_i, s, v\); got \('a', 'b', 'c'\)"),
    ],
)
def test_bad_initial_states(z0, message):
    with pytest.raises(SimulationError, match=message):
        simulate(P, z0, 1.0)


@pytest.mark.parametrize("t_end", [0, 0.0, -1.0, np.nan, np.inf])
def test_horizon_must_be_positive_and_finite(t_end):
    with pytest.raises(SimulationError, match=r"t_end must be finite and > 0; got"):
        simulate(P, (0, 0, 1), t_end)


def test_horizon_must_be_a_number():
    with pytest.raises(SimulationError, match=r"t_end must be a number; got 'soon'"):
        simulate(P, (0, 0, 1), "soon")


def test_unknown_method():
    expected = r"unknown method 'rk4'; expected one of event, ivp-events, moreau, regularized"
    with pytest.raises(SimulationError, match=expected):
        simulate(P, (0, 0, 1), 1.0, method="rk4")


def test_unknown_option_is_named_with_the_accepted_ones():
    with pytest.raises(
        SimulationError, match=r"unknown option\(s\) 'h' for method 'event'; expected some of grid_points, max_events"
    ):
        simulate(P, (0, 0, 1), 1.0, h=0.1)


@pytest.mark.parametrize("value", [0, -3, 2.5, True, "10"])
def test_max_events_must_be_a_positive_integer(value):
    with pytest.raises(SimulationError, match=rf"max_events must be an integer ≥ 1; got {value!r}"):
        simulate(P, (0, 0, 1), 1.0, max_events=value)


@pytest.mark.parametrize("value", [1, 0, 10.0])
def test_grid_points_must_be_an_integer_of_at_least_two(value):
    with pytest.raises(SimulationError, match=rf"grid_points must be an integer ≥ 2; got {value!r}"):
        simulate(P, (0, 0, 1), 1.0, grid_points=value)


@pytest.mark.parametrize(
    "t_eval, message",
    [
        ([], r"t_eval must be a non-empty 1-D sequence of times; got shape \(0,\)"),
        ([[0.0, 1.0]], r"got shape \(1, 2\)"),
        ([0.0, np.nan], r"t_eval must contain only finite times"),
        ([0.0, 2.0], r"t_eval must be nondecreasing within \[0, t_end\] = \[0, 1\]; got range \[0, 2\]"),
        ([-0.5, 0.5], r"got range \[-0.5, 0.5\]"),
        ([0.5, 0.2], r"nondecreasing"),
    ],
)
def test_bad_sample_times(t_eval, message):
    with pytest.raises(SimulationError, match=message):
        simulate(P, (0, 0, 1), 1.0, t_eval=t_eval)


def test_params_must_be_parameters():
    with pytest.raises(SimulationError, match=r"params must be a Parameters instance; got tuple"):
        simulate((3, 4, 6.4, 1), (0, 0, 1), 1.0)


def test_errors_are_value_errors_for_callers_that_do_not_know_the_package():
    with pytest.raises(ValueError):
        simulate(P, (0, 0, 1), -1.0)
