"""Corollary 1's empirical ISS gain."""

from __future__ import annotations

import pytest

from symbolic_friction.errors import ParameterError
from symbolic_friction import Parameters
from symbolic_friction._crosscheck import iss_gain


def test_iss_gain_grows_with_rho_and_vanishes_at_zero():
    p = Parameters.table_i("a")
    est = iss_gain(p, ("0", "0.01", "0.3"), laws=("greedy",), horizon=30.0, h=1e-2)
    g = est.gamma_from_attractor["greedy"]
    assert g[0] == 0.0  # from 𝒜 with the paper's law nothing moves
    assert 0 < g[1] < g[2]
    assert est.rows()[0][0] == "greedy" and len(est.rows()) == 3


def test_iss_stribeck_hunts_for_large_rho():
    p = Parameters.table_i("a")
    est = iss_gain(p, ("1",), laws=("stribeck",), horizon=60.0, h=1e-2)
    assert est.hunting["stribeck"][0] > 0  # a persistent stick–slip cycle (f_s = 2 f_c)
    assert 0 < est.gamma["stribeck"][0] < 10


def test_iss_errors():
    p = Parameters.table_i("a")
    with pytest.raises(ParameterError, match="unknown friction law"):
        iss_gain(p, ("0.1",), laws=("coulomb",))
    with pytest.raises(ParameterError, match="rho must be ≥ 0; got rho = -1/10"):
        iss_gain(p, ("-0.1",))
