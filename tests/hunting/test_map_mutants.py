"""The hunting map's derivative is the derivative of the map (implicit differentiation against central differences)."""

from __future__ import annotations

import dataclasses
from fractions import Fraction as F

import pytest

from symbolic_friction import Parameters
from symbolic_friction._hunting import HuntingMap


@pytest.mark.parametrize("params, sigma", [
    (dataclasses.replace(Parameters.table_i("a"), f_s=F(6, 5)), 0.105),
    (dataclasses.replace(Parameters.table_i("a"), f_s=F(6, 5)), 0.2),
    (dataclasses.replace(Parameters.table_i("a"), f_c=F(2), f_s=F(12, 5)), 0.3),
])
def test_the_derivative_is_the_maps(params, sigma):
    P = HuntingMap(params)
    h = 1e-6 * sigma
    numeric = (P(sigma + h) - P(sigma - h)) / (2 * h)
    exact = P.derivative(sigma)
    assert abs(exact - numeric) <= 1e-5 * max(1.0, abs(numeric)), (exact, numeric)
