"""Corollary 1's adversary: admissible selections only, an exact rest point, and the Stribeck family under the worst found."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction.errors import ParameterError
from symbolic_friction._crosscheck._iss_search import (
    _BOUNDS,
    FAMILIES,
    WorstFound,
    equilibrium_bound,
    selection,
    worst_found,
)


@pytest.mark.parametrize("family", FAMILIES)
def test_every_selection_is_admissible(family):
    rng = np.random.default_rng(0)
    rho = 0.3
    for _ in range(50):
        theta = np.array([rng.uniform(lo, hi) for lo, hi in _BOUNDS[family]])
        law = selection(family, theta, rho)
        for x in rng.normal(size=(20, 3)) * np.array([1.0, 2.0, 0.5]):
            for state in (tuple(x), (x[0], x[1], 0.0)):
                d, e = law(float(rng.uniform(0, 50)), state)
                assert abs(d) <= rho and abs(e) <= rho


def test_the_rest_point_is_exact():
    assert equilibrium_bound(Parameters.table_i("b"), Fraction(1)) == Fraction(25, 2)
    assert equilibrium_bound(Parameters.table_i("a"), Fraction(1, 10)) == Fraction(1, 40)


def test_a_search_below_a_stribeck_law_is_not_done():
    w = WorstFound(rho=1.0, bound=3.6, law="greedy", initial_state=(0.0, 0.0, 0.0), stribeck={"0.1": 8.22})
    assert not w.covers_stribeck
    assert WorstFound(rho=1.0, bound=12.5, law="x", initial_state=(0.0, 0.0, 0.0), stribeck={"0.1": 8.22}).covers_stribeck


def test_worst_found_covers_the_stribeck_family_in_case_b_at_rho_one():
    # the greedy selection alone stays far below Stribeck here (about 3.1 against 8.2)
    w = worst_found(Parameters.table_i("b"), "1", horizon=60.0, h=1e-2, search_horizon=30.0, search_h=2e-2,
                    maxiter=1, popsize=2, families=("velocity-shaped",), stribeck_velocities=("0.1",))
    assert w.covers_stribeck and w.bound >= w.stribeck["0.1"] > w.candidates["greedy"]
    assert w.candidates["equilibrium"] == 12.5


def test_rho_must_be_positive():
    with pytest.raises(ParameterError, match="rho must be > 0"):
        worst_found(Parameters.table_i("a"), "0")
